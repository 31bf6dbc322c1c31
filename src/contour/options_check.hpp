// The range checks of the contour options (BasicContourOptions<dim>): written once, so that
// both dimensions refuse the same settings with the same words.
#pragma once

#include <fmt/format.h>

#include <cmath>

#include "slc/contour/contour_options.hpp"
#include "slc/core/error.hpp"

namespace slc::contouring {

/// Throws InvalidInput naming the first option out of range: K outside 0..max_depth (the deepest
/// level the dimension's tree takes), a negative thin depth, P below 0 other than
/// until_converged, a negative cap on passes, η not positive, ε not positive or below η, a
/// negative or infinite distance slack, γ not positive, ρ outside [0, 1); or an option of the
/// other dimension set (creases for curves, ρ or the triangle safeguard for surfaces).
template <int dim>
void check_options(const BasicContourOptions<dim>& o, int max_depth) {
    using Options = BasicContourOptions<dim>;
    auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
    if (o.depth < 0 || o.depth > max_depth) {
        throw InvalidInput(
            fmt::format("contour depth K must be between 0 and {}, got {}", max_depth, o.depth));
    }
    if (o.thin_depth < 0) {
        throw InvalidInput(
            fmt::format("thin cells' extra depth must be >= 0, got {}", o.thin_depth));
    }
    if (o.refine_passes < 0 && o.refine_passes != Options::until_converged) {
        throw InvalidInput(
            fmt::format("refinement passes P must be >= 0, got {}", o.refine_passes));
    }
    if (o.max_refine_passes < 0) {
        throw InvalidInput(
            fmt::format("max_refine_passes must be >= 0, got {}", o.max_refine_passes));
    }
    if (o.eta && !positive(*o.eta))
        throw InvalidInput(fmt::format("eta must be positive, got {}", *o.eta));
    if (o.eps && (!positive(*o.eps) || *o.eps < o.resolved_eta())) {
        throw InvalidInput(
            fmt::format("eps must be at least eta = {}, got {}", o.resolved_eta(), *o.eps));
    }
    if (o.distance_slack && !(*o.distance_slack >= 0.0 && std::isfinite(*o.distance_slack))) {
        throw InvalidInput(
            fmt::format("distance slack must be >= 0 and finite, got {}", *o.distance_slack));
    }
    if (!positive(o.gamma))
        throw InvalidInput(fmt::format("gamma must be positive, got {}", o.gamma));
    if (!(o.rho >= 0.0 && o.rho < 1.0))
        throw InvalidInput(fmt::format("rho must be in [0, 1), got {}", o.rho));
    if constexpr (dim == 2) {
        if (o.creases) throw InvalidInput("creases are followed by the contours of surfaces only");
    } else {
        if (o.rho != Options{}.rho || !o.triangle_safeguard || !o.part_bridges) {
            throw InvalidInput(
                "rho, the triangle safeguard and parting bridges apply to the contours of curves "
                "only");
        }
    }
}

}  // namespace slc::contouring
