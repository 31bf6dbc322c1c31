/// @file
/// Exact geometric predicates: the sign of an orientation determinant and segment intersection,
/// decided without rounding error (Shewchuk-style filter, then exact expansion arithmetic), so that
/// topology decisions (crossings, orientation) never depend on rounding.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "slc/core/vec2.hpp"
#include "slc/core/vec3.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// Sign of cross(b − a, c − a), computed exactly: +1 if a, b, c turn counterclockwise, −1 if
/// clockwise, 0 if collinear. O(1); exact for all finite doubles.
int orientation(Vec2 a, Vec2 b, Vec2 c);

/// True if the closed segments s and t share at least one point (touching and collinear overlap
/// included). Exact.
bool segments_intersect(Segment s, Segment t);

/// Sign of (b − a) × (c − a) · (d − a): +1 if d lies on the side of the plane through a, b, c
/// that the normal of the counterclockwise triangle a, b, c points to, −1 on the other side, 0
/// if the four points are coplanar. O(1) almost always (a floating-point filter); exact for
/// finite coordinates whose nonzero magnitudes span at most 2^600 (for instance 1e-80 beside
/// 1e100). NOTE: beyond that span, which no mesh has in practice, the lowest bits of the exact
/// tier may underflow.
int orientation(Vec3 a, Vec3 b, Vec3 c, Vec3 d);

/// Sign of Σ_t a_t · (b_t × c_t) over the triangles (a_t, b_t, c_t) of vertices indexed by
/// `triangles`: six times the volume a closed surface encloses, positive when it faces outward.
/// Computed exactly: every triple product split without error into four doubles, summed in a
/// fixed-point integer, after scaling by a power of two that puts the largest coordinate near
/// 2^300. O(N), about 100 times the cost of a floating-point sum: volume_sign() calls it only
/// when rounding could have decided the sign. NOTE: coordinates more than 2^600 below the
/// largest may lose low bits to underflow, as in orientation().
int exact_volume_sign(std::span<const Vec3> vertices,
                      std::span<const std::array<std::uint32_t, 3>> triangles);

}  // namespace slc
