// Tests of the closest point on a segment (segment.hpp), the distance tree's innermost kernel:
// the clamped projection of x, with endpoints returned exactly, on random, tiny, huge and
// degenerate segments and on points whose projection falls exactly on an endpoint.
#include "slc/geometry/segment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace slc {
namespace {

/// The definition: t = dot(x − a, b − a) / |b − a|² clamped to [0, 1] (0 for a degenerate
/// segment), the point a + t (b − a), except that t = 0 and t = 1 give a and b themselves.
SegmentPoint clamped_projection(Segment s, Vec2 x) {
    const Vec2 d = s.b - s.a;
    const double len2 = norm2(d);
    const double t = len2 > 0.0 ? std::clamp(dot(x - s.a, d) / len2, 0.0, 1.0) : 0.0;
    const Vec2 p = t == 0.0 ? s.a : (t == 1.0 ? s.b : s.a + t * d);
    return {p, t, norm2(x - p)};
}

void expect_same(const SegmentPoint& got, const SegmentPoint& want) {
    EXPECT_EQ(got.point.x, want.point.x);
    EXPECT_EQ(got.point.y, want.point.y);
    EXPECT_EQ(got.t, want.t);  // also +0 against −0: both are t == 0
    EXPECT_EQ(got.distance2, want.distance2);
}

TEST(ClosestPointOnSegment, IsTheClampedProjectionToTheLastBit) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-30, 30);
    std::uniform_int_distribution<int> shorter(0, 30);  // segment length: scale down to 2^-30 scale
    int interior = 0, ends = 0;
    for (int i = 0; i < 200000; ++i) {
        const double scale = std::ldexp(1.0, exponent(rng));
        const Vec2 a{scale * unit(rng), scale * unit(rng)};
        // Segments from 2^-30 of the scale up to the scale itself.
        const double length = scale * std::ldexp(1.0, -shorter(rng));
        const Vec2 b = a + length * Vec2{unit(rng), unit(rng)};
        const Vec2 x = a + scale * Vec2{unit(rng), unit(rng)};
        const SegmentPoint got = closest_point({a, b}, x);
        expect_same(got, clamped_projection({a, b}, x));
        (got.t == 0.0 || got.t == 1.0 ? ends : interior) += 1;
        if (HasFailure()) return;
    }
    EXPECT_GT(interior, 1000);  // both branches of the kernel were exercised
    EXPECT_GT(ends, 1000);
}

TEST(ClosestPointOnSegment, EndpointsAreExactWhereTheProjectionFallsOnThem) {
    const Segment s{{0.1, 0.2}, {0.7, -0.3}};
    const Vec2 d = s.b - s.a;
    const Vec2 normal{-d.y, d.x};
    // Points on the normal lines through a and b project onto the ends (up to rounding, which
    // can put the quotient just inside or just outside [0, 1]).
    for (double along : {-2.0, -0.5, 0.0, 0.5, 2.0}) {
        for (const Vec2 end : {s.a, s.b}) {
            const Vec2 x = end + along * normal;
            const SegmentPoint got = closest_point(s, x);
            expect_same(got, clamped_projection(s, x));
        }
    }
    // Beyond the ends: the ends themselves, with t exactly 0 and 1.
    const SegmentPoint before = closest_point(s, s.a - 0.25 * d);
    EXPECT_EQ(before.t, 0.0);
    EXPECT_EQ(before.point.x, s.a.x);
    EXPECT_EQ(before.point.y, s.a.y);
    const SegmentPoint after = closest_point(s, s.b + 1e-3 * d);
    EXPECT_EQ(after.t, 1.0);
    EXPECT_EQ(after.point.x, s.b.x);
    EXPECT_EQ(after.point.y, s.b.y);
    EXPECT_EQ(after.distance2, norm2((s.b + 1e-3 * d) - s.b));

    // An end near 0 on a segment from far away: a + (b − a) rounds to 0, not b.
    const Segment far{{1.0, 1.0}, {1e-20, -1e-20}};
    const SegmentPoint near_end = closest_point(far, {-1.0, -1.0});
    EXPECT_EQ(near_end.t, 1.0);
    EXPECT_EQ(near_end.point.x, 1e-20);
    EXPECT_EQ(near_end.point.y, -1e-20);
}

TEST(ClosestPointOnSegment, DegenerateSegmentIsItsEndpoint) {
    const Vec2 a{0.3, -0.4};
    const SegmentPoint got = closest_point({a, a}, {1.3, 0.6});
    EXPECT_EQ(got.t, 0.0);
    EXPECT_EQ(got.point.x, a.x);
    EXPECT_EQ(got.point.y, a.y);
    EXPECT_DOUBLE_EQ(got.distance2, 2.0);
}

}  // namespace
}  // namespace slc
