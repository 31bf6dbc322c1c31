/// @file
/// Convergence studies of surfaces (paper §4.2, Tables 5–7, in space): a table of runs whose
/// rows refine N, K and ε together (N ← 2N, K ← K + 1, ε ← ε/4: the finest cell halves and ε,
/// a sag, follows its square) and whose columns add passes of adaptive refinement (P = 0, 1,
/// ...), with the observed orders.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "slc/evolve/self_convergence.hpp"
#include "slc/evolve/study.hpp"
#include "slc/evolve/surface_problems.hpp"

namespace slc {

/// One run of a study of surfaces.
struct SurfaceStudyCell {
    int row = 0;                        ///< N, K and ε refined `row` times
    int refine = 0;                     ///< P, the column
    SurfaceRunOptions options;          ///< the run's settings
    RunStatus status = RunStatus::ok;   ///< how the run ended
    std::optional<double> e_inf;        ///< surface_error at the end
    double cpu_s_per_step = 0.0;        ///< process CPU seconds of the time loop / N
    double wall_s = 0.0;                ///< wall seconds of the time loop
    std::size_t triangles = 0;          ///< triangles of the final surface
    std::size_t initial_triangles = 0;  ///< triangles of the initial surface
};

/// The table of a study of surfaces.
using SurfaceStudyResult = BasicStudyResult<SurfaceStudyCell>;

/// The largest |exact(t, x)| over the vertices and triangle centroids of s; nullopt when the
/// problem has no exact solution at t (or s is empty).
std::optional<double> surface_error(const SurfaceProblem& problem, double t, const Surface& s);

/// The options of the run in row `row` and column `refine` of the problem's study: N, K, ε of
/// its plan refined `row` times, P = refine, from 0 to t_end. Throws InvalidInput for a problem
/// without a plan, a row outside 0..4 or P outside 0..4.
SurfaceRunOptions surface_study_cell_options(const SurfaceProblem& problem, int row, int refine);

/// The options of resolution `level` relative to base, refined as the study's rows are: N·2^level
/// steps (rounded down for a negative level), depth K + level, ε/4^level (ε resolved from base,
/// never below η); the rest as in base. Level −1 is the run at half resolution that `slc run
/// --estimate` compares with. Throws InvalidInput when the steps or the depth would fall below 1.
SurfaceRunOptions surface_resolution_options(const SurfaceRunOptions& base, int level);

/// The symmetric distance between two surfaces: the largest exact distance from a vertex or a
/// triangle centroid of either one to the other (a SurfaceDistanceTree of each). 0 when both are
/// empty, +inf when only one is. Cost O((n_a + n_b) log(n_a + n_b)) for n_a and n_b triangles.
double surface_distance(const Surface& a, const Surface& b);

/// The exact signed distance from each vertex of a to b, > 0 outside b (what a run's final.png
/// is coloured by: how far each point of the final surface lies from the initial one, outward
/// positive). b must be a valid surface (prepare_surface). Empty for a without vertices; throws
/// InvalidInput when b is empty. Cost O((N + M) log M) for N vertices and M triangles of b.
std::vector<double> vertex_distances(const Surface& a, const Surface& b);

/// surface_distance between the final surfaces of two runs of the same problem, or +inf when
/// they cannot be compared: they ended with different statuses or at different times, or either
/// ended empty (as final_distance for curves).
double final_distance(const SurfaceRunResult& a, const SurfaceRunResult& b);

/// Called after each run with the finished cell.
using SurfaceStudyObserver = std::function<void(const SurfaceStudyCell&)>;

/// Runs rows × columns cells (rows 1..5, columns 1..5: P = 0..columns − 1) of the problem's
/// plan. Each run starts from the problem's initial surface contoured with the cell's K, P and
/// ε (initial_surface), so that the table measures the whole method at that resolution. Throws
/// InvalidInput for a problem without a plan or an exact solution, or rows or columns out of range.
SurfaceStudyResult surface_study(const SurfaceProblem& problem, int rows, int columns,
                                 const SurfaceStudyObserver& observer = {});

/// One resolution of a self-convergence study of a surface.
using SurfaceResolutionRun = BasicResolutionRun<SurfaceRunOptions, SurfaceRunResult>;
/// What a self-convergence study of a surface found.
using SurfaceSelfConvergenceResult = BasicSelfConvergenceResult<SurfaceResolutionRun>;

/// Called after each run of a self-convergence study of a surface.
using SurfaceSelfConvergenceObserver = std::function<void(const SurfaceResolutionRun&)>;

/// Self-convergence of a surface that has no exact solution (`slc study --initial S.obj`): runs
/// at resolutions r = 0..resolutions − 1 of base (surface_resolution_options: N·2^r, K + r,
/// ε/4^r), coarsest first, each from `initial` as the steps read it at that resolution
/// (surface_as_read, as `slc run --initial` starts), and compares the final surfaces of
/// neighbours (final_distance). A run that ends badly (status error, unstable) is reported like
/// any other, never thrown. Deterministic: the same for any number of threads, CPU seconds
/// aside. Throws InvalidInput for resolutions outside 3..5 and as run() and surface_as_read()
/// do.
SurfaceSelfConvergenceResult surface_self_convergence(
    const Surface& initial, const SurfaceVelocityLaw& law, const Box3& domain,
    const SurfaceRunOptions& base, int resolutions,
    const SurfaceSelfConvergenceObserver& observer = {});

}  // namespace slc
