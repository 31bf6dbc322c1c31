/// @file
/// Exact geometric predicates: the sign of an orientation determinant and segment intersection,
/// decided without rounding error (Shewchuk-style filter, then exact expansion arithmetic), so that
/// topology decisions (crossings, orientation) never depend on rounding.
#pragma once

#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// Sign of cross(b − a, c − a), computed exactly: +1 if a, b, c turn counterclockwise, −1 if
/// clockwise, 0 if collinear. O(1); exact for all finite doubles.
int orientation(Vec2 a, Vec2 b, Vec2 c);

/// True if the closed segments s and t share at least one point (touching and collinear overlap
/// included). Exact.
bool segments_intersect(Segment s, Segment t);

}  // namespace slc
