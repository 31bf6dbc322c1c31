/// @file
/// The run loop's physical guards (docs/errors.md, "What the guards catch"): after every step,
/// what the law's exact motion keeps (Invariants) is compared with what the step did, within an
/// error budget. A sub-step that breaks it is taken again in halves (time_loop.hpp's
/// guarded_step); a run that still breaks it ends with status unstable.
#pragma once

#include <optional>
#include <string>

#include "slc/contour/contour_options.hpp"  // ShapeTopology
#include "slc/geometry/interface.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/velocity/invariants.hpp"

namespace slc {

/// The error budget of one step's area: max(area_fraction·|A|, eps_lengths·ε·L) for a law that
/// keeps it, max(rate_fraction·|ΔA|, eps_lengths·ε·L) for a law that changes it by ΔA in the step,
/// with A the larger of the areas before and after, L the length before and ε the step's contour
/// tolerance. The paper's experiments change the area of their area-keeping laws by at most 1.9e−3
/// of A in a step (the single vortex, whose filaments thin below a cell), and curvature flow's area
/// falls within a quarter of 2πk per curve.
struct GuardBudget {
    double area_fraction = 1e-2;  ///< of the area a law that keeps it may change by in a step
    /// A law that shortens the curves may lengthen them by at most this fraction in a step
    /// (the chords of a contour grow towards the arcs they cut as it is refined).
    double length_fraction = 1e-2;
    /// A rigid motion's area may drift from start_area by at most this fraction of it over the
    /// run (steps each within area_fraction cannot add up to more); its length may grow by
    /// rigid_run_fraction·k/T in a step of length k of a run of length T, when that is below
    /// length_fraction. The area is judged over the run, not step by step: a contour's chords
    /// take a little area at every step whatever its length (more at P = 0, where the linear
    /// contour's O(h²) stands in for ε), and smaller steps would only take it more often.
    double rigid_run_fraction = 5e-2;
    /// A law with an area rate: the steps' area changes, summed, may miss the law's by at most
    /// this fraction of the area at the start (RunResult::area_lag): steps each within their
    /// quarter, all lagging the same way, cannot add up to a wrong curve.
    double run_lag_fraction = 5e-2;
    /// The same lag may also be at most this fraction of the change the law has made over the
    /// run (RunResult::area_law_change), plus eps_lengths ε L: 0, not checked (the paper's
    /// problems); a user's curves 0.02 (RunOptions::area_rate_drift).
    double run_rate_fraction = 0.0;
    /// A step's own lag may be at most this many times its even share of what is left of
    /// run_lag_fraction's budget, or it is taken again in finer sub-steps while they help
    /// (RunOptions::area_step_share); 0: not checked.
    double step_share = 0.0;
    /// A rigid motion keeps the shape, so its contours need as many segments as its first one
    /// did, to within the tree's alignment: more than this many times as many means the steps
    /// roughen the curves (RunResult::rigid_segments).
    double rigid_segments_growth = 4.0;
    /// A law that shortens the curves: their length may exceed the least the run has reached
    /// by at most this fraction of it (RunResult::least_length). Steps each within
    /// length_fraction can add up to curves roughened at the scale of the cells, which the
    /// exact flow never makes: measured, the arclength module's runs never exceed their least
    /// length, while the embedded module's circle under Eq. 13 beyond its stable k/h² goes 0.97%
    /// over it at S = 2 and 7.7% at S = 3, visibly bumpy.
    double run_length_growth = 5e-3;
    /// T, the length of the run; 0 for no run-wide budget.
    double run_length = 0.0;
    double eps_lengths = 20.0;    ///< the least tolerance, in ε times the length
    double rate_fraction = 0.25;  ///< of the area a law with an area rate should change by
    /// Under a law that shrinks curves at a rate, the curves may vanish in a step once their area
    /// is below |ΔA| plus this, and below this their rate is not checked: π h² for the finest
    /// cell h of the contouring tree, which need not resolve a curve smaller than a cell.
    double resolved_area = 0.0;
    /// The area at the start of the run, for a rigid motion's drift; 0: not checked.
    double start_area = 0.0;
};

/// The least value a quantity has reached over a run (a shortening law's length, a shrinking
/// law's area) and the time it was reached; value 0 before the first.
struct RunLeast {
    double value = 0.0;  ///< the least value
    double t = 0.0;      ///< when it was reached
};

/// Records x, reached at time t, in least. Returns x's growth above the least, as a fraction of
/// it, when x exceeds the least by more than fraction of it plus slack; else nothing.
std::optional<double> growth_above_least(RunLeast& least, double x, double t, double fraction,
                                         double slack);

/// The area change the law's rate gives a step of length k from `before` to `after`, when the
/// guards check it: the law has a rate, no curve appeared or vanished, and the area is resolved.
std::optional<double> area_change_expected(const Invariants& law, const Interface& before,
                                           double area_before, const Interface& after, double k,
                                           const GuardBudget& budget = {});

/// The parts of an enclosed region: its components, each bounded outside by a counterclockwise
/// curve or an outward shell, and its holes, clockwise curves or inward shells (cavities).
struct RegionParts {
    std::size_t parts = 0;  ///< components of the region
    std::size_t holes = 0;  ///< holes or cavities
};
/// The region enclosed by curves (each curve's orientation from its signed area).
RegionParts region_parts(const Interface& curves);
/// The region enclosed by a valid surface (each component's orientation from its volume).
RegionParts region_parts(const Surface& surface);

ShapeTopology shape_topology(const Interface& curves);
ShapeTopology shape_topology(const Surface& surface);
/// "2 components with 1 hole" (curves), "1 component with 3 handles" (a surface: dim = 3).
std::string describe(const ShapeTopology& t, int dim);
/// What a contour of a given shape says when it does not keep its topology: both counts, that a
/// part was thinner than the cells resolve, and `advice` (the settings to raise, as the caller
/// names them); nothing when it is kept.
std::optional<std::string> lost_topology_note(const ShapeTopology& given,
                                              const ShapeTopology& contour, int dim,
                                              const std::string& advice);

/// Why a step from a region with parts `before` to one with `after` cannot be the law's, in one
/// line, or nothing. A region that only grows (Invariants::cannot_vanish) keeps its parts apart
/// or merges them: more parts after a step means a part tore. One that only shrinks
/// (Invariants::cannot_grow) does the same to its holes. The same rule for curves and surfaces.
std::optional<std::string> region_parts_violation(const Invariants& law, RegionParts before,
                                                  RegionParts after);
/// region_parts_violation of a step from `before` to `after` (curves or a surface), whose parts
/// are read only under a law that claims to grow or to shrink the region.
template <class Shape>
std::optional<std::string> shape_parts_violation(const Invariants& law, const Shape& before,
                                                 const Shape& after) {
    if (!law.cannot_vanish && !law.cannot_grow) return std::nullopt;
    return region_parts_violation(law, region_parts(before), region_parts(after));
}

/// Curves' area and length as a step reads them (step_area, step_length).
struct CurveMeasures {
    double area = 0.0;    ///< signed area enclosed
    double length = 0.0;  ///< total length
};

/// Why a step of length k from `before` to `after` breaks the law's invariants, in one line
/// ("the area changed by 85% in one step under a law that keeps it"), or nothing when it keeps
/// them within the budget. m0, m1: their measures; eps: the contour tolerance ε of the step.
std::optional<std::string> invariant_violation(const Invariants& law, const Interface& before,
                                               const CurveMeasures& m0, const Interface& after,
                                               const CurveMeasures& m1, double k, double eps,
                                               const GuardBudget& budget = {});

}  // namespace slc
