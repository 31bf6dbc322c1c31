// Tests of the 3D orientation predicate against integer arithmetic, of the nearest point on a
// triangle against an independent construction, and of the exact contact tests on known cases.
#include "slc/geometry/triangle3.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "slc/geometry/predicates.hpp"

namespace slc {
namespace {

/// The orientation of integer points by 64-bit integer arithmetic: the oracle.
int integer_orientation(const std::int64_t p[4][3]) {
    std::int64_t u[3], v[3], w[3];
    for (int i = 0; i < 3; ++i) {
        u[i] = p[1][i] - p[0][i];
        v[i] = p[2][i] - p[0][i];
        w[i] = p[3][i] - p[0][i];
    }
    const std::int64_t det = u[0] * (v[1] * w[2] - v[2] * w[1]) +
                             u[1] * (v[2] * w[0] - v[0] * w[2]) +
                             u[2] * (v[0] * w[1] - v[1] * w[0]);
    return (det > 0) - (det < 0);
}

TEST(Orientation3, AgreesWithIntegerArithmeticUnderScalingAndTranslation) {
    std::mt19937 rng(7);
    // Small integers make many coplanar quadruples; scaling by 2^k and adding an offset 2^(k+45)
    // (both exact: 47 bits at most) keep the sign but defeat the floating-point filter.
    std::uniform_int_distribution<int> coordinate(-3, 3);
    for (int trial = 0; trial < 20000; ++trial) {
        SCOPED_TRACE(trial);
        std::int64_t p[4][3];
        for (auto& q : p)
            for (auto& c : q) c = coordinate(rng);
        const int want = integer_orientation(p);
        for (const int k : {-40, 0, 30}) {
            for (const double offset : {0.0, std::ldexp(1.0, k + 45)}) {
                Vec3 v[4];
                for (int i = 0; i < 4; ++i) {
                    v[i] = {std::ldexp(static_cast<double>(p[i][0]), k) + offset,
                            std::ldexp(static_cast<double>(p[i][1]), k) - offset,
                            std::ldexp(static_cast<double>(p[i][2]), k) + offset};
                }
                ASSERT_EQ(orientation(v[0], v[1], v[2], v[3]), want) << "k " << k;
            }
        }
    }
}

TEST(Orientation3, DecidesPointsNearlyOnAPlane) {
    const Vec3 a{0.1, 0.2, 0.3}, b{1.7, -0.4, 0.9}, c{-0.6, 1.3, 0.5};
    EXPECT_EQ(orientation(a, b, c, b), 0);
    EXPECT_EQ(orientation(a, b, c, a), 0);
    // A point one ulp above a corner in z: the sign of the normal's z-component decides.
    const double nz = cross(b - a, c - a).z;
    EXPECT_EQ(orientation(a, b, c, Vec3{b.x, b.y, std::nextafter(b.z, 10.0)}), nz > 0 ? 1 : -1);
    EXPECT_EQ(orientation(a, b, c, Vec3{b.x, b.y, std::nextafter(b.z, -10.0)}), nz > 0 ? -1 : 1);
    // Magnitudes far apart, so that the differences of the points are not exact doubles: the
    // plane z = 0, whose normal ((q − p) × (r − p)).z = −6·2^60 − 26 is negative.
    const Vec3 p{0x1p60, 0, 0}, q{-3, 1, 0}, r{5, 7, 0};
    EXPECT_EQ(orientation(p, q, r, Vec3{1, 2, 0}), 0);
    EXPECT_EQ(orientation(p, q, r, Vec3{1, 2, 0x1p-80}), -1);
    EXPECT_EQ(orientation(p, q, r, Vec3{1, 2, -0x1p-80}), 1);
}

/// The nearest point by another construction: the projection on the plane when it falls inside
/// the triangle, else the nearest of the three edges' nearest points.
Vec3 nearest_by_projection(const Triangle3& t, Vec3 x) {
    const Vec3 n = unit_normal(t);
    const Vec3 p = x - dot(x - t.a, n) * n;
    bool inside = true;
    for (int k = 0; k < 3; ++k)
        if (dot(cross(t[(k + 1) % 3] - t[k], p - t[k]), n) < 0.0) inside = false;
    if (inside) return p;
    Vec3 best;
    double best2 = INFINITY;
    for (int k = 0; k < 3; ++k) {
        const Vec3 a = t[k], d = t[(k + 1) % 3] - a;
        const double s = std::clamp(dot(x - a, d) / norm2(d), 0.0, 1.0);
        const Vec3 q = a + s * d;
        if (norm2(x - q) < best2) {
            best2 = norm2(x - q);
            best = q;
        }
    }
    return best;
}

TEST(Triangle3, ClosestPointAgreesWithProjectionAndNamesItsFeature) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int trial = 0; trial < 20000; ++trial) {
        const Triangle3 t{
            {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
        if (area(t) < 1e-3) continue;
        const Vec3 x{u(rng), u(rng), u(rng)};
        const FacetPoint p = closest_point(t, x);
        const Vec3 q = nearest_by_projection(t, x);
        // Both are the exact nearest point up to a few roundings of O(1) quantities (the
        // triangles are not thin: area at least 1e-3 within a box of width 4).
        constexpr double rounding = 1e-12;
        ASSERT_LT(distance(p.point, q), rounding) << "trial " << trial;
        ASSERT_NEAR(std::sqrt(p.distance2), distance(x, q), rounding);
        const Vec3 back = p.weights[0] * t.a + p.weights[1] * t.b + p.weights[2] * t.c;
        ASSERT_LT(distance(back, p.point), rounding);
        if (p.feature == Feature::vertex) {
            ASSERT_EQ(p.point, t[p.index]);
        } else if (p.feature == Feature::edge) {
            // x − p is perpendicular to the edge.
            const Vec3 d = t[(p.index + 1) % 3] - t[p.index];
            ASSERT_NEAR(dot(x - p.point, d) / norm(d), 0.0, rounding);
            ASSERT_EQ(p.weights[(p.index + 2) % 3], 0.0);
        } else {
            // x − p is along the normal.
            ASSERT_LT(norm(cross(x - p.point, unit_normal(t))), rounding);
        }
    }
}

// Scaling by a power of two is exact, so the nearest point of a triangle scaled up to the
// coordinate limit, or down to 1e-90, is the unit one's scaled, bit for bit, where the products
// of the scalar products (the fourth power of the coordinates) would overflow or underflow
// without care.
TEST(Triangle3, ClosestPointIsExactlyScaleInvariantUpToTheCoordinateLimit) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (const int e : {-300, -250, -100, 0, 100, 250, 260, 300, 330}) {
        const double s = std::ldexp(1.0, e);
        for (int trial = 0; trial < 2000; ++trial) {
            const Triangle3 t{
                {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
            const Vec3 x{u(rng), u(rng), u(rng)};
            const FacetPoint p = closest_point(t, x);
            const FacetPoint q = closest_point({s * t.a, s * t.b, s * t.c}, s * x);
            ASSERT_EQ(q.point, s * p.point) << "2^" << e << ", trial " << trial;
            ASSERT_EQ(q.distance2, s * s * p.distance2) << "2^" << e;
            ASSERT_EQ(q.weights, p.weights);
            ASSERT_EQ(q.feature, p.feature);
            ASSERT_EQ(q.index, p.index);
        }
    }
}

TEST(Triangle3, DegeneracyIsDecidedExactly) {
    EXPECT_TRUE(is_degenerate({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}));
    EXPECT_TRUE(is_degenerate({{0.1, 0.2, 0.3}, {0.1, 0.2, 0.3}, {1, 0, 0}}));
    EXPECT_FALSE(is_degenerate({{0, 0, 0}, {1, 1, 1}, {2, 2, std::nextafter(2.0, 3.0)}}));
}

const Triangle3 base{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};

TEST(Triangle3, TrianglesIntersectCases) {
    // Crossing the plane through the interior.
    EXPECT_TRUE(triangles_intersect(base, {{0.5, 0.5, -1}, {0.5, 0.5, 1}, {0.6, 0.6, 1}}));
    // Above, disjoint.
    EXPECT_FALSE(triangles_intersect(base, {{0.5, 0.5, 0.1}, {1.5, 0.5, 1}, {0.6, 1.6, 1}}));
    // A corner touching the face: touching counts.
    EXPECT_TRUE(triangles_intersect(base, {{0.5, 0.5, 0}, {1.5, 0.5, 1}, {0.6, 1.6, 1}}));
    // Touching the edge x + y = 2 from outside, in another plane.
    EXPECT_TRUE(triangles_intersect(base, {{1, 1, 0}, {3, 3, 1}, {3, 3, -1}}));
    // Passing just beyond that edge.
    EXPECT_FALSE(
        triangles_intersect(base, {{1, std::nextafter(1.0, 2.0), 0}, {3, 3, 1}, {3, 3, -1}}));
    // Coplanar: overlapping, touching by a corner, disjoint.
    EXPECT_TRUE(triangles_intersect(base, {{1, 1, 0}, {-1, 1, 0}, {0, -1, 0}}));
    EXPECT_TRUE(triangles_intersect(base, {{2, 0, 0}, {3, 0, 0}, {3, 1, 0}}));
    EXPECT_FALSE(triangles_intersect(base, {{2.5, 0, 0}, {3, 0, 0}, {3, 1, 0}}));
    // Coplanar, one inside the other.
    EXPECT_TRUE(triangles_intersect(base, {{0.1, 0.1, 0}, {0.2, 0.1, 0}, {0.1, 0.2, 0}}));
}

TEST(Triangle3, TrianglesIntersectIsAnEdgeOfOneMeetingTheOther) {
    // Corners on a small grid, so that touching, coplanar and collinear cases are common: the
    // answer, with its early test of each triangle against the other's plane, is the edges'.
    std::mt19937 rng(21);
    std::uniform_int_distribution<int> coordinate(0, 3);
    auto corner = [&] {
        return Vec3{static_cast<double>(coordinate(rng)), static_cast<double>(coordinate(rng)),
                    static_cast<double>(coordinate(rng))};
    };
    int met = 0, apart = 0;
    for (int k = 0; k < 20000; ++k) {
        const Triangle3 s{corner(), corner(), corner()}, t{corner(), corner(), corner()};
        if (is_degenerate(s) || is_degenerate(t)) continue;
        bool edges = false;
        for (int e = 0; e < 3; ++e) {
            edges = edges || segment_meets_triangle(s[e], s[(e + 1) % 3], t) ||
                    segment_meets_triangle(t[e], t[(e + 1) % 3], s);
        }
        ASSERT_EQ(triangles_intersect(s, t), edges) << "case " << k;
        (edges ? met : apart) += 1;
    }
    EXPECT_GT(met, 1000);
    EXPECT_GT(apart, 1000);
}

TEST(Triangle3, OverlapOfTrianglesSharingACorner) {
    // Two faces of a tetrahedron meet only at their corner... (the shared corner comes first)
    EXPECT_FALSE(triangles_overlap(base, {{0, 0, 0}, {0, 0, 2}, {-1, 1, 0}}, 1));
    // ...but a triangle through the other's face at the corner does not.
    EXPECT_TRUE(triangles_overlap(base, {{0, 0, 0}, {1, 1, -1}, {1, 1, 1}}, 1));
    // Coplanar, opening inside the other's angle at the corner.
    EXPECT_TRUE(triangles_overlap(base, {{0, 0, 0}, {1, 0.5, 0}, {0.5, 1, 0}}, 1));
    // Coplanar, outside the angle.
    EXPECT_FALSE(triangles_overlap(base, {{0, 0, 0}, {-1, -0.5, 0}, {-0.5, -1, 0}}, 1));
    // An edge along the other's edge (in its plane), the rest above.
    EXPECT_TRUE(triangles_overlap(base, {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, 1));
    // Far side crossing the other triangle.
    EXPECT_TRUE(triangles_overlap(base, {{0, 0, 0}, {1, 0.2, -1}, {0.2, 1, 1}}, 1));
}

TEST(Triangle3, OverlapOfTrianglesSharingAnEdge) {
    // A hinge: different planes meet only along the edge.
    EXPECT_FALSE(triangles_overlap(base, {{0, 0, 0}, {2, 0, 0}, {0, 1, 1}}, 2));
    // Flat, opposite sides: the two halves of a square.
    EXPECT_FALSE(triangles_overlap(base, {{0, 0, 0}, {2, 0, 0}, {1, -1, 0}}, 2));
    // Flat, the same side: folded over.
    EXPECT_TRUE(triangles_overlap(base, {{0, 0, 0}, {2, 0, 0}, {1, 0.1, 0}}, 2));
}

}  // namespace
}  // namespace slc
