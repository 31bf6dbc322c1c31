// The convergence study of surfaces: the runs of its table and their errors.
#include "slc/evolve/surface_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "resolution_study.hpp"
#include "slc/contour/surface_contour.hpp"
#include "slc/core/error.hpp"
#include "slc/distance/surface_distance_tree.hpp"

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
    SurfaceRunOptions first;
    first.t_start = 0.0;
    first.t_end = problem.t_end;
    first.steps = plan.steps;
    first.step.contour.depth = plan.depth;
    first.step.contour.refine_passes = refine;
    first.step.contour.eps = plan.eps;
    return surface_resolution_options(first, row);
}

SurfaceRunOptions surface_resolution_options(const SurfaceRunOptions& base, int level) {
    SurfaceRunOptions o = base;
    o.steps = level >= 0 ? base.steps << level : base.steps >> -level;
    o.step.contour.depth = base.step.contour.depth + level;
    if (o.steps < 1 || o.step.contour.depth < 1) {
        throw InvalidInput(
            fmt::format("resolution {} of N = {}, K = {} needs at least one step and depth 1",
                        level, base.steps, base.step.contour.depth));
    }
    o.step.contour.eps = std::max(base.step.contour.resolved_eps() * std::pow(4.0, -level),
                                  base.step.resolved_eta());
    return o;
}

namespace {

/// The signed distances from points to b (not empty), b's tree built in the cube around both.
std::vector<double> signed_distances_to(std::span<const Vec3> points, const Surface& b) {
    Box3 box = bounding_box(b);
    for (const Vec3& p : points) box = unite(box, Box3{p, p});
    const double half =
        0.5 * std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z, 1e-300});
    const Box3 domain = Box3::cube(box.center(), 1.1 * half);
    const SurfaceDistanceTree tree(b, domain,
                                   {.depth = SurfaceDistanceTree::default_depth(b, domain)});
    return tree.signed_distances(points);
}

/// The largest exact distance from a vertex or centroid of a to b (not empty).
double one_way_distance(const Surface& a, const Surface& b) {
    std::vector<Vec3> points = a.vertices;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Triangle3 t = a.triangle(i);
        points.push_back((t.a + t.b + t.c) / 3.0);
    }
    double d = 0.0;
    for (const double f : signed_distances_to(points, b)) d = std::max(d, std::abs(f));
    return d;
}

}  // namespace

std::vector<double> vertex_distances(const Surface& a, const Surface& b) {
    if (a.vertices.empty()) return {};
    if (b.empty()) throw InvalidInput("vertex_distances: the surface to measure to is empty");
    return signed_distances_to(a.vertices, b);
}

double surface_distance(const Surface& a, const Surface& b) {
    if (a.empty() && b.empty()) return 0.0;
    if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
    return std::max(one_way_distance(a, b), one_way_distance(b, a));
}

double final_distance(const SurfaceRunResult& a, const SurfaceRunResult& b) {
    if (a.status != b.status || a.t != b.t || a.surface.empty() || b.surface.empty())
        return std::numeric_limits<double>::infinity();
    return surface_distance(a.surface, b.surface);
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

SurfaceSelfConvergenceResult surface_self_convergence(
    const Surface& initial, const SurfaceVelocityLaw& law, const Box3& domain,
    const SurfaceRunOptions& base, int resolutions,
    const SurfaceSelfConvergenceObserver& observer) {
    return detail::resolution_study(
        resolutions, [&](int r) { return surface_resolution_options(base, r); },
        [&](const SurfaceRunOptions& o) {
            SurfaceRunOptions used = o;  // with the thin depth the start needs
            const Surface start = surface_as_read(initial, domain, used);
            return run(start, law, domain, used);
        },
        observer);
}

}  // namespace slc
