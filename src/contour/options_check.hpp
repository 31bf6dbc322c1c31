// The range checks of the contour options that curves and surfaces share (ContourOptions,
// SurfaceContourOptions): written once, so that both dimensions refuse the same settings with
// the same words.
#pragma once

#include <fmt/format.h>

#include <cmath>

#include "slc/core/error.hpp"

namespace slc::contouring {

/// Throws InvalidInput naming the first shared option out of range: K outside 0..max_depth (the
/// deepest level the dimension's tree takes), a negative thin depth, P below 0 other than
/// until_converged, a negative cap on passes, η not positive, ε not positive or below η, a
/// negative or infinite distance slack, γ not positive.
template <class Options>
void check_shared_options(const Options& o, int max_depth) {
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
}

}  // namespace slc::contouring
