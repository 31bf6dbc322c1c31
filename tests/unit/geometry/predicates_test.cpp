// Tests of the exact predicates (predicates.hpp): orientation against exact integer arithmetic on
// inputs where plain double arithmetic gets the sign wrong, at every scale of the exponent range;
// segments_intersect against a rational oracle on grid segments.
#include "slc/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace slc {
namespace {

__extension__ typedef __int128 Int128;  // __extension__: a GCC/Clang type, fine in a test

int sign_of(Int128 v) { return (v > 0) - (v < 0); }

/// The exact orientation of integer points, |coordinates| < 2^58: differences below 2^59,
/// products below 2^118, well inside __int128.
int exact_orientation(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by,
                      std::int64_t cx, std::int64_t cy) {
    const Int128 det = Int128(bx - ax) * Int128(cy - ay) - Int128(by - ay) * Int128(cx - ax);
    return sign_of(det);
}

int naive_orientation(Vec2 a, Vec2 b, Vec2 c) {
    const double det = cross(b - a, c - a);
    return (det > 0.0) - (det < 0.0);
}

TEST(Orientation, SignsOfSimpleTurns) {
    const Vec2 a{0, 0};
    const Vec2 b{1, 0};
    const Vec2 c{0, 1};
    EXPECT_EQ(orientation(a, b, c), 1);
    EXPECT_EQ(orientation(a, c, b), -1);
    EXPECT_EQ(orientation(b, c, a), 1);
    EXPECT_EQ(orientation(a, b, Vec2{2, 0}), 0);
    EXPECT_EQ(orientation(a, a, c), 0);
    EXPECT_EQ(orientation(a, a, a), 0);
    // Vertical and horizontal lines, where the filter's products vanish.
    EXPECT_EQ(orientation(Vec2{3, 0}, Vec2{3, 1}, Vec2{3, 7}), 0);
    EXPECT_EQ(orientation(Vec2{0, 5}, Vec2{1, 5}, Vec2{-9, 5}), 0);
    EXPECT_EQ(orientation(Vec2{3, 0}, Vec2{3, 1}, Vec2{2, 7}), 1);
}

TEST(Orientation, ExactForNearlyCollinearPoints) {
    // a near (2^49, 2^49); b = a + (q, q + 1), a step along a line of slope nearly 1 (y ≈ x);
    // c = a + k·(q, q + 1) + D·(−1, −1), the far point of the line moved off it by a few units.
    // The determinant is exactly q·(−D) − (q + 1)·(−D) = D in {−2, …, 2}, while the products
    // in it are near 2^75, whose rounding errors (~2^22) swamp it. All coordinates are integers
    // below 2^51, so they and their differences are exact doubles; __int128 gives the exact sign.
    const std::uint32_t seed = 20240611;
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::int64_t> base(std::int64_t{1} << 48, std::int64_t{1} << 49);
    std::uniform_int_distribution<std::int64_t> step(std::int64_t{1} << 24, std::int64_t{1} << 25);
    std::uniform_int_distribution<std::int64_t> off(-2, 2);
    std::uniform_int_distribution<int> rotation(0, 2);
    int naive_wrong = 0;
    for (int n = 0; n < 20000; ++n) {
        const std::int64_t ax = base(rng), ay = ax + off(rng);
        const std::int64_t q = step(rng), k = step(rng), d = off(rng);
        std::int64_t v[6] = {ax, ay, ax + q, ay + q + 1, ax + k * q - d, ay + k * (q + 1) - d};
        // Any of the three points may come first.
        std::rotate(v, v + 2 * rotation(rng), v + 6);
        const Vec2 a{double(v[0]), double(v[1])};
        const Vec2 b{double(v[2]), double(v[3])};
        const Vec2 c{double(v[4]), double(v[5])};
        const int expected = exact_orientation(v[0], v[1], v[2], v[3], v[4], v[5]);
        ASSERT_EQ(orientation(a, b, c), expected) << "case " << n;
        ASSERT_EQ(orientation(b, a, c), -expected) << "case " << n;
        naive_wrong += naive_orientation(a, b, c) != expected;
    }
    // The test is only meaningful if plain doubles fail often on these inputs.
    EXPECT_GT(naive_wrong, 5000);
}

TEST(Orientation, ExactOnUlpGridNearOneHalf) {
    // Kettner et al., "Classroom examples of robustness problems in geometric computations"
    // (2008): p = (0.5 + i·u, 0.5 + j·u) with u = 2^-53, q = (12, 12), r = (24, 24). Scaled by 2^53
    // every coordinate is an integer below 2^58.
    const double u = std::ldexp(1.0, -53);
    const std::int64_t scale = std::int64_t{1} << 53;
    int naive_wrong = 0;
    for (std::int64_t i = 0; i < 256; ++i) {
        for (std::int64_t j = 0; j < 256; ++j) {
            const Vec2 p{0.5 + double(i) * u, 0.5 + double(j) * u};
            const Vec2 q{12, 12};
            const Vec2 r{24, 24};
            const int expected = exact_orientation(scale / 2 + i, scale / 2 + j, 12 * scale,
                                                   12 * scale, 24 * scale, 24 * scale);
            ASSERT_EQ(orientation(p, q, r), expected) << "i " << i << ", j " << j;
            naive_wrong += naive_orientation(p, q, r) != expected;
        }
    }
    EXPECT_GT(naive_wrong, 1000);
}

TEST(Orientation, ExactAtEveryScale) {
    // Scaling all coordinates by 2^k multiplies the determinant by 2^2k and keeps its sign. From
    // subnormal (k = -1074) to near overflow (k = 971) the scaled integers stay exact doubles;
    // naive products underflow to zero or overflow to infinity at the extremes.
    const std::uint32_t seed = 7;
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::int64_t> base(std::int64_t{1} << 48, std::int64_t{1} << 49);
    std::uniform_int_distribution<std::int64_t> offset(-2, 2);
    for (int scale : {-1074, -1000, -700, -300, 0, 300, 600, 900, 971}) {
        for (int k = 0; k < 2000; ++k) {
            std::int64_t v[6];
            for (int i = 0; i < 3; ++i) {
                const std::int64_t t = base(rng);
                v[2 * i] = t + offset(rng);
                v[2 * i + 1] = t + offset(rng);
            }
            auto at = [&](int i) {
                return Vec2{std::ldexp(double(v[2 * i]), scale),
                            std::ldexp(double(v[2 * i + 1]), scale)};
            };
            const int expected = exact_orientation(v[0], v[1], v[2], v[3], v[4], v[5]);
            ASSERT_EQ(orientation(at(0), at(1), at(2)), expected)
                << "scale 2^" << scale << ", case " << k;
        }
    }
}

TEST(Orientation, ExactWhenProductsUnderflow) {
    // Coordinates near 2^-530 make the filter's products subnormal, where rounding error is no
    // longer relative and an unguarded Shewchuk filter returns the wrong sign about once in 10^4
    // cases. The reference is the same triple scaled by 2^600 (exact: all values are normal),
    // where nothing underflows; the sign of the determinant does not change under scaling.
    const std::uint32_t seed = 17;
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> mantissa(1.0, 2.0);
    std::uniform_int_distribution<int> exponent(-560, -500);
    std::bernoulli_distribution coin(0.5);
    auto draw = [&] { return (coin(rng) ? -1 : 1) * std::ldexp(mantissa(rng), exponent(rng)); };
    auto scaled = [](Vec2 p) { return Vec2{std::ldexp(p.x, 600), std::ldexp(p.y, 600)}; };
    for (int k = 0; k < 300000; ++k) {
        const Vec2 a{draw(), draw()};
        const Vec2 b{draw(), draw()};
        // c on the line ab up to rounding, then nudged by one ulp.
        Vec2 c = a + mantissa(rng) * (b - a);
        c.x = std::nextafter(c.x, coin(rng) ? 1.0 : -1.0);
        ASSERT_EQ(orientation(a, b, c), orientation(scaled(a), scaled(b), scaled(c)))
            << "case " << k;
    }
}

TEST(Orientation, ExactWhenMagnitudesSpanTheWholeExponentRange) {
    // b and c lie exactly on y = x with huge coordinates L1, L2; a = (0, t) is off the line by a
    // tiny t. The determinant is t·(L2 − L1): the products L1·L2 cancel and what decides is
    // 2^-1074-sized terms against 2^2000-sized ones, too wide a span for one expansion of doubles.
    const std::uint32_t seed = 99;
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> mantissa(1.0, 2.0);
    std::uniform_int_distribution<int> huge(600, 1022);
    std::uniform_int_distribution<int> tiny(-1074, -600);
    for (int k = 0; k < 5000; ++k) {
        const double l1 = std::ldexp(mantissa(rng), huge(rng));
        const double l2 = std::ldexp(mantissa(rng), huge(rng));
        const double t = (k % 2 == 0 ? 1.0 : -1.0) * std::ldexp(mantissa(rng), tiny(rng));
        const int expected = (t > 0 ? 1 : -1) * ((l2 > l1) - (l2 < l1));
        const Vec2 a{0, t};
        const Vec2 b{l1, l1};
        const Vec2 c{l2, l2};
        ASSERT_EQ(orientation(a, b, c), expected) << "case " << k;
        ASSERT_EQ(orientation(b, c, a), expected) << "case " << k;
        ASSERT_EQ(orientation(c, b, a), -expected) << "case " << k;
        // The same with the offset along x: a = (t, 0) lies on the other side.
        ASSERT_EQ(orientation(Vec2{t, 0}, b, c), -expected) << "case " << k;
    }
}

TEST(Orientation, AntisymmetricUnderSwapsOnRandomPoints) {
    const std::uint32_t seed = 3;
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> coord(-1.0, 1.0);
    for (int k = 0; k < 20000; ++k) {
        const Vec2 a{coord(rng), coord(rng)};
        const Vec2 b{coord(rng), coord(rng)};
        // c on the segment ab up to rounding: the hard case for a filter.
        const double s = coord(rng);
        const Vec2 c = a + s * (b - a);
        const int o = orientation(a, b, c);
        ASSERT_EQ(orientation(b, c, a), o);
        ASSERT_EQ(orientation(c, a, b), o);
        ASSERT_EQ(orientation(b, a, c), -o);
        ASSERT_EQ(orientation(a, c, b), -o);
    }
}

/// Independent oracle for integer segments: solve p1 + λ·d1 = p3 + μ·d2 with Cramer's rule in
/// exact integers and check λ, μ in [0, 1]; parallel and degenerate segments by projection.
bool intersect_rational(const std::int64_t s[4], const std::int64_t t[4]) {
    const std::int64_t d1x = s[2] - s[0], d1y = s[3] - s[1];
    const std::int64_t d2x = t[2] - t[0], d2y = t[3] - t[1];
    const std::int64_t ex = t[0] - s[0], ey = t[1] - s[1];
    const std::int64_t denom = d1x * d2y - d1y * d2x;
    if (denom != 0) {
        std::int64_t num_l = ex * d2y - ey * d2x;  // λ = num_l / denom
        std::int64_t num_m = ex * d1y - ey * d1x;  // μ = num_m / denom
        std::int64_t den = denom;
        if (den < 0) {
            den = -den;
            num_l = -num_l;
            num_m = -num_m;
        }
        return num_l >= 0 && num_l <= den && num_m >= 0 && num_m <= den;
    }
    auto on_segment = [](std::int64_t px, std::int64_t py, const std::int64_t seg[4]) {
        const std::int64_t dx = seg[2] - seg[0], dy = seg[3] - seg[1];
        const std::int64_t wx = px - seg[0], wy = py - seg[1];
        if (dx * wy - dy * wx != 0) return false;
        const std::int64_t along = dx * wx + dy * wy;
        if (dx == 0 && dy == 0) return wx == 0 && wy == 0;
        return along >= 0 && along <= dx * dx + dy * dy;
    };
    // Parallel (or degenerate): they meet iff an endpoint of one lies on the other.
    return on_segment(t[0], t[1], s) || on_segment(t[2], t[3], s) || on_segment(s[0], s[1], t) ||
           on_segment(s[2], s[3], t);
}

Segment to_segment(const std::int64_t s[4]) {
    return {{double(s[0]), double(s[1])}, {double(s[2]), double(s[3])}};
}

TEST(SegmentsIntersect, ExactCases) {
    const Segment diagonal{{0, 0}, {2, 2}};
    EXPECT_TRUE(segments_intersect(diagonal, {{0, 2}, {2, 0}}));    // proper crossing
    EXPECT_TRUE(segments_intersect(diagonal, {{1, 1}, {3, 0}}));    // touching in the interior
    EXPECT_TRUE(segments_intersect(diagonal, {{2, 2}, {3, 0}}));    // shared endpoint
    EXPECT_TRUE(segments_intersect(diagonal, {{1, 1}, {3, 3}}));    // collinear overlap
    EXPECT_TRUE(segments_intersect(diagonal, {{2, 2}, {3, 3}}));    // collinear, end to end
    EXPECT_TRUE(segments_intersect(diagonal, {{-1, -1}, {3, 3}}));  // one contains the other
    EXPECT_FALSE(segments_intersect(diagonal, {{3, 3}, {4, 4}}));   // collinear, apart
    EXPECT_FALSE(segments_intersect(diagonal, {{1, 0}, {3, 2}}));   // parallel
    EXPECT_FALSE(segments_intersect(diagonal, {{2, 0}, {3, -1}}));
    // Vertical and horizontal.
    EXPECT_TRUE(segments_intersect({{1, -1}, {1, 1}}, {{0, 0}, {2, 0}}));
    EXPECT_TRUE(segments_intersect({{1, 0}, {1, 1}}, {{0, 0}, {2, 0}}));
    EXPECT_FALSE(segments_intersect({{1, 0.5}, {1, 1}}, {{0, 0}, {2, 0}}));
    EXPECT_TRUE(segments_intersect({{1, 0}, {1, 2}}, {{1, 1}, {1, 3}}));
    // Degenerate segments (points).
    EXPECT_TRUE(segments_intersect({{1, 1}, {1, 1}}, diagonal));
    EXPECT_FALSE(segments_intersect({{1, 1.5}, {1, 1.5}}, diagonal));
    EXPECT_TRUE(segments_intersect({{1, 1}, {1, 1}}, {{1, 1}, {1, 1}}));
    EXPECT_FALSE(segments_intersect({{1, 1}, {1, 1}}, {{1, 2}, {1, 2}}));
}

TEST(SegmentsIntersect, ExactForEndpointsOneUlpFromTheOtherSegment) {
    // Far from the origin the line y = x through (L, L) and (3L, 3L): an endpoint at (2L, 2L) is on
    // it, one ulp above is not, whatever the rounding of a naive computation would say.
    const double l = std::ldexp(1.0, 60);
    const Segment line{{l, l}, {3 * l, 3 * l}};
    const double above = std::nextafter(2 * l, 4 * l);
    EXPECT_TRUE(segments_intersect(line, {{2 * l, 2 * l}, {2 * l, 5 * l}}));
    EXPECT_FALSE(segments_intersect(line, {{2 * l, above}, {2 * l, 5 * l}}));
    EXPECT_FALSE(segments_intersect(line, {{2 * l, above}, {0, 5 * l}}));
    const Segment unit{{0, 0}, {1, 1}};
    EXPECT_TRUE(segments_intersect(unit, {{0.5, 0.5}, {0.5, 2}}));
    EXPECT_FALSE(segments_intersect(unit, {{0.5, std::nextafter(0.5, 1.0)}, {0.5, 2}}));
    EXPECT_TRUE(segments_intersect(unit, {{0.5, std::nextafter(0.5, 0.0)}, {0.5, 2}}));
}

TEST(SegmentsIntersect, AgreesWithRationalOracleOnGridSegments) {
    // A 5×5 grid makes collinear, touching, vertical and degenerate pairs common.
    const std::uint32_t seed = 11;
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::int64_t> coord(0, 4);
    int hits = 0;
    for (int k = 0; k < 50000; ++k) {
        std::int64_t s[4];
        std::int64_t t[4];
        for (auto& v : s) v = coord(rng);
        for (auto& v : t) v = coord(rng);
        const bool expected = intersect_rational(s, t);
        ASSERT_EQ(segments_intersect(to_segment(s), to_segment(t)), expected)
            << "case " << k << ": (" << s[0] << "," << s[1] << ")-(" << s[2] << "," << s[3]
            << ") and (" << t[0] << "," << t[1] << ")-(" << t[2] << "," << t[3] << ")";
        ASSERT_EQ(segments_intersect(to_segment(t), to_segment(s)), expected) << "case " << k;
        hits += expected;
    }
    EXPECT_GT(hits, 10000);
    EXPECT_LT(hits, 40000);
}

}  // namespace
}  // namespace slc
