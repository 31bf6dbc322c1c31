// Tests of validate.hpp: find_crossing on exact cases and against an O(N²) oracle on thousands of
// seeded random interfaces (simple stars, perturbed stars, grid polygons full of collinear,
// vertical and touching segments); prepare_interface's errors, messages, duplicates and
// orientation.
#include "slc/geometry/validate.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/geometry/predicates.hpp"
#include "slc/geometry/segment.hpp"

namespace slc {
namespace {

using Curves = std::vector<std::vector<Vec2>>;

// ---------------------------------------------------------------------------------------------
// The oracle: every pair of segments.

/// Segments i and j meet where they should not: anywhere, unless they are consecutive on a curve
/// and meet only at their shared vertex (they overlap beyond it exactly when the curve turns
/// back: the three vertices are collinear and the outer two lie on the same side of the middle).
bool is_crossing_pair(const Interface& curves, std::size_t i, std::size_t j) {
    if (!segments_intersect(curves.segment(i), curves.segment(j))) return false;
    if (curves.next(j) == i) std::swap(i, j);
    if (curves.next(i) != j) return true;
    const Vec2 p = curves.point(i);
    const Vec2 q = curves.point(j);
    const Vec2 r = curves.point(curves.next(j));
    // For collinear points the rounded differences keep their signs, so the dot product's sign
    // is exact.
    return p != q && r != q && orientation(p, q, r) == 0 && dot(p - q, r - q) > 0;
}

bool has_crossing_brute_force(const Interface& curves) {
    for (std::size_t j = 0; j < curves.size(); ++j) {
        for (std::size_t i = 0; i < j; ++i) {
            if (is_crossing_pair(curves, i, j)) return true;
        }
    }
    return false;
}

/// Compares find_crossing with the oracle; returns whether there is a crossing.
bool expect_agrees_with_oracle(const Curves& input) {
    const Interface curves(input);
    const bool expected = has_crossing_brute_force(curves);
    const std::optional<Crossing> found = find_crossing(curves);
    EXPECT_EQ(found.has_value(), expected);
    if (found) {
        EXPECT_LT(found->first, found->second);
        EXPECT_LT(found->second, curves.size());
        EXPECT_TRUE(is_crossing_pair(curves, found->first, found->second))
            << "reported segments " << found->first << " and " << found->second;
    }
    return expected;
}

// ---------------------------------------------------------------------------------------------
// Random interfaces.

/// A star-shaped polygon: n ≥ 8 vertices at increasing angles, gaps under 1.5·2π/n < π, so it
/// is simple; the disc of radius r_min·cos(1.5·π/n) ≥ 0.83·r_min about the centre lies inside.
std::vector<Vec2> random_star(std::mt19937& rng, Vec2 center, double r_min, double r_max, int n) {
    std::uniform_real_distribution<double> jitter(0.0, 0.5);
    std::uniform_real_distribution<double> radius(r_min, r_max);
    std::vector<Vec2> star;
    for (int k = 0; k < n; ++k) {
        const double angle = 2 * std::numbers::pi * (k + jitter(rng)) / n;
        const double r = radius(rng);
        star.push_back(center + r * Vec2{std::cos(angle), std::sin(angle)});
    }
    return star;
}

/// Disjoint stars in the cells of a row, some holding a smaller star inside (a hole): the inner
/// star reaches 0.35, the outer one's inscribed disc at least 0.83·0.5 > 0.41.
Curves random_simple_stars(std::mt19937& rng) {
    std::uniform_int_distribution<int> count(1, 3);
    std::uniform_int_distribution<int> size(8, 24);
    std::bernoulli_distribution nested(0.5);
    Curves curves;
    const int cells = count(rng);
    for (int c = 0; c < cells; ++c) {
        const Vec2 center{2.0 * c, 0.0};
        curves.push_back(random_star(rng, center, 0.5, 0.99, size(rng)));
        if (nested(rng)) curves.push_back(random_star(rng, center, 0.1, 0.35, size(rng)));
    }
    return curves;
}

/// Moves one to three vertices of simple stars anywhere nearby: often a crossing, not always.
Curves random_perturbed_stars(std::mt19937& rng) {
    Curves curves = random_simple_stars(rng);
    std::uniform_int_distribution<int> moves(1, 3);
    std::uniform_real_distribution<double> coord(-1.0, 1.0);
    for (int m = moves(rng); m > 0; --m) {
        auto& curve = curves[std::uniform_int_distribution<std::size_t>(0, curves.size() - 1)(rng)];
        Vec2& v = curve[std::uniform_int_distribution<std::size_t>(0, curve.size() - 1)(rng)];
        v += 0.6 * Vec2{coord(rng), coord(rng)};
    }
    return curves;
}

/// A star with integer vertices (radii and angles snapped to a grid), so that collinear
/// segments, vertical segments and shared vertices are common.
std::vector<Vec2> random_grid_star(std::mt19937& rng, Vec2 center, int r_max) {
    std::uniform_int_distribution<int> size(3, 9);
    std::uniform_int_distribution<int> radius(1, r_max);
    const int n = size(rng);
    std::vector<Vec2> star;
    for (int k = 0; k < n; ++k) {
        const double angle = 2 * std::numbers::pi * k / n;
        const double r = radius(rng);
        star.push_back(center +
                       Vec2{std::round(r * std::cos(angle)), std::round(r * std::sin(angle))});
    }
    return star;
}

/// A histogram: a rectilinear polygon of columns of random integer heights; its vertical sides
/// share x coordinates and equal heights make collinear consecutive segments.
std::vector<Vec2> random_histogram(std::mt19937& rng, Vec2 origin) {
    std::uniform_int_distribution<int> columns(1, 5);
    std::uniform_int_distribution<int> height(1, 3);
    std::vector<Vec2> poly{origin};
    const int n = columns(rng);
    for (int k = 0; k < n; ++k) {
        const double h = height(rng);
        poly.push_back(origin + Vec2{double(k), h});
        poly.push_back(origin + Vec2{double(k + 1), h});
    }
    poly.push_back(origin + Vec2{double(n), 0});
    return poly;
}

/// Random vertices on a small grid, consecutive ones sometimes equal (segments of zero length).
std::vector<Vec2> random_grid_polygon(std::mt19937& rng, int grid) {
    std::uniform_int_distribution<int> size(3, 7);
    std::uniform_int_distribution<int> coord(0, grid - 1);
    std::vector<Vec2> poly;
    for (int n = size(rng); n > 0; --n) poly.push_back({double(coord(rng)), double(coord(rng))});
    return poly;
}

/// Exact symmetries of the plane, so that every configuration is also seen turned on its side
/// (vertical becomes horizontal), mirrored, reversed and started at another vertex.
void randomly_transform(std::mt19937& rng, Curves& curves) {
    std::bernoulli_distribution coin(0.5);
    const bool swap_xy = coin(rng);
    const bool mirror = coin(rng);
    for (auto& curve : curves) {
        for (Vec2& p : curve) {
            if (swap_xy) std::swap(p.x, p.y);
            if (mirror) p.x = -p.x;
        }
        if (coin(rng)) std::reverse(curve.begin(), curve.end());
        const auto shift = std::uniform_int_distribution<std::size_t>(0, curve.size() - 1)(rng);
        std::rotate(curve.begin(), curve.begin() + static_cast<std::ptrdiff_t>(shift), curve.end());
    }
}

/// A family of random interfaces: a name and how to draw one.
struct Family {
    const char* name;
    Curves (*draw)(std::mt19937&);
};

Curves draw_grid_stars(std::mt19937& rng) {
    std::uniform_int_distribution<int> count(1, 3);
    std::uniform_int_distribution<int> offset(-2, 6);
    Curves curves;
    for (int c = count(rng); c > 0; --c) {
        curves.push_back(random_grid_star(rng, {double(offset(rng)), double(offset(rng))}, 4));
    }
    return curves;
}

Curves draw_histograms(std::mt19937& rng) {
    std::uniform_int_distribution<int> count(1, 3);
    std::uniform_int_distribution<int> offset(-1, 6);
    Curves curves;
    for (int c = count(rng); c > 0; --c) {
        curves.push_back(random_histogram(rng, {double(offset(rng)), double(offset(rng))}));
    }
    return curves;
}

Curves draw_grid_polygons(std::mt19937& rng) {
    std::uniform_int_distribution<int> count(1, 2);
    std::uniform_int_distribution<int> grid(3, 8);
    Curves curves;
    for (int c = count(rng); c > 0; --c) curves.push_back(random_grid_polygon(rng, grid(rng)));
    return curves;
}

/// Two grid stars, the second moved so that one of its vertices lands on one of the first's.
Curves draw_touching_stars(std::mt19937& rng) {
    Curves curves{random_grid_star(rng, {0, 0}, 4), random_grid_star(rng, {0, 0}, 4)};
    const Vec2 target =
        curves[0][std::uniform_int_distribution<std::size_t>(0, curves[0].size() - 1)(rng)];
    const Vec2 source =
        curves[1][std::uniform_int_distribution<std::size_t>(0, curves[1].size() - 1)(rng)];
    for (Vec2& p : curves[1]) p += target - source;
    return curves;
}

// ---------------------------------------------------------------------------------------------
// find_crossing: exact cases.

std::optional<Crossing> crossing_of(const Curves& input) { return find_crossing(Interface(input)); }

TEST(FindCrossing, NoneForEmptyInterface) { EXPECT_FALSE(find_crossing(Interface()).has_value()); }

TEST(FindCrossing, NoneForConsecutiveSegmentsMeetingAtTheirVertex) {
    EXPECT_FALSE(crossing_of({{{0, 0}, {1, 0}, {0, 1}}}).has_value());
    EXPECT_FALSE(crossing_of({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}).has_value());
    // Collinear consecutive segments that go on (do not fold back) are fine.
    EXPECT_FALSE(crossing_of({{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {0, 1}}}).has_value());
    EXPECT_FALSE(crossing_of({{{0, 0}, {0, 1}, {0, 2}, {-1, 1}}}).has_value());
}

TEST(FindCrossing, FindsBowTie) {
    const auto c = crossing_of({{{0, 0}, {1, 1}, {1, 0}, {0, 1}}});
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(c->first, 0u);
    EXPECT_EQ(c->second, 2u);
}

TEST(FindCrossing, FindsCurveFoldingBackOnItself) {
    // Segment 1 runs back along segment 0.
    const auto fold = crossing_of({{{0, 0}, {2, 0}, {1, 0}, {1, 1}}});
    ASSERT_TRUE(fold.has_value());
    EXPECT_EQ(fold->first, 0u);
    EXPECT_EQ(fold->second, 1u);
    // Three collinear vertices: the closing segment runs back over both others.
    EXPECT_TRUE(crossing_of({{{0, 0}, {1, 0}, {2, 0}}}).has_value());
    // Vertical spike.
    EXPECT_TRUE(crossing_of({{{0, 0}, {2, 0}, {2, 2}, {2, 1}, {0, 1}}}).has_value());
}

TEST(FindCrossing, FindsCurveTouchingItselfAtAVertex) {
    // Two triangles joined at (1, 1), traversed as one curve.
    const auto c = crossing_of({{{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}}});
    ASSERT_TRUE(c.has_value());
    EXPECT_TRUE(is_crossing_pair(Interface({{{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}}}),
                                 c->first, c->second));
}

TEST(FindCrossing, FindsVertexLyingInsideAnotherSegment) {
    // Vertex (1, 0) of the inner dent lies on the bottom side of the same curve.
    EXPECT_TRUE(crossing_of({{{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}}}).has_value());
    // A vertical side touched by another curve's vertex.
    EXPECT_TRUE(
        crossing_of({{{0, 0}, {1, 0}, {1, 2}, {0, 2}}, {{1, 1}, {2, 0}, {2, 2}}}).has_value());
}

TEST(FindCrossing, FindsCurvesTouchingAtAVertex) {
    const auto c = crossing_of({{{0, 0}, {1, 0}, {1, 1}}, {{1, 1}, {2, 1}, {2, 2}}});
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(c->first, 1u);   // (1, 0)–(1, 1)
    EXPECT_EQ(c->second, 3u);  // (1, 1)–(2, 1)
}

TEST(FindCrossing, FindsCollinearOverlapOfCurves) {
    // Two unit squares sharing part of a vertical side.
    EXPECT_TRUE(
        crossing_of({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{1, 0.5}, {2, 0.5}, {2, 2}, {1, 2}}})
            .has_value());
    // Sharing part of a horizontal side.
    EXPECT_TRUE(crossing_of({{{0, 0}, {2, 0}, {2, 1}, {0, 1}}, {{1, -1}, {3, -1}, {3, 0}, {1, 0}}})
                    .has_value());
}

TEST(FindCrossing, NoneForNestedAndSideBySideCurvesSharingCoordinates) {
    // A comb of vertical teeth, a square inside one tooth and a square beside it, sharing x and y
    // coordinates with the comb without touching it.
    const std::vector<Vec2> comb{{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                                 {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
    const Curves curves{
        comb, {{0.25, 1}, {0.75, 1}, {0.75, 2}, {0.25, 2}}, {{6, 0}, {7, 0}, {7, 3}, {6, 3}}};
    EXPECT_FALSE(crossing_of(curves).has_value());
    EXPECT_FALSE(expect_agrees_with_oracle(curves));
}

TEST(FindCrossing, FindsCrossingInLargeStar) {
    // 100 000 vertices: a quadratic search would take minutes; the sweep takes milliseconds.
    const std::uint32_t seed = 5;
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    Curves curves{random_star(rng, {0, 0}, 0.5, 1.0, 100000)};
    EXPECT_FALSE(crossing_of(curves).has_value());
    // Pull one vertex through the centre and out the other side.
    curves[0][50000] = -1.5 * curves[0][50000];
    const auto c = crossing_of(curves);
    ASSERT_TRUE(c.has_value());
    EXPECT_TRUE(is_crossing_pair(Interface(curves), c->first, c->second));
}

// ---------------------------------------------------------------------------------------------
// find_crossing against the oracle.

TEST(FindCrossing, AgreesWithBruteForceOnRandomInterfaces) {
    const Family families[] = {
        {"simple stars", random_simple_stars}, {"perturbed stars", random_perturbed_stars},
        {"grid stars", draw_grid_stars},       {"histograms", draw_histograms},
        {"grid polygons", draw_grid_polygons}, {"touching stars", draw_touching_stars},
    };
    constexpr int cases_per_family = 2000;
    for (const Family& family : families) {
        int crossing = 0;
        for (int k = 0; k < cases_per_family; ++k) {
            const std::uint32_t seed = 1000u * 1000u + static_cast<std::uint32_t>(k);
            SCOPED_TRACE(testing::Message() << family.name << ", seed " << seed);
            std::mt19937 rng(seed);
            Curves curves = family.draw(rng);
            randomly_transform(rng, curves);
            crossing += expect_agrees_with_oracle(curves);
            if (testing::Test::HasFailure()) return;  // one seed to reproduce is enough
        }
        // Each family must exercise the outcome it is meant to.
        const std::string name = family.name;
        if (name == "simple stars") {
            EXPECT_EQ(crossing, 0) << name;
        } else if (name == "touching stars") {
            EXPECT_EQ(crossing, cases_per_family) << name;
        } else {
            EXPECT_GT(crossing, cases_per_family / 10) << name;
            EXPECT_LT(crossing, cases_per_family * 9 / 10) << name;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// prepare_interface.

/// The message of the InvalidInput that prepare_interface throws, or "" if it does not throw.
std::string error_of(const Curves& raw, const std::optional<Box>& domain = std::nullopt) {
    try {
        prepare_interface(raw, domain);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

const Curves unit_square{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
const std::vector<Vec2> square_ccw{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
const std::vector<Vec2> hole_cw{{-0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}, {0.5, -0.5}};

TEST(Interface, AreaAndLengthOfOneCurveAndOfAll) {
    EXPECT_EQ(signed_area(square_ccw), 4.0);
    EXPECT_EQ(signed_area(hole_cw), -1.0);
    EXPECT_EQ(length(square_ccw), 8.0);  // the closing segment counted
    EXPECT_EQ(length(hole_cw), 4.0);
    const Interface both({square_ccw, hole_cw});
    EXPECT_EQ(area(both), 3.0);
    EXPECT_EQ(length(both), 12.0);
}

TEST(PrepareInterface, RejectsEmptyInput) {
    EXPECT_EQ(error_of({}), "no curves: the interface is empty");
}

TEST(PrepareInterface, RejectsNonFiniteCoordinateNamingCurveAndVertex) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(error_of({{{0, 0}, {1, 0}, {1, 1}, {nan, 1}}}),
              "curve 0, vertex 3: coordinate is not finite (nan)");
    EXPECT_EQ(error_of({square_ccw, {{0, 0}, {1, -inf}, {1, 1}}}),
              "curve 1, vertex 1: coordinate is not finite (-inf)");
}

TEST(PrepareInterface, RejectsPointOutsideDomain) {
    EXPECT_EQ(error_of({square_ccw, {{3, 0}, {4, 0}, {4, 1}}}, Box::centered_square(2)),
              "curve 1, vertex 0: point (3, 0) lies outside the domain [-2, 2]x[-2, 2]");
    // The domain is closed: its boundary is inside.
    EXPECT_EQ(error_of({{{-2, -2}, {2, -2}, {2, 2}}}, Box::centered_square(2)), "");
}

TEST(PrepareInterface, RejectsCurveWithFewerThanThreeDistinctPoints) {
    EXPECT_EQ(error_of({square_ccw, {{0, 0}, {1, 0}, {1, 0}, {0, 0}}}),
              "curve 1 has 2 distinct points; a closed curve needs at least 3");
    EXPECT_EQ(error_of({{}}), "curve 0 has 0 distinct points; a closed curve needs at least 3");
    EXPECT_EQ(error_of({{{1, 1}, {1, 1}, {1, 1}}}),
              "curve 0 has 1 distinct points; a closed curve needs at least 3");
}

TEST(PrepareInterface, RejectsCoordinatesBeyondTheLimit) {
    EXPECT_EQ(error_of({{{0, 0}, {1e101, 0}, {0, 1}}}),
              "curve 0, vertex 1: point (1e+101, 0) is beyond the coordinate limit ±1e+100");
    EXPECT_EQ(error_of({{{0, 0}, {1e100, 0}, {0, -1e100}}}), "");
}

TEST(PrepareInterface, SaysWhenDistinctPointsMergeAtTheScaleOfTheDomain) {
    // Three different points closer than 1e-12 of the domain's width are one.
    EXPECT_EQ(error_of({{{0, 0}, {1e-14, 0}, {0, 1e-14}}}, Box::centered_square(1)),
              "curve 0 has 1 distinct points (points closer than 2e-12 are one at this scale); a "
              "closed curve needs at least 3");
}

TEST(PrepareInterface, RejectsSelfCrossingCurve) {
    EXPECT_EQ(error_of({square_ccw, {{5, 5}, {6, 6}, {6, 5}, {5, 6}}}),
              "curve 1 crosses itself: segment 0 meets segment 2");
}

TEST(PrepareInterface, RejectsCurvesCrossingEachOther) {
    // The right side of the square (segment 1) meets two sides of the triangle; either may be
    // named.
    EXPECT_THAT(error_of({square_ccw, {{0, 0}, {3, 0}, {3, 0.5}}}),
                testing::MatchesRegex("curve 0 crosses curve 1 \\(segment 1 of curve 0 meets "
                                      "segment [02] of curve 1\\)"));
}

TEST(PrepareInterface, NamesSegmentsByInputVertexAfterDroppingDuplicates) {
    // The bow tie with vertex 1 repeated: its segments start at input vertices 0, 1, 3 and 4.
    EXPECT_EQ(error_of({{{0, 0}, {1, 1}, {1, 1}, {1, 0}, {0, 1}}}),
              "curve 0 crosses itself: segment 0 meets segment 3");
}

TEST(PrepareInterface, ChecksInTheOrderOfTheHeader) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // A point outside the domain in curve 0 and a NaN in curve 1: non-finite comes first.
    EXPECT_EQ(
        error_of({{{5, 0}, {1, 0}, {1, 1}}, {{0, 0}, {nan, 0}, {1, 1}}}, Box::centered_square(2)),
        "curve 1, vertex 1: coordinate is not finite (nan)");
    // A crossing in curve 0 and too few points in curve 1: the count comes first.
    EXPECT_EQ(error_of({{{0, 0}, {1, 1}, {1, 0}, {0, 1}}, {{5, 5}, {6, 6}}}),
              "curve 1 has 2 distinct points; a closed curve needs at least 3");
}

TEST(PrepareInterface, DropsConsecutiveAndClosingDuplicates) {
    const PreparedInterface p = prepare_interface(
        {{{0, 0}, {0, 0}, {1, 0}, {1, 1}, {1, 1}, {1, 1}, {0, 1}, {0, 0}, {0, 0}}});
    EXPECT_EQ(p.curves.curves(), unit_square);
    EXPECT_TRUE(p.notes.empty());
}

TEST(PrepareInterface, DropsPointsCloserThanTheDuplicateTolerance) {
    // The tolerance is tolerance::duplicate_point times the domain width (4 here): a point a
    // quarter of it away is the same point, one a thousand tolerances away is not.
    const Box domain = Box::centered_square(2);
    const double tol = tolerance::duplicate_point * domain.width();
    const PreparedInterface same =
        prepare_interface({{{0, 0}, {0.25 * tol, 0}, {1, 0}, {1, 1}, {0, 1}}}, domain);
    EXPECT_EQ(same.curves.curves(), unit_square);
    const PreparedInterface kept =
        prepare_interface({{{0, 0}, {1000 * tol, 0}, {1, 0}, {1, 1}, {0, 1}}}, domain);
    EXPECT_EQ(kept.curves.size(), 5u);
}

TEST(PrepareInterface, ReversesClockwiseOuterCurveWithNote) {
    std::vector<Vec2> clockwise(square_ccw.rbegin(), square_ccw.rend());
    const PreparedInterface p = prepare_interface({clockwise});
    ASSERT_EQ(p.notes.size(), 1u);
    EXPECT_EQ(p.notes[0], "curve 0 was clockwise; reoriented counterclockwise");
    EXPECT_GT(signed_area(p.curves.curve(0)), 0.0);
}

TEST(PrepareInterface, ReversesCounterclockwiseHoleWithNote) {
    std::vector<Vec2> hole_ccw(hole_cw.rbegin(), hole_cw.rend());
    const PreparedInterface p = prepare_interface({square_ccw, hole_ccw});
    ASSERT_EQ(p.notes.size(), 1u);
    EXPECT_EQ(p.notes[0], "curve 1 is a hole and was counterclockwise; reoriented clockwise");
    EXPECT_EQ(p.curves.curves(), (Curves{square_ccw, hole_cw}));
}

TEST(PrepareInterface, KeepsIslandInsideHoleCounterclockwise) {
    const std::vector<Vec2> island{{-0.25, -0.25}, {0.25, -0.25}, {0.25, 0.25}, {-0.25, 0.25}};
    std::vector<Vec2> island_cw(island.rbegin(), island.rend());
    const PreparedInterface p = prepare_interface({island_cw, square_ccw, hole_cw});
    ASSERT_EQ(p.notes.size(), 1u);
    EXPECT_EQ(p.notes[0], "curve 0 was clockwise; reoriented counterclockwise");
    EXPECT_EQ(p.curves.curves(), (Curves{island, square_ccw, hole_cw}));
}

TEST(PrepareInterface, PassesValidInputUntouched) {
    const Curves input{square_ccw, hole_cw, {{2, 2}, {3, 2}, {2.5, 3}}};
    const PreparedInterface p = prepare_interface(input, Box::centered_square(4));
    EXPECT_EQ(p.curves.curves(), input);
    EXPECT_TRUE(p.notes.empty());
}

TEST(PrepareInterface, HandlesExtremeCoordinateScales) {
    // Nothing overflows at the coordinate limit or underflows near the smallest double: the
    // predicates are exact and the duplicate tolerance is computed from half-widths.
    for (const double s : {tolerance::max_coordinate, 1e-300}) {
        const Curves input{{{-s, -s}, {s, -s}, {s, s}, {-s, s}},
                           {{-s / 2, -s / 2}, {-s / 2, s / 2}, {s / 2, s / 2}, {s / 2, -s / 2}}};
        const PreparedInterface p = prepare_interface(input);
        EXPECT_EQ(p.curves.curves(), input) << "scale " << s;
        EXPECT_TRUE(p.notes.empty()) << "scale " << s;
        const Curves reversed{{input[0].rbegin(), input[0].rend()}, input[1]};
        EXPECT_EQ(prepare_interface(reversed).notes.size(), 1u) << "scale " << s;
    }
}

TEST(PrepareInterface, OrientsRandomNestedStarsByNestingDepth) {
    // A point this far left of the middle of a segment lies inside the interface exactly when
    // the curve is oriented right: in random_simple_stars curves are at least 0.06 apart and
    // sides longer than 0.05, so no other segment comes this close to the middle of a side.
    constexpr double step_inside = 1e-6;
    for (int k = 0; k < 500; ++k) {
        const std::uint32_t seed = 4242u + static_cast<std::uint32_t>(k);
        SCOPED_TRACE(testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        Curves curves = random_simple_stars(rng);
        randomly_transform(rng, curves);
        const PreparedInterface p = prepare_interface(curves);
        for (std::size_t c = 0; c < p.curves.curve_count(); ++c) {
            ASSERT_EQ(p.curves.curve(c).size(), curves[c].size());
            for (std::size_t i = p.curves.offsets()[c]; i < p.curves.offsets()[c + 1]; ++i) {
                const Segment s = p.curves.segment(i);
                const Vec2 left =
                    0.5 * (s.a + s.b) + step_inside * perp(s.b - s.a) / norm(s.b - s.a);
                ASSERT_TRUE(is_inside_even_odd(p.curves, left))
                    << "curve " << c << ", segment " << i;
            }
        }
    }
}

}  // namespace
}  // namespace slc
