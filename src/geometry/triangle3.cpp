// Kernels on one triangle of space: nearest point with its feature, and exact contact tests built
// on the exact orientation predicates of predicates.cpp (3D orientation, and the 2D orientation
// in a coordinate plane for coplanar configurations).
#include "slc/geometry/triangle3.hpp"

#include <algorithm>
#include <cmath>

#include "slc/core/error.hpp"
#include "slc/geometry/predicates.hpp"

namespace slc {
namespace {

/// p with coordinate `drop` removed: the projection onto a coordinate plane, keeping the
/// handedness of the remaining axes cyclic (y, z), (z, x), (x, y).
Vec2 project(Vec3 p, int drop) {
    if (drop == 0) return {p.y, p.z};
    if (drop == 1) return {p.z, p.x};
    return {p.x, p.y};
}

/// A coordinate plane onto which t projects to a non-degenerate triangle, with the sign of the
/// projected orientation; drop = −1 when t is degenerate. Exact.
struct Projection {
    int drop = -1;
    int sign = 0;
};
Projection projection_of(const Triangle3& t) {
    for (int drop = 2; drop >= 0; --drop) {
        const int o = orientation(project(t.a, drop), project(t.b, drop), project(t.c, drop));
        if (o != 0) return {drop, o};
    }
    return {};
}

/// Closed 2D point-in-triangle test with exact orientations; sign is the triangle's orientation.
bool contains_2d(Vec2 a, Vec2 b, Vec2 c, int sign, Vec2 p) {
    return orientation(a, b, p) * sign >= 0 && orientation(b, c, p) * sign >= 0 &&
           orientation(c, a, p) * sign >= 0;
}

/// True if the point w, seen from corner v of t, lies in t's plane and within t's closed angle
/// at v: then the segment from v towards w enters t beyond v. Corners t[1], t[2] are the other
/// two; v = t[0].
bool enters_at_corner(const Triangle3& t, Vec3 w) {
    if (orientation(t.a, t.b, t.c, w) != 0) return false;
    const Projection pr = projection_of(t);
    const Vec2 v = project(t.a, pr.drop), p = project(t.b, pr.drop), q = project(t.c, pr.drop);
    const Vec2 ww = project(w, pr.drop);
    return orientation(v, p, ww) * pr.sign >= 0 && orientation(v, ww, q) * pr.sign >= 0;
}

/// True when the products of scalar products within m = max |d| neither overflow nor lose
/// their precision to underflow: m in [2^−400, 2^500], or 0.
inline bool products_in_range(double m) { return m <= 0x1p500 && (m >= 0x1p-400 || m == 0.0); }

FacetPoint scaled_closest_point(const Triangle3& t, Vec3 x);

/// Ericson §5.1.5: the Voronoi regions of the corners, then of the edges, then the face,
/// decided by the signs of the scalar products d1..d6 and of the barycentric numerators, their
/// products. checked: before the first product of each pair of d's, hand over to
/// scaled_closest_point where the products could overflow or underflow (coordinates beyond
/// about 1e75, or below 1e−60 in a small triangle).
template <bool checked>
[[gnu::always_inline]] inline FacetPoint ericson_closest_point(const Triangle3& t, Vec3 x) {
    const Vec3 ab = t.b - t.a, ac = t.c - t.a, ap = x - t.a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return {t.a, {1.0, 0.0, 0.0}, norm2(ap), Feature::vertex, 0};
    const Vec3 bp = x - t.b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return {t.b, {0.0, 1.0, 0.0}, norm2(bp), Feature::vertex, 1};
    if constexpr (checked) {
        const double m =
            std::max(std::max(std::abs(d1), std::abs(d2)), std::max(std::abs(d3), std::abs(d4)));
        if (!products_in_range(m)) return scaled_closest_point(t, x);
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double v = d1 / (d1 - d3);
        const Vec3 p = t.a + v * ab;
        return {p, {1.0 - v, v, 0.0}, norm2(x - p), Feature::edge, 0};
    }
    const Vec3 cp = x - t.c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return {t.c, {0.0, 0.0, 1.0}, norm2(cp), Feature::vertex, 2};
    // d1..d4 set the scale: d5 and d6 may only overflow.
    if constexpr (checked) {
        if (!(std::max(std::abs(d5), std::abs(d6)) <= 0x1p500)) return scaled_closest_point(t, x);
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double w = d2 / (d2 - d6);
        const Vec3 p = t.a + w * ac;
        return {p, {1.0 - w, 0.0, w}, norm2(x - p), Feature::edge, 2};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        const Vec3 p = t.b + w * (t.c - t.b);
        return {p, {0.0, 1.0 - w, w}, norm2(x - p), Feature::edge, 1};
    }
    const double denom = 1.0 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    const Vec3 p = t.a + v * ab + w * ac;
    return {p, {1.0 - v - w, v, w}, norm2(x - p), Feature::face, 0};
}

/// The same arithmetic on t and x scaled by a power of two that brings the largest coordinate
/// difference near 1, which is exact and keeps every rounding, and the answer scaled back.
FacetPoint scaled_closest_point(const Triangle3& t, Vec3 x) {
    auto largest = [](Vec3 v) {
        return std::max(std::max(std::abs(v.x), std::abs(v.y)), std::abs(v.z));
    };
    const double m = std::max(std::max(largest(t.b - t.a), largest(t.c - t.a)), largest(x - t.a));
    const int e = std::ilogb(m);
    const double s = std::ldexp(1.0, -e), back = std::ldexp(1.0, e);
    FacetPoint f = ericson_closest_point<false>({s * t.a, s * t.b, s * t.c}, s * x);
    f.point = back * f.point;
    f.distance2 *= back * back;
    return f;
}

}  // namespace

FacetPoint closest_point(const Triangle3& t, Vec3 x) { return ericson_closest_point<true>(t, x); }

FacetPoint closest_point_in_range(const Triangle3& t, Vec3 x) {
    return ericson_closest_point<false>(t, x);
}

bool in_plain_range(const Triangle3& t) {
    const Vec3 ab = t.b - t.a;
    return in_plain_range(t.a) && in_plain_range(t.b) && in_plain_range(t.c) &&
           norm2(ab) >= plain_edge * plain_edge;
}

Vec3 unit_normal(const Triangle3& t) {
    const Vec3 n = cross(t.b - t.a, t.c - t.a);
    return n / norm(n);
}

double area(const Triangle3& t) { return 0.5 * norm(cross(t.b - t.a, t.c - t.a)); }

bool is_degenerate(const Triangle3& t) { return projection_of(t).drop < 0; }

bool segment_meets_triangle(Vec3 p, Vec3 q, const Triangle3& t) {
    if (!bounding_box(t).overlaps(unite({p, p}, {q, q}))) return false;
    const int sp = orientation(t.a, t.b, t.c, p);
    const int sq = orientation(t.a, t.b, t.c, q);
    if (sp == sq && sp != 0) return false;  // both strictly on one side
    if (sp == 0 && sq == 0) {
        // Coplanar: in a plane where t stays a triangle, an endpoint inside t or a crossing of
        // one of its edges.
        const Projection pr = projection_of(t);
        SLC_ASSERT(pr.drop >= 0, "segment_meets_triangle: t is not degenerate");
        const Vec2 a = project(t.a, pr.drop), b = project(t.b, pr.drop), c = project(t.c, pr.drop);
        const Segment s{project(p, pr.drop), project(q, pr.drop)};
        return contains_2d(a, b, c, pr.sign, s.a) || contains_2d(a, b, c, pr.sign, s.b) ||
               segments_intersect(s, {a, b}) || segments_intersect(s, {b, c}) ||
               segments_intersect(s, {c, a});
    }
    // The line through p and q crosses t's plane once, at a point of the segment; it passes
    // through the closed triangle iff it turns the same way (or not at all) around all three
    // edges.
    const int o0 = orientation(p, q, t.a, t.b);
    const int o1 = orientation(p, q, t.b, t.c);
    const int o2 = orientation(p, q, t.c, t.a);
    return (o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0);
}

bool triangles_intersect(const Triangle3& s, const Triangle3& t) {
    if (!bounding_box(s).overlaps(bounding_box(t))) return false;
    // A triangle strictly on one side of the other's plane meets nothing of it (three
    // predicates, where the edges' tests below would take twelve or more to say so).
    auto beyond_plane = [](const Triangle3& u, const Triangle3& v) {
        const int a = orientation(u.a, u.b, u.c, v.a);
        return a != 0 && a == orientation(u.a, u.b, u.c, v.b) &&
               a == orientation(u.a, u.b, u.c, v.c);
    };
    if (beyond_plane(s, t) || beyond_plane(t, s)) return false;
    // Two closed triangles meet iff an edge of one meets the other: the ends of their common
    // part (a segment on the line where their planes cross, or a convex polygon when coplanar)
    // lie on edges.
    for (int k = 0; k < 3; ++k) {
        if (segment_meets_triangle(s[k], s[(k + 1) % 3], t)) return true;
        if (segment_meets_triangle(t[k], t[(k + 1) % 3], s)) return true;
    }
    return false;
}

bool triangles_overlap(const Triangle3& s, const Triangle3& t, int shared) {
    if (shared == 0) return triangles_intersect(s, t);
    if (shared == 1) {
        // Common corner v = s[0] = t[0]. A triangle whose other corners lie strictly on one
        // side of the other's plane meets that plane only at v (on a smooth surface, nearly
        // every pair of triangles around a vertex): two predicates decide it.
        const int tb = orientation(s.a, s.b, s.c, t.b);
        if (tb != 0 && tb == orientation(s.a, s.b, s.c, t.c)) return false;
        const int sb = orientation(t.a, t.b, t.c, s.b);
        if (sb != 0 && sb == orientation(t.a, t.b, t.c, s.c)) return false;
        // Otherwise the common part is convex and holds v; if it holds
        // more, its far end lies on an edge opposite v (which then meets the other triangle), or
        // the common part runs along an edge at v lying in the other triangle's angle at v.
        if (segment_meets_triangle(s.b, s.c, t) || segment_meets_triangle(t.b, t.c, s)) return true;
        return enters_at_corner(t, s.b) || enters_at_corner(t, s.c) || enters_at_corner(s, t.b) ||
               enters_at_corner(s, t.c);
    }
    // Common edge s[0]s[1] = t[0]t[1]: triangles in different planes meet only on the line of
    // their planes' crossing, which is the edge; in one plane they overlap iff their third
    // corners lie on the same side of the edge (a fold).
    if (orientation(s.a, s.b, s.c, t.c) != 0) return false;
    const Projection pr = projection_of(s);
    const Vec2 a = project(s.a, pr.drop), b = project(s.b, pr.drop);
    return orientation(a, b, project(t.c, pr.drop)) == pr.sign;
}

}  // namespace slc
