// Closest point on a segment, the sign rule at corners, and the brute-force oracles.
#include "slc/geometry/segment.hpp"

#include <limits>

namespace slc {

namespace {

/// Outward unit normal of segment i: its direction turned a quarter clockwise (outside on the
/// right).
Vec2 outward_normal(const Interface& curves, std::size_t i) {
    const Segment s = curves.segment(i);
    const Vec2 d = s.b - s.a;
    const double len = norm(d);
    return len > 0.0 ? Vec2{d.y / len, -d.x / len} : Vec2{};
}

}  // namespace

int side_of(const Interface& curves, std::size_t s, double t, Vec2 x) {
    const Segment seg = curves.segment(s);
    double side = 0.0;
    if (t > 0.0 && t < 1.0) {
        // Left of a segment is inside (F < 0).
        side = -cross(seg.b - seg.a, x - seg.a);
    } else {
        const std::size_t v = t == 0.0 ? s : curves.next(s);
        const Vec2 pseudo_normal =
            outward_normal(curves, curves.prev(v)) + outward_normal(curves, v);
        side = dot(x - curves.point(v), pseudo_normal);
    }
    return side < 0.0 ? -1 : 1;
}

ClosestPoint closest_point_brute_force(const Interface& curves, Vec2 x) {
    double best = std::numeric_limits<double>::infinity();
    ClosestPoint result;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const SegmentPoint p = closest_point(curves.segment(i), x);
        if (p.distance2 < best) {
            best = p.distance2;
            result.point = p.point;
            result.segment = i;
            result.t = p.t;
        }
    }
    const double d = std::sqrt(best);
    result.distance = d == 0.0 ? 0.0 : side_of(curves, result.segment, result.t, x) * d;
    return result;
}

bool is_inside_even_odd(const Interface& curves, Vec2 x) {
    bool inside = false;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const Segment s = curves.segment(i);
        if ((s.a.y > x.y) != (s.b.y > x.y)) {
            const double xc = s.a.x + (x.y - s.a.y) * (s.b.x - s.a.x) / (s.b.y - s.a.y);
            if (x.x < xc) inside = !inside;
        }
    }
    return inside;
}

}  // namespace slc
