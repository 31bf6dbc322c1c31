/// @file
/// Closest point on a segment and signed distance to an interface by brute force: the exact kernel
/// that the distance tree calls, and the oracle its tests compare against.
#pragma once

#include <algorithm>
#include <cstddef>

#include "slc/core/box.hpp"
#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// The point of segment [a, b] nearest x: point = a + t (b − a) with t in [0, 1].
struct SegmentPoint {
    Vec2 point;              ///< the nearest point of the segment
    double t = 0.0;          ///< its parameter: point = a + t (b − a), t in [0, 1]
    double distance2 = 0.0;  ///< squared distance from x to point
};

/// The smallest box holding the segment.
inline Box bounding_box(Segment s) {
    return {{std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y)},
            {std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y)}};
}

/// Nearest point to x on the segment [a, b] (a degenerate segment is its endpoint). O(1); inline,
/// since the distance tree calls it in its innermost loop.
inline SegmentPoint closest_point(Segment s, Vec2 x) {
    const Vec2 d = s.b - s.a;
    const double len2 = norm2(d);
    const double along = dot(x - s.a, d);
    // Endpoints are returned exactly, so that a nearest vertex is recognised by t == 0 or 1.
    // They are told by the sign of along and its size against len2, before any division: the
    // same t as clamping along / len2 to [0, 1], without waiting for the quotient.
    if (along < 0.0 || len2 == 0.0) return {s.a, 0.0, norm2(x - s.a)};
    if (along >= len2) return {s.b, 1.0, norm2(x - s.b)};
    const double t = along / len2;
    const Vec2 p = t == 0.0 ? s.a : (t == 1.0 ? s.b : s.a + t * d);
    return {p, t, norm2(x - p)};
}

/// Signed closest point of an interface to a query point x.
struct ClosestPoint {
    double distance = 0.0;    ///< signed distance F(x): negative inside, positive outside
    Vec2 point;               ///< a nearest point of Γ to x
    std::size_t segment = 0;  ///< the segment holding point
    double t = 0.0;           ///< point = a + t (b − a) on that segment
};

/// The sign of F at x, given that point (parameter t on segment s) is a nearest point of Γ to x.
/// Inside the segment the side of its line decides; at a vertex the sum of the outward normals of
/// the two incident segments (the pseudo-normal) decides, which is right at convex and concave
/// corners alike. Returns +1 or −1; +1 when x is on Γ.
int side_of(const Interface& curves, std::size_t s, double t, Vec2 x);

/// Signed closest point by comparing every segment: O(N). The oracle for the distance tree.
/// Precondition: curves is not empty.
ClosestPoint closest_point_brute_force(const Interface& curves, Vec2 x);

/// Crossing-number test: true if x lies inside an odd number of the curves. Independent of
/// orientation; the sign oracle for tests.
bool is_inside_even_odd(const Interface& curves, Vec2 x);

}  // namespace slc
