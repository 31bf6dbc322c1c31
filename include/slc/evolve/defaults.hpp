/// @file
/// The settings slc uses for a user's own curves when none are given (docs/defaults.md measures
/// them law by law): what `slc run --initial` and the Python package take, and what a C++ caller
/// gets from one call. The named problems keep the paper's own settings instead (problems.hpp).
#pragma once

#include <string>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/evolve/problems.hpp"
#include "slc/evolve/run.hpp"

namespace slc {

/// The default domain of curves: the square centred on their bounding box with 1.5 times its
/// larger half-side (half-width 1 for curves at a single point). Throws InvalidInput when there
/// are no points, or the curves span less than tolerance::min_domain_width.
Box default_domain(const std::vector<std::vector<Vec2>>& curves);

/// ℓ, the half-width of the curves' bounding box (its larger side): the length the defaults
/// scale with. Precondition: curves is not empty.
double length_scale(const Interface& curves);

/// The run options for curves (valid, not empty) moved by law from t_start to t_end:
/// - N = 40 steps (10 for a flow field evaluated directly, whose steps each add their
///   contour's error; more for a stiff law, VelocityLaw::stiffness), K = 5 (the finest cell 1/32 of
///   the domain, which doubles, K one level deeper, up to 10 times when the curves near its edge:
///   RunOptions::max_domain_doublings);
/// - lengths relative to the curves' half-width ℓ: ε = 1e−5 ℓ (eps_for_depth, the rule -K
///   follows), η = 1e−10 ℓ, so that a curve scaled by any factor runs alike;
/// - a law known only at the vertices (the curvature laws, with their module's default,
///   arclength, and arcs; a law of vertex velocities): P = 2 passes; a law evaluated directly:
///   refinement until converged; both without the triangle safeguard, so that corners the tree
///   cuts are found again (ContourOptions::triangle_safeguard);
/// - thin cells 6 levels beyond K (default_thin_depth), 2 under a normal law whose speed depends
///   on the normal (whose non-convex Wulff shapes leave G loops smaller than a cell);
/// - the extension: the law itself where it is known off the curve (flow fields, normal laws),
///   the nearest-point extension otherwise (StepOptions::resolved_extension); arcs for the
///   curvature laws and the laws evaluated directly (StepOptions::resolved_arcs);
/// - the guards of a law with an area rate: the run's area within 1% of the start's and 2% of the
///   law's change (RunOptions::area_drift, area_rate_drift), each step within half its share of
///   what is left of the 1% (RunOptions::area_step_share), and the start checked
///   (RunOptions::check_start).
/// Throws InvalidInput for empty curves or t_end not after t_start.
RunOptions default_run_options(const Interface& curves, const VelocityLaw& law, double t_start,
                               double t_end);

/// A user's curves (valid, not empty, inside domain) moved by law from t_start to t_end, as a
/// Problem with the settings of default_run_options (ℓ = length_scale(curves)) and the law's
/// own extension, arcs and area correction; velocity and params name the law in summary.json.
Problem curve_problem(std::string name, const Interface& curves, const Box& domain, double t_start,
                      double t_end, const VelocityLaw& law, std::string velocity,
                      VelocityParams params);

}  // namespace slc
