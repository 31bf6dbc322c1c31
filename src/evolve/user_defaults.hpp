// What the defaults of a user's own curves and of a user's own surface share (internal to
// evolve): the time interval checked, the depth K = 5 with ε by eps_for_depth and η = 1e−10 ℓ at
// the shape's length scale ℓ, thin cells down to default_thin_depth levels beyond K, and a domain
// that may double as the shape grows. The rest (steps,
// refinement, extension) is each dimension's own (default_run_options,
// default_surface_run_options).
#pragma once

#include <fmt/format.h>

#include <cmath>

#include "slc/core/error.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc::detail {

/// Whether law is a normal law whose speed is not one constant (anisotropic, a speed expression
/// in the normal): where its Wulff shape is not convex, its step leaves G loops smaller than a
/// cell at the corners, which thin cells resolve as parts or holes the law forbids.
template <int dim>
bool normal_speed_varies(const BasicVelocityLaw<dim>& law) {
    return law.is_normal_law() && !law.constant_speed();
}

/// RunOptions (dim 2) or SurfaceRunOptions (dim 3) for a shape of length scale ℓ from t_start to
/// t_end in N = steps steps: K = 5, ε = eps_for_depth(dim, 5, ℓ), η = 1e−10 ℓ, up to ten
/// doublings of the domain (a drop 1e−3 across carried round LeVeque's vortex needs eight).
/// Throws InvalidInput unless t_start and t_end are finite with t_end after t_start.
template <int dim, class Options>
Options user_run_options(double t_start, double t_end, double length_scale, int steps) {
    if (!std::isfinite(t_start) || !std::isfinite(t_end) || !(t_end > t_start)) {
        throw InvalidInput(fmt::format("t-end must be finite and after the start time {}, got {}",
                                       t_start, t_end));
    }
    Options o;
    o.t_start = t_start;
    o.t_end = t_end;
    o.steps = steps;
    o.max_domain_doublings = 10;
    o.step.contour.depth = default_depth;
    o.step.contour.eps = eps_for_depth(dim, o.step.contour.depth, length_scale);
    o.step.contour.eta = ContourOptions::default_eta * length_scale;
    o.step.contour.thin_depth = default_thin_depth(dim);
    return o;
}

}  // namespace slc::detail
