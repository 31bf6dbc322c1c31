// The cube around a box given by its corners, checked.
#include "slc/core/box3.hpp"

#include <fmt/format.h>

#include "slc/core/error.hpp"
#include "slc/core/tolerances.hpp"

namespace slc {

Box3 cube_around_corners(std::span<const double> six, std::string_view name) {
    if (six.size() != 6) {
        throw InvalidInput(
            fmt::format("{} must be six numbers x0, y0, z0, x1, y1, z1, got {}", name, six.size()));
    }
    const Box3 b{{six[0], six[1], six[2]}, {six[3], six[4], six[5]}};
    if (!is_finite(b.lo) || !is_finite(b.hi) || !(b.extent(0) > 0) || !(b.extent(1) > 0) ||
        !(b.extent(2) > 0)) {
        throw InvalidInput(fmt::format(
            "{} must have x0 < x1, y0 < y1 and z0 < z1, all finite, got ({}, {}, {}, {}, {}, {})",
            name, six[0], six[1], six[2], six[3], six[4], six[5]));
    }
    if (b.largest_magnitude() > tolerance::max_coordinate) {
        throw InvalidInput(
            fmt::format("{} corners must lie within ±{:g}", name, tolerance::max_coordinate));
    }
    return Box3::cube(b.center(), 0.5 * std::max({b.extent(0), b.extent(1), b.extent(2)}));
}

}  // namespace slc
