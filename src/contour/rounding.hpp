// ε and η raised to what doubles resolve in a contour's domain (tolerance::rounding_floor), for
// curves and surfaces alike (internal to contour).
#pragma once

#include <fmt/format.h>

#include <algorithm>

#include "slc/core/error.hpp"
#include "slc/core/tolerances.hpp"

namespace slc::contouring {

/// The options (ContourOptions or SurfaceContourOptions) with ε and η resolved and raised to the
/// rounding floor: a given ε below the floor is bad input (refinement would stop short of it
/// with every split rejected, silently), a default ε and any η below it are raised to it, so that
/// what a run reports as its η is the η it used.
template <class Options, class Domain>
Options within_rounding(Options o, const Domain& domain) {
    const double floor = tolerance::rounding_floor(domain);
    if (o.eps && *o.eps < floor) {
        throw InvalidInput(fmt::format(
            "eps {:g} is below what doubles resolve in this domain ({:.2g}, two ulps of its "
            "coordinates up to {:g}): raise eps",
            *o.eps, floor, domain.largest_magnitude()));
    }
    // η's default may follow ε (surfaces): resolved before ε is raised, as the options were given.
    o.eta = std::max(o.resolved_eta(), floor);
    o.eps = std::max(o.resolved_eps(), floor);
    return o;
}

}  // namespace slc::contouring
