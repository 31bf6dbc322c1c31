// What the defaults of a user's own curves and of a user's own surface share (internal to
// evolve): the time interval checked, the steps of a flow field, the depth K = 5 with ε by
// eps_for_depth and η = 1e−10 ℓ at the shape's length scale ℓ, thin cells down to
// default_thin_depth levels beyond K, and a domain that may double as the shape grows. The rest
// (other laws' steps, refinement, extension) is each dimension's own (default_run_options,
// default_surface_run_options).
#pragma once

#include <fmt/format.h>

#include <cmath>

#include "slc/core/error.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/velocity/velocity.hpp"
#include "step_common.hpp"

namespace slc::detail {

/// Whether law is a normal law whose speed is not one constant (anisotropic, a speed expression
/// in the normal): where its Wulff shape is not convex, its step leaves G loops smaller than a
/// cell at the corners, which thin cells resolve as parts or holes the law forbids.
template <int dim>
bool normal_speed_varies(const BasicVelocityLaw<dim>& law) {
    return law.is_normal_law() && !law.constant_speed();
}

/// The steps of a user's run under a law that is not stiff: 40 for curves, 20 for a surface
/// (whose step costs seconds).
constexpr int user_steps(int dim) { return dim == 2 ? 40 : 20; }

/// The steps of a user's run of a flow field stepped directly (flows_directly): its step traces
/// the feet to a tenth of ε whatever its length, so each step adds its contour's error and fewer
/// steps add fewer. Curves take 10 (a star turned a full turn: 3.1e−4 of its size from the
/// start in 40 steps, 3.2e−5 in 10, in a quarter of the time), so that a run's history and its
/// guards still see the motion. A surface keeps its 20: fewer would also help a smooth one (a
/// spindle with tips of 23° turned a full turn: −0.27% of its volume and 0.0104 from the start
/// in 20 steps, 10 s; −0.135% and 0.0077 in 10, 5.9 s), but a unit box with a wall 0.03 thick,
/// turned in 10, is refused at t = π, where the contours hold 1, 11 and 34 handles at 2, 4 and 6
/// levels of thin cells along the cavity's chamfered edges beside the wall
/// (docs/notes/thin-gaps.md).
constexpr int flow_field_steps(int dim) { return dim == 2 ? 10 : user_steps(3); }

/// RunOptions (dim 2) or SurfaceRunOptions (dim 3) for a shape of length scale ℓ from t_start to
/// t_end under law: N = flow_field_steps(dim) for a flow field stepped directly, else `steps`
/// (the dimension's own); K = 5, ε = eps_for_depth(dim, 5, ℓ), η = 1e−10 ℓ, up to ten doublings of
/// the domain (a drop 1e−3 across carried round LeVeque's vortex needs eight). Throws InvalidInput
/// unless t_start and t_end are finite with t_end after t_start.
template <int dim, class Options>
Options user_run_options(const BasicVelocityLaw<dim>& law, double t_start, double t_end,
                         double length_scale, int steps) {
    if (!std::isfinite(t_start) || !std::isfinite(t_end) || !(t_end > t_start)) {
        throw InvalidInput(fmt::format("t-end must be finite and after the start time {}, got {}",
                                       t_start, t_end));
    }
    Options o;
    o.t_start = t_start;
    o.t_end = t_end;
    o.steps = flows_directly(law, o.step) ? flow_field_steps(dim) : steps;
    o.max_domain_doublings = 10;
    o.step.contour.depth = default_depth;
    o.step.contour.eps = eps_for_depth(dim, o.step.contour.depth, length_scale);
    o.step.contour.eta = ContourOptions::default_eta * length_scale;
    o.step.contour.thin_depth = default_thin_depth(dim);
    return o;
}

}  // namespace slc::detail
