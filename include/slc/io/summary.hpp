/// @file
/// summary.json of a run (DESIGN §6): the settings it used, how it ended and what it cost; the
/// same keys from `slc run` and from Python's `slc.run(...).summary`.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "slc/evolve/problems.hpp"
#include "slc/evolve/run.hpp"
#include "slc/evolve/surface_problems.hpp"

namespace slc {

/// P as summary.json writes it: the number of passes, or "converged".
std::string refine_name(int passes);

/// The run's name N/S/K/P/ε as the paper writes it ("80/0/6/2/1e-06").
std::string run_name(const RunOptions& options);

/// A surface run's name as summary.json writes it: "N 4, K 5, eps 0.001".
std::string run_name(const SurfaceRunOptions& options);

/// The most memory the process has held so far (resident set, MiB): the check that long runs
/// stay bounded (scripts/memcheck) reads it from summary.json.
double peak_rss_mib();

/// A contour's statistics as `slc contour` writes them into summary.json and Python's contour
/// functions return them: the same key for a field of BasicContourStats in both dimensions
/// (finest_at as a list of coordinates), then the dimension's own (the curves' max_midpoint_value
/// is null unless refinement ran to convergence). Whether a surface's refinement converged is for
/// the caller to add, who knows whether refinement was asked for.
nlohmann::json contour_stats_json(const ContourStats& stats);
nlohmann::json contour_stats_json(const SurfaceContourStats& stats);  ///< (see above)

/// summary.json of a run: problem, run, params (N, K, P, ε, η, ρ, M, E, S, L, domain, the law and
/// its parameters, extension, arcs, area correction, σ, the problem's own parameters), t_end, t,
/// steps, steps_done, status, e_inf (Equation 11 where the problem has an exact solution, else
/// null), area, length, components, segments, wall_s, cpu_s, cpu_s_per_step, threads, g_evals,
/// peak_rss_mib, g_evals_per_vertex; message for an error or an unstable run, substeps
/// (split_steps, most) when the guards split steps, area_corrected when the correction was
/// on, domain_grown when the domain doubled. law: the law the run used, whose defaults resolve the
/// extension and arcs.
nlohmann::json run_summary(const Problem& problem, const RunOptions& options,
                           const RunResult& result, const VelocityLaw& law);

/// summary.json of a run of a surface (`slc run` on a surface, Python's `slc.run` on a
/// Surface): problem, velocity, dimension 3, domain, t_end, params (N, k, K, P, ε, η, threads),
/// status, t, steps, steps_done, triangles, vertices, components, genus, volume, area,
/// volume_initial, area_initial, volume_change, volume_read and volume_read_change (the volume
/// as the steps read the surface, its curved patches included: step_volume), e_inf
/// (surface_error at the end, null where the exact surface is not known), g_evals, split_steps,
/// most_substeps, cpu_s, wall_s; message for an error or an unstable run. initial: the surface
/// the run started from.
nlohmann::json surface_run_summary(const SurfaceProblem& problem, const Surface& initial,
                                   const SurfaceRunOptions& options,
                                   const SurfaceRunResult& result);

/// How the run at half resolution of an error estimate ended, and the distance between its final
/// curves or surface and the run's (+inf when they cannot be compared).
struct CoarseRun {
    RunStatus status = RunStatus::ok;  ///< how it ended
    double t = 0.0;                    ///< the time it reached
    double cpu_s = 0.0;                ///< its CPU seconds
    bool empty = false;                ///< it ended with no curves or surface
    double distance = 0.0;             ///< between its final curves or surface and the run's
};

/// Throws InvalidInput unless a run of N steps at depth K has a run at half resolution (N, K ≥ 2);
/// the message names the option that asked for it (`--estimate`, `estimate`).
void require_half_resolution(int steps, int depth, const std::string& option = "--estimate");

/// summary.json's "error_estimate" (`slc run --estimate`, Python's `run(..., estimate=True)`): the
/// distance between the run's final curves or surface (what: "curves", "surface") and those of
/// the same run at half resolution (named coarse: N/2, K − 1, 4ε, resolution_options(o, −1)),
/// which run_coarse runs unless the run ended with a status other than ok. If the error falls at
/// least as fast as first order, e ≤ d/(2 − 1) = d: the estimate is d itself (a third of it at
/// second order); a note says so, or why there is none.
nlohmann::json estimate_json(const std::string& coarse, RunStatus status,
                             const std::function<CoarseRun()>& run_coarse, const std::string& what);

}  // namespace slc
