/// @file
/// The time loop of surfaces (paper §4.3 with d = 3): N steps of advance() on a surface, with an
/// observer that sees every step and may stop the run, the guards of what the law keeps (volume,
/// shape, growth, area), and the run's statistics. The statuses are those of curves (run.hpp).
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "slc/evolve/run.hpp"
#include "slc/evolve/surface_step.hpp"

namespace slc {

/// The time interval, the number of steps and the parameters of every step.
struct SurfaceRunOptions {
    double t_start = 0.0;     ///< the initial surface's time
    double t_end = 1.0;       ///< the final time
    int steps = 20;           ///< N; k = (t_end − t_start) / N
    SurfaceStepOptions step;  ///< K, P, ε, L of each step
    /// Check every step against the law's invariants (surface_invariant_violation): a sub-step
    /// that breaks them is taken again in two halves, down to 1/2^max_substep_halvings of the
    /// step, the halves that keep them kept (guarded_step in time_loop.hpp), and a run that still
    /// breaks them ends with status unstable. Off: every step is taken whole and kept, and the
    /// run goes on to t_end; the steps are still checked (with the volume drift and the area
    /// growth below), and a run that broke what its law keeps ends with status broken, its
    /// message the first break (a coarse run whose sheet tears, measured anyway).
    bool guards = true;
    /// See guards: 4 (curves take 8). A surface's sub-step costs seconds, and its breaks seen so
    /// far are sheets thinner than the contours, which shorter sub-steps do not mend: a model
    /// with ears turned whole in 20 steps is refused after 130 s at 4, and was still in its
    /// first step after 20 minutes at 8.
    int max_substep_halvings = 4;
    /// End the run, status ok, once the surface has at most this many connected components (0:
    /// run to t_end), as RunOptions::stop_components for curves.
    std::size_t stop_components = 0;
    /// With guards, under a law that keeps the volume: the run ends unstable once the volume has
    /// drifted from the start's by more than this fraction (steps each within their budget may
    /// otherwise add up: a sheet thinner than the contours resolve loses volume step after
    /// step).
    double volume_drift = 0.01;
    /// With guards, under a law that shrinks the area (the mean curvature flows): the run ends
    /// unstable once the area is more than this fraction above the least the run has reached
    /// (steps each within their 1% may add up to a roughened surface, as they do for curves).
    double area_growth = 5e-3;
    /// A step whose contour reaches the domain's edge is done again in the domain doubled about
    /// its centre, with K a level deeper (the same finest cell), up to this many times; each
    /// step starts in the domain doubled the fewest times that keep the surface's bounding box
    /// an eighth of the width from its edge. 0: the domain is fixed (a named problem's).
    int max_domain_doublings = 0;
};

struct SurfaceRunResult;

/// What the observer sees after each step.
struct SurfaceStepReport {
    int step = 0;                             ///< 1..N
    int steps = 0;                            ///< N
    double t = 0.0;                           ///< time reached
    const Surface* surface = nullptr;         ///< S(t)
    const SurfaceStepStats* stats = nullptr;  ///< what the step cost (its last sub-step)
    double wall_s = 0.0;                      ///< seconds of the time loop so far
    double step_cpu_s = 0.0;  ///< process CPU seconds of this step alone (all threads)
    const SurfaceRunResult* run = nullptr;  ///< the run so far
};

/// Called after every step; returning false stops the run (status interrupted).
using SurfaceObserver = std::function<bool(const SurfaceStepReport&)>;

/// How a run of a surface ended and what it cost.
struct SurfaceRunResult : RunTotals {
    Surface surface;  ///< S at the end (empty when vanished)
    /// The volume the run started with, which the guard of volume drift compares with.
    double volume_initial = 0.0;
    /// The volume given back by the steps' volume correction (SurfaceStepOptions::
    /// volume_correction), summed over the steps kept.
    double volume_corrected = 0.0;
    /// Under a law that shrinks the area: the least area of the run's surfaces so far (0 before
    /// the first step) and the time it was reached (SurfaceRunOptions::area_growth).
    RunLeast least_area;
    /// With refinement until converged: the steps kept whose new surface's contour stopped with
    /// a midpoint or centroid beyond ε (splits the safeguards refused, as along sharp edges),
    /// and the largest |G| such a contour left (SurfaceContourStats::residual).
    int unconverged_steps = 0;
    double largest_residual = 0.0;  ///< (see unconverged_steps)
};

/// A user's surface as the steps of a run read it: the contour, at the run's K, P, ε and η, of
/// its distance read as curved patches (SurfaceStepOptions::patches), which is what a step of a
/// motion at rest returns. Runs of users' surfaces start from it, as a named problem's start from
/// its own contour: the first step from a coarse polyhedron would otherwise jump to the smooth
/// surface its vertex normals describe (an icosphere of 320 triangles gains 3.4% of its volume),
/// which the guards would take for a broken law. Its refinement follows the creases where the
/// reading is flat (SurfaceContourOptions::creases), so that a polyhedron's start is within ε of
/// it, edges and corners too. Where the contour does not keep the surface as
/// given (its components, handles, and every vertex within a cell at K), a shallower thin depth
/// that keeps it is taken (thin cells following a sharp edge or point can catch it unevenly),
/// else the thin cells go two levels deeper at a time, up to setting_range::thin_depth's most;
/// options' thin_depth is set to the depth that keeps it, for the run to go on with. Throws as
/// advance() does, NumericalFailure naming the part when the deepest does not keep it, and
/// InvalidInput when the contour misses a surface that is not empty (smaller than the contours
/// resolve).
Surface surface_as_read(const Surface& s, const Box3& domain, SurfaceRunOptions& options);

/// The least thickness 3V/A (V the volume, A the area; a sphere's radius) of the components of
/// `after` beyond those of `before`, when `after` has more components; nullopt otherwise.
std::optional<double> thinnest_new_component(const Surface& before, const Surface& after);

/// The cube domain doubled about its centre `times` times.
Box3 doubled_domain(const Box3& domain, int times);

/// The domain of a step from s: domain doubled about its centre the fewest times (at most
/// max_doublings) for which s's bounding box keeps an eighth of the doubled width from its edge.
/// Returns the number of doublings.
int domain_doublings_for(const Surface& s, const Box3& domain, int max_doublings);

/// Why a step of length k from `before` to `after` breaks what the law keeps, in one line, or
/// nothing when it keeps it within the budget: a kept volume may move in a step by at most the
/// larger of 1% of it and 20 ε A (A the area before); a rigid motion keeps the number of
/// components and the genus; a law that cannot split the surface (a smooth flow field) does not
/// raise the number of components; a surface that cannot vanish does not; a law that shrinks
/// area (the mean curvature flows) may grow it in a step by at most the larger of 1% and 20 ε
/// times its square root; under a constant normal speed s the volume changes by that of the
/// offset by d = s k, d (A₀ + A₁)/2 − π χ d³/3 (χ the Euler characteristic), within the larger of
/// 10% of that and 20 ε A, unless the number of components changed. eps: the step's contour
/// tolerance.
std::optional<std::string> surface_invariant_violation(const Invariants& law, const Surface& before,
                                                       const Surface& after, double k, double eps);

/// Runs initial (valid, inside domain) from t_start to t_end in `steps` steps under law.
/// Failures inside a step end the run with status error and a message naming the time; throws
/// InvalidInput only for bad options (steps < 1, t_end ≤ t_start, non-finite times) or an empty
/// initial surface. Deterministic: the same for any thread count.
SurfaceRunResult run(const Surface& initial, const SurfaceVelocityLaw& law, const Box3& domain,
                     const SurfaceRunOptions& options, const SurfaceObserver& observer = {});

/// Continues the run `from` (its surface, t, steps done, counters, clocks and initial volume:
/// a result of run() or resume() stopped after from.steps_done steps, or read back from a
/// checkpoint) to t_end with the same options: the surface at the end is the one the run
/// without a stop gives, bit for bit (a step depends only on the surface and t). Throws
/// InvalidInput when from.steps_done is not below N, from.t is not the time after that many
/// steps, or the surface is empty.
SurfaceRunResult resume(const SurfaceRunResult& from, const SurfaceVelocityLaw& law,
                        const Box3& domain, const SurfaceRunOptions& options,
                        const SurfaceObserver& observer = {});

}  // namespace slc
