// The convergence study of surfaces: the runs of its table and their errors.
#include "slc/evolve/surface_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "slc/contour/surface_contour.hpp"
#include "slc/core/error.hpp"

namespace slc {

std::optional<double> surface_error(const SurfaceProblem& problem, double t, const Surface& s) {
    if (!problem.exact || s.empty()) return std::nullopt;
    double e = 0.0;
    auto offer = [&](Vec3 x) {
        const double d = problem.exact(t, x);
        if (std::isnan(d)) return false;
        e = std::max(e, std::abs(d));
        return true;
    };
    for (const Vec3& v : s.vertices)
        if (!offer(v)) return std::nullopt;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const Triangle3 tri = s.triangle(i);
        if (!offer((tri.a + tri.b + tri.c) / 3.0)) return std::nullopt;
    }
    return e;
}

SurfaceRunOptions surface_study_cell_options(const SurfaceProblem& problem, int row, int refine) {
    if (!problem.study)
        throw InvalidInput(fmt::format("problem '{}' has no convergence study", problem.name));
    if (row < 0 || row > 4 || refine < 0 || refine > 4) {
        throw InvalidInput(
            fmt::format("a study cell has row and P in 0..4, got row {} and P {}", row, refine));
    }
    const SurfaceStudyPlan& plan = *problem.study;
    SurfaceRunOptions o;
    o.t_start = 0.0;
    o.t_end = problem.t_end;
    o.steps = plan.steps << row;
    o.step.contour.depth = plan.depth + row;
    o.step.contour.refine_passes = refine;
    o.step.contour.eps = plan.eps * std::pow(4.0, -row);
    return o;
}

SurfaceStudyResult surface_study(const SurfaceProblem& problem, int rows, int columns,
                                 const SurfaceStudyObserver& observer) {
    if (rows < 1 || rows > 5 || columns < 1 || columns > 5) {
        throw InvalidInput(
            fmt::format("a study has 1 to 5 rows and 1 to 5 columns, got {} rows and {} columns",
                        rows, columns));
    }
    if (!problem.exact)
        throw InvalidInput(fmt::format("problem '{}' has no exact solution", problem.name));
    SurfaceStudyResult result{rows, columns, {}};
    for (int row = 0; row < rows; ++row) {
        for (int p = 0; p < columns; ++p) {
            SurfaceStudyCell cell;
            cell.row = row;
            cell.refine = p;
            cell.options = surface_study_cell_options(problem, row, p);
            const Surface initial = initial_surface(problem, cell.options.step.contour);
            const SurfaceRunResult r = run(initial, *problem.law, problem.domain, cell.options);
            cell.status = r.status;
            cell.e_inf =
                r.status == RunStatus::ok ? surface_error(problem, r.t, r.surface) : std::nullopt;
            cell.cpu_s_per_step = r.steps_done > 0 ? r.cpu_s / r.steps_done : 0.0;
            cell.wall_s = r.wall_s;
            cell.triangles = r.surface.size();
            cell.initial_triangles = initial.size();
            if (observer) observer(cell);
            result.cells.push_back(std::move(cell));
        }
    }
    return result;
}

}  // namespace slc
