/// @file
/// The time loop (paper §4.3): N steps of advance() from t = 0 to a, with an observer that sees
/// every step and may stop the run, and the run's statistics for summary.json.
#pragma once

#include <functional>
#include <limits>
#include <string>

#include "slc/evolve/guards.hpp"
#include "slc/evolve/step.hpp"

namespace slc {

/// How a run ended (summary.json "status").
enum class RunStatus {
    ok,           ///< reached t_end
    vanished,     ///< every component shrank away; the run ended at that time
    interrupted,  ///< the observer asked to stop
    error,        ///< a step failed (contour left the domain, velocity not finite): see message
    /// a step broke what the law keeps (VelocityLaw::invariants) even split into sub-steps
    /// (RunOptions::guards): see message
    unstable,
    /// a surface's run with its guards off (SurfaceRunOptions::guards) reached t_end, but a step
    /// broke what the law keeps: message names the first
    broken,
};

/// The summary.json spelling of a status.
const char* to_string(RunStatus status);

/// A part a step split off thinner than the finest cell (RunTotals::thin_split): the time at the
/// end of the step (NaN if none did), its thickness d·(area or volume)/(length or area), a disc's
/// or ball's radius, the cell's width, and the part's centre (x, y or x, y, z).
struct ThinSplit {
    double at = std::numeric_limits<double>::quiet_NaN();
    double thickness = 0.0;
    double cell = 0.0;
    std::vector<double> near;
};

/// What every run reports, of curves or of surfaces: how and where it ended, and what it cost.
struct RunTotals {
    double t = 0.0;                    ///< the time reached
    int steps_done = 0;                ///< steps completed, N when status is ok
    RunStatus status = RunStatus::ok;  ///< how the run ended
    std::string message;               ///< why, when status is error or unstable
    std::size_t g_evals = 0;           ///< every G evaluation of the run
    double wall_s = 0.0;               ///< the time loop alone
    double cpu_s = 0.0;                ///< process CPU seconds of the time loop (all threads)
    /// Steps the guards split into sub-steps (the options' guards), and the most sub-steps one
    /// step took (1 when none was split).
    int split_steps = 0;
    int most_substeps = 1;  ///< (see split_steps)
    /// The most times a step's domain was doubled (the options' max_domain_doublings), and the
    /// time at the start of the first step that doubled it (NaN if none did).
    int domain_doublings = 0;
    double domain_grown_at = std::numeric_limits<double>::quiet_NaN();  ///< (see domain_doublings)
    /// The edge of the finest cell the steps' contours used, thin cells included (0 before a
    /// step), the time at the end of the first step that used it, and the centre of one such
    /// cell there (x, y or x, y, z): where the shape needed the most resolution.
    double finest_cell = 0.0;
    double finest_t = std::numeric_limits<double>::quiet_NaN();  ///< (see finest_cell)
    std::vector<double> finest_at;                               ///< (see finest_cell)
    /// The time at the end of the first step whose contours left cells that bend whole, thin
    /// cells having reached their budget (contouring::thin_cell_budget); NaN if none.
    double thin_budget_at = std::numeric_limits<double>::quiet_NaN();
    /// The levels of thin cells each step of the run starts from: the options' own, or fewer or
    /// more where the start of a user's shape needed them to keep it (RunOptions::check_start,
    /// surface_as_read); −1 when the run did not say (a resume takes the options'). A step
    /// takes more where its contours tear a part (deeper_at).
    int thin_depth = -1;
    /// The most levels of thin cells a step took (deeper_at), each step starting from
    /// thin_depth; −1 when none went deeper.
    int deepest_thin_depth = -1;
    /// The steps that took deeper thin cells than thin_depth (deeper_at).
    int deeper_steps = 0;
    /// The time at the start of the first step that changed the topology where the contours may
    /// have torn a part thinner than they resolve, and was taken again with deeper thin cells
    /// (deepest_thin_depth), and what that step did: a part split off, and where, or the
    /// invariant it broke; NaN and empty when no step did.
    double deeper_at = std::numeric_limits<double>::quiet_NaN();
    std::string deeper_why;  ///< (see deeper_at)
    /// The time at the start of the first step whose deeper thin cells made holes or handles
    /// that neither its start nor the depth in hand had (the gap narrowing to nothing where
    /// parts meet), and which kept the deepest depth from the one in hand down that added no
    /// part, hole or handle (the least such depth of the run: shallowest_thin_depth), and what
    /// the depths gave; NaN and empty when no step did. shallower_substeps counts the sub-steps
    /// that kept such a depth.
    double shallower_at = std::numeric_limits<double>::quiet_NaN();
    std::string shallower_why;                                    ///< (see shallower_at)
    int shallowest_thin_depth = std::numeric_limits<int>::max();  ///< (see shallower_at)
    int shallower_substeps = 0;                                   ///< (see shallower_at)
    /// With no thin cells asked (thin_depth 0, the paper's uniform trees): the first step that
    /// split off a part thinner than the finest cell, which the contours may have torn; noted,
    /// as the paper's method at that depth gives it (a user's default thin cells take such a
    /// step again deeper, deeper_at, or end the run unstable).
    ThinSplit thin_split;
    /// With the guards off (RunOptions::guards, SurfaceRunOptions::guards): where and how the
    /// run first broke what its law keeps, as in the message of an unstable run; empty while it
    /// has not.
    std::string broken;
};

/// The time interval, the number of steps and the parameters of every step.
struct RunOptions {
    double t_start = 0.0;  ///< the initial curves' time
    double t_end = 1.0;    ///< a, the final time
    int steps = 40;        ///< N; k = (t_end − t_start) / N
    StepOptions step;      ///< K, P, ε, L, M, E, S, ... of each step
    /// How many times the domain may double about its centre (each doubling adds a level to K, so
    /// the finest cell stays the same) when the curves come near its edge. 0, the default, keeps
    /// the domain fixed, as the paper's experiments do: a contour reaching its edge ends the run
    /// with an error. `slc run --initial` allows 6 (a domain up to 64 times as wide).
    int max_domain_doublings = 0;
    /// Before the first step, contour the curves at rest and refuse (NumericalFailure, naming the
    /// place) a start whose contour has other components or holes than the curves, or leaves a
    /// vertex farther than a finest cell from it: a part thinner than the contours resolve.
    /// `slc run --initial` (default_run_options) checks; a named problem does not.
    bool check_start = false;
    /// Check every step against the law's invariants (evolve/guards.hpp): a sub-step that breaks
    /// them is taken again in two halves, down to 1/2^max_substep_halvings of the step, the
    /// halves that keep them kept (the N steps the observer sees stay N), and a run that still
    /// breaks them ends with status unstable. 8: a polygon's corners under curvature flow need
    /// steps of about 1/32 of the default's at first, and a few sub-steps that fine cost little.
    bool guards = true;
    int max_substep_halvings = 8;  ///< see guards
    /// End the run, status ok, once it has at most this many components (0: run to t_end): a
    /// coarsening run "until 10 particles are left". The components are the outer curves (a hole
    /// is not a particle); a surface's are its connected components
    /// (SurfaceRunOptions::stop_components).
    std::size_t stop_components = 0;
    /// With guards, under a law with an area rate (curvature flow): the steps' area changes,
    /// summed, may miss the law's by at most this fraction of the area at the start
    /// (RunResult::area_lag); a step that takes the run beyond it is split into sub-steps like
    /// one that breaks an invariant, and the run ends unstable when no split keeps it within.
    /// 0.05 for the paper's problems; a user's curves take 0.01 (default_run_options).
    double area_drift = 0.05;
    /// With guards, under a law with an area rate: the summed area changes may also miss the
    /// law's by at most this fraction of the change the law has made so far
    /// (RunResult::area_law_change), beyond one step's tolerance of the contours; the steps
    /// that take the run beyond it are split into sub-steps as for area_drift. 0: not checked
    /// (the paper's problems); a user's curves take 0.02 (default_run_options), so that a run
    /// that ends ok keeps dA/dt = −2π a curve to 2% (a coarse star's first steps miss it by 3%).
    double area_rate_drift = 0.0;
    /// With guards, under a law with an area rate: a step whose own lag exceeds this many times
    /// its even share of what is left of area_drift's budget (the budget left × k / (t_end − t),
    /// plus ε L) is taken again in finer sub-steps, as long as each halving takes its lag down
    /// by a quarter; the finest that did is kept. So the early steps of a sharp start (a thin
    /// ellipse's tips, where the flow is fastest) do not spend the budget the later ones need.
    /// 0: not checked (the paper's problems take the paper's steps); a user's curves take 0.5
    /// (default_run_options).
    double area_step_share = 0.0;
};

struct RunResult;

/// What the observer sees after each step.
struct StepReport {
    int step = 0;                       ///< 1..N
    int steps = 0;                      ///< N
    double t = 0.0;                     ///< time reached
    const Interface* curves = nullptr;  ///< Γ(t)
    const StepStats* stats = nullptr;   ///< what the step cost
    double wall_s = 0.0;                ///< seconds of the time loop so far
    double step_cpu_s = 0.0;            ///< process CPU seconds of this step alone (all threads)
    /// The run so far (Γ, t, steps done, counters, clocks): what resume() continues from.
    const RunResult* run = nullptr;
};

/// Called after every step; returning false stops the run (status interrupted).
using Observer = std::function<bool(const StepReport&)>;

/// How a run ended and what it cost.
struct RunResult : RunTotals {
    Interface curves;                   ///< Γ at the end (empty when vanished)
    std::size_t vertices_produced = 0;  ///< every vertex every contour of the run produced
    /// The area StepOptions::area_correction gave back over the run, summed with signs.
    double area_corrected = 0.0;
    /// For a law with an area rate (curvature flow) or a rigid motion: the area at the start of
    /// the run (GuardBudget::start_area), and, with a rate, the sum over its steps of the area
    /// change minus the law's (area_change_expected), which the guards keep within
    /// GuardBudget::run_lag_fraction of the start's area.
    double start_area = 0.0;
    double area_lag = 0.0;  ///< (see start_area)
    /// With a rate: the area change the law has made over the run's steps, summed with signs
    /// (RunOptions::area_rate_drift).
    double area_law_change = 0.0;
    /// For a rigid motion: the segments of the run's first contour (0 before it), which the
    /// guards keep the later contours within GuardBudget::rigid_segments_growth of.
    std::size_t rigid_segments = 0;
    /// For a law that shortens the curves (curvature flow, Eq. 13): the least length of the
    /// run's contours so far (0 before the first) and the time it was reached, which the guards
    /// keep the later lengths within GuardBudget::run_length_growth of.
    RunLeast least_length;
};

/// domain doubled about its centre `times` times (0: domain itself).
Box doubled_domain(const Box& domain, int times);

/// The domain of a step from Γ: domain doubled about its centre the fewest times (at most
/// max_doublings) for which Γ's bounding box keeps an eighth of the doubled width from its edge.
/// Returns the number of doublings.
int domain_doublings_for(const Interface& curves, const Box& domain, int max_doublings);

/// Runs initial (valid, inside domain) from t_start to t_end in `steps` steps under law. Each
/// step runs in the domain doubled domain_doublings_for(Γ(t)) times, once more for each time its
/// contour reaches the edge (RunOptions::max_domain_doublings), with K raised by a level per
/// doubling; a step depends only on Γ and t, so resume() still continues bit for bit.
/// Failures inside a step end the run with status error and a message naming the time, as do
/// curves that leave the law's extent (VelocityLaw::extent); throws InvalidInput only for bad
/// options (steps < 1, t_end ≤ t_start, non-finite times) and initial curves outside the law's
/// extent.
RunResult run(const Interface& initial, const VelocityLaw& law, const Box& domain,
              const RunOptions& options, const Observer& observer = {});

/// Continues a run from `from`, the state after from.steps_done of its N steps (as an observer saw
/// it in StepReport::run, or read back from a checkpoint): steps from.steps_done + 1 .. N, with
/// the counters and clocks of `from` carried on. With the same law, domain and options, the
/// final interface is the one of the uninterrupted run, bit for bit: each step depends only on
/// Γ, t and the step index. Throws InvalidInput as run() does, and when from.steps_done is not
/// in [0, N) or from.t is not the time the run reaches after that many steps.
RunResult resume(const RunResult& from, const VelocityLaw& law, const Box& domain,
                 const RunOptions& options, const Observer& observer = {});

}  // namespace slc
