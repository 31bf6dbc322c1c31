// The convergence study loop and its observed orders.
#include "slc/evolve/study.hpp"

#include <fmt/format.h>

#include <cmath>

#include "slc/core/error.hpp"
#include "slc/geometry/validate.hpp"

namespace slc {

RunOptions study_cell_options(const Problem& problem, int row, int refine, const RunOptions& base) {
    if (row < 0 || row > 4 || refine < 0 || refine > 4) {
        throw InvalidInput(
            fmt::format("a study cell has row and P in 0..4, got row {} and P {}", row, refine));
    }
    const StudyPlan& plan = problem.study;
    RunOptions o = base;
    o.t_start = 0.0;
    o.t_end = problem.t_end;
    o.steps = plan.steps << row;
    o.step.contour.depth = plan.depth + row;
    o.step.contour.refine_passes = refine;
    o.step.contour.eps = plan.eps * std::pow(10.0, -row);
    o.step.tree_depth = 0;
    o.step.embedded.mesh = default_mesh_size(o.step.contour.depth);
    o.step.embedded.smoothing = plan.smoothing[static_cast<std::size_t>(row)];
    const StepOptions& own = problem.run.step;
    if (!o.step.extension) o.step.extension = own.extension;
    if (!o.step.arcs) o.step.arcs = own.arcs;
    if (!o.step.area_correction) o.step.area_correction = own.area_correction;
    return o;
}

StudyResult study(const Problem& problem, int rows, const RunOptions& base,
                  const StudyObserver& observer) {
    if (rows < 1 || rows > 5)
        throw InvalidInput(fmt::format("rows must be between 1 and 5, got {}", rows));
    const auto law = problem_law(problem, problem.module);
    const Interface initial = prepare_interface(problem.initial, problem.domain).curves;
    StudyResult result{rows, 5, {}};
    for (int row = 0; row < rows; ++row) {
        for (int p = 0; p < 5; ++p) {
            StudyCell cell;
            cell.row = row;
            cell.refine = p;
            cell.options = study_cell_options(problem, row, p, base);
            const RunOptions& o = cell.options;
            RunResult r = run(initial, *law, problem.domain, o);
            if (r.status == RunStatus::unstable && o.guards) {
                // The paper's table has every cell: without the guards the run goes on to its
                // end, and its error is reported beside the break that stopped it.
                cell.stopped = r.message;
                RunOptions off = o;
                off.guards = false;
                r = run(initial, *law, problem.domain, off);
            }
            cell.status = r.status;
            // A run stopped short of its end (error) has no error to compare: the exact
            // solution is known at t_end, and its curves stopped at an earlier time.
            if (r.status == RunStatus::ok || r.status == RunStatus::vanished ||
                r.status == RunStatus::broken)
                cell.e_inf = max_error(problem, r.curves, r.t);
            cell.cpu_s_per_step = r.steps_done > 0 ? r.cpu_s / r.steps_done : 0.0;
            cell.g_evals_per_vertex = r.vertices_produced > 0
                                          ? static_cast<double>(r.g_evals) / r.vertices_produced
                                          : 0.0;
            cell.segments = r.curves.size();
            if (observer) observer(cell);
            result.cells.push_back(std::move(cell));
        }
    }
    return result;
}

}  // namespace slc
