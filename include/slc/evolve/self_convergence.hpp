/// @file
/// Self-convergence of a run that has no exact solution: the same curves and law at R successive
/// resolutions, the distance between the final curves of each pair of neighbours, the observed
/// orders of convergence, and a Richardson estimate of the finest run's error. The paper (§4)
/// judged convergence of its curves without exact solutions graphically, by overlaying runs at
/// successive resolutions; this measures the same thing.
///
/// Resolution r runs base's N·2^r steps at depth K + r with ε/4^r. If run r has error e_r ≈ C·2^−pr
/// then the distance between runs r and r + 1 is d_r ≈ e_r − e_{r+1} = e_{r+1}(2^p − 1), so
/// p ≈ log2(d_r / d_{r+1}) and e_{R−1} ≈ d_{R−2} / (2^p − 1).
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "slc/evolve/run.hpp"

namespace slc {

/// The options of resolution `level` relative to base (level 0 is base itself; −1 is the run at
/// half resolution that `slc run --estimate` compares with):
/// - N·2^level steps (rounded down for a negative level), depth K + level;
/// - ε/4^level, but never below η. The linear contour's error is O(h²) in the cell size h, so
///   one level of K (h halved) divides it by 4; ε, which refinement meets at every midpoint,
///   follows it so that neither the tree nor the refinement dominates the finer runs. The
///   paper's own studies divide ε by 10 per row (Tables 5–7); 4 keeps the spatial and the
///   second-order temporal error in step when N doubles.
/// - η as in base: the root-finding tolerance is far below every ε already (1e−10 against 1e−5
///   of the curves' size by default, and ε/4^4 = ε/256 at the finest of five levels).
/// - the embedded mesh M·2^level (at least 8), so that its spacing follows the cells; L + level
///   when base sets L (0, the default, resolves from K and P at each level).
/// - everything else (P, ρ, S, E, the extension, arcs, σ, domain doublings, times) as in base.
/// Throws InvalidInput when the steps or the depth would fall below 1.
RunOptions resolution_options(const RunOptions& base, int level);

/// The symmetric Hausdorff distance between two interfaces as Eq. (11) measures errors: the
/// largest exact distance (a DistanceTree over the other interface) from a vertex or a segment
/// midpoint of either one to the other. 0 when both are empty; +inf when only one is. Cost
/// O((n_a + n_b) log(n_a + n_b)) for n_a and n_b segments.
double interface_distance(const Interface& a, const Interface& b);

/// interface_distance between the final curves of two runs of the same problem, or +inf when
/// they cannot be compared: they ended with different statuses or at different times, or either
/// ended empty (vanished: the time of vanishing, not the curves, is then what differs).
double final_distance(const RunResult& a, const RunResult& b);

/// One resolution of a self-convergence study, of curves or of surfaces.
template <class Options, class Result>
struct BasicResolutionRun {
    int level = 0;    ///< r = 0..R − 1
    Options options;  ///< the options of resolution r (resolution_options(base, r))
    Result result;    ///< how it ended, its final interface and cost
};
/// One resolution of a self-convergence study of curves.
using ResolutionRun = BasicResolutionRun<RunOptions, RunResult>;

/// The order p that error_estimate assumes is the last observed one, clamped to this range: an
/// order below 1/2 would multiply the distance by more than 2.4, one above 4 (rounding, or two
/// runs that happen to agree) would shrink it below a fifteenth.
constexpr double min_estimate_order = 0.5;
constexpr double max_estimate_order = 4.0;  ///< (see min_estimate_order)

/// The Richardson estimate of the finest run's error.
struct ErrorEstimate {
    double error = 0.0;    ///< d_{R−2} / (2^p − 1)
    double order = 1.0;    ///< p used: the last observed order, clamped
    bool observed = true;  ///< false: no order was observed and p = 1 was assumed
};

/// What a self-convergence study found.
template <class Run>
struct BasicSelfConvergenceResult {
    std::vector<Run> runs;  ///< R runs, coarsest first
    /// R − 1 distances: d_r = final_distance(run r, run r + 1); +inf where they differ in status,
    /// time, or one is empty.
    std::vector<double> distances;
    /// R − 2 observed orders p_r = log2(d_r / d_{r+1}); nullopt where a distance is +inf or 0.
    std::vector<std::optional<double>> orders;
    /// The finest run's error from d_{R−2} and the last observed order; nullopt when d_{R−2} is
    /// +inf. When no order was observed (d_{R−3} infinite), p = 1 (ErrorEstimate::observed false).
    std::optional<ErrorEstimate> estimate;
};
/// What a self-convergence study of curves found.
using SelfConvergenceResult = BasicSelfConvergenceResult<ResolutionRun>;

/// Throws InvalidInput for a number of resolutions outside 3..5: runs are compared in pairs, and
/// two pairs give an order.
void check_resolutions(int resolutions);

/// The observed orders and the estimate of BasicSelfConvergenceResult from its distances (at
/// least one).
void observe_orders(std::span<const double> distances, std::vector<std::optional<double>>& orders,
                    std::optional<ErrorEstimate>& estimate);

/// error_estimate(d, p) = d / (2^p − 1) with p clamped to [min_estimate_order,
/// max_estimate_order]: the error of the finer of two runs that differ by d when the error falls
/// as 2^−p per level.
double error_estimate(double distance, double order);

/// Called after each run with its level, options and result.
using SelfConvergenceObserver = std::function<void(const ResolutionRun&)>;

/// Runs initial (valid, inside domain) under law at resolutions r = 0..resolutions − 1 of base
/// (resolution_options), coarsest first, and compares the final curves of neighbours. A run that
/// fails (status error) is reported like any other, never thrown. Deterministic: the same result
/// for any number of threads, CPU seconds aside. Throws InvalidInput for resolutions outside
/// 3..5, and as run() does for bad options.
SelfConvergenceResult self_convergence(const Interface& initial, const VelocityLaw& law,
                                       const Box& domain, const RunOptions& base, int resolutions,
                                       const SelfConvergenceObserver& observer = {});

}  // namespace slc
