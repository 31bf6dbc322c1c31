/// @file
/// Points as messages name them, "(x, y)" or "(x, y, z)": one formatter for every module and
/// both dimensions.
#pragma once

#include <fmt/format.h>

#include <string>

#include "slc/core/vec2.hpp"
#include "slc/core/vec3.hpp"

namespace slc {

/// Each coordinate in full: the shortest text that reads back as the same double.
inline std::string point_text(Vec2 p) { return fmt::format("({}, {})", p.x, p.y); }
/// (see above)
inline std::string point_text(Vec3 p) { return fmt::format("({}, {}, {})", p.x, p.y, p.z); }
/// Each coordinate to `digits` significant digits.
inline std::string point_text(Vec2 p, int digits) {
    return fmt::format("({:.{}g}, {:.{}g})", p.x, digits, p.y, digits);
}
/// (see above)
inline std::string point_text(Vec3 p, int digits) {
    return fmt::format("({:.{}g}, {:.{}g}, {:.{}g})", p.x, digits, p.y, digits, p.z, digits);
}

}  // namespace slc
