/// @file
/// Kernels on one triangle of space: the nearest point to x with the feature (face, edge, vertex)
/// that holds it, exactly as the distance tree and its brute-force oracle need it (paper §1.3 with
/// d = 3); and exact tests of degeneracy and of contact between triangles and segments, on which
/// the validation of surfaces rests.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "slc/core/box3.hpp"
#include "slc/core/vec3.hpp"

namespace slc {

/// A triangle of space given by its corners; counterclockwise seen from the side its normal
/// (b − a) × (c − a) points to.
struct Triangle3 {
    Vec3 a;  ///< corner 0
    Vec3 b;  ///< corner 1
    Vec3 c;  ///< corner 2
    /// Corner k (0, 1, 2).
    constexpr Vec3 operator[](int k) const { return k == 0 ? a : (k == 1 ? b : c); }
};

/// The smallest box holding the triangle.
constexpr Box3 bounding_box(const Triangle3& t) {
    return unite(unite({t.a, t.a}, {t.b, t.b}), {t.c, t.c});
}

/// Which part of a triangle holds a point: its open face, an open edge (edge k joins corner k to
/// corner k + 1 mod 3), or a corner.
enum class Feature : std::uint8_t { face, edge, vertex };

/// The point of a triangle nearest x.
struct FacetPoint {
    Vec3 point;  ///< the nearest point
    std::array<double, 3>
        weights{};           ///< barycentric: point = Σ weights[k]·corner k, each in [0, 1]
    double distance2 = 0.0;  ///< squared distance from x to point
    Feature feature = Feature::face;  ///< the part of the triangle holding point
    std::uint8_t index = 0;           ///< the edge or corner number when feature is not face
};

/// Nearest point of the closed triangle t to x, by the Voronoi regions of its corners, edges and
/// face (Ericson, Real-Time Collision Detection, §5.1.5). A corner is returned exactly (weights
/// 1, 0, 0), so that a nearest vertex is recognised by its feature. Distance exact to rounding.
/// Precondition: t is not degenerate. O(1). At any coordinates: where products of its scalar
/// products would overflow or underflow (coordinates beyond about 1e75, or a triangle and a
/// distance below about 1e−60), the same arithmetic on everything scaled by a power of two,
/// which keeps every rounding.
FacetPoint closest_point(const Triangle3& t, Vec3 x);

/// closest_point without the range checks, the same answer when in_plain_range(t) and every
/// coordinate of x is within ±plain_coordinate (the trees check that once per query).
FacetPoint closest_point_in_range(const Triangle3& t, Vec3 x);

/// The coordinates, and the least length of a triangle's first edge, within which
/// closest_point_in_range needs no checks: its scalar products d then lie within 2^404 and
/// max|d| is at least 2^−301 (d1 − d3 = |b − a|²), so their products neither overflow nor
/// underflow.
inline constexpr double plain_coordinate = 0x1p200;
inline constexpr double plain_edge = 0x1p-150;  ///< (see plain_coordinate)
/// True when every corner of t is within ±plain_coordinate and |b − a| ≥ plain_edge.
bool in_plain_range(const Triangle3& t);
/// True when every coordinate of x is within ±plain_coordinate.
inline bool in_plain_range(Vec3 x) {
    return std::abs(x.x) <= plain_coordinate && std::abs(x.y) <= plain_coordinate &&
           std::abs(x.z) <= plain_coordinate;
}

/// The unit normal of t, (b − a) × (c − a) normalised. Precondition: t is not degenerate.
Vec3 unit_normal(const Triangle3& t);

/// Area of t.
double area(const Triangle3& t);

/// True when the three corners are collinear (zero area), decided exactly.
bool is_degenerate(const Triangle3& t);

/// True if the closed segment [p, q] and the closed triangle t share a point, decided exactly.
/// Precondition: t is not degenerate.
bool segment_meets_triangle(Vec3 p, Vec3 q, const Triangle3& t);

/// True if the closed triangles s and t share a point, decided exactly (touching counts).
/// Preconditions: neither is degenerate.
bool triangles_intersect(const Triangle3& s, const Triangle3& t);

/// How two triangles of a surface that share `shared` corners (0, 1 or 2) meet: true if they meet
/// anywhere else than in the corners and the edge they share, decided exactly. The corners are
/// given so that s[k] == t[k] for k < shared. Preconditions: neither is degenerate.
bool triangles_overlap(const Triangle3& s, const Triangle3& t, int shared);

}  // namespace slc
