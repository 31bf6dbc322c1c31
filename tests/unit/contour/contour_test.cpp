// Tests of contour() (paper §2) on analytic functions: circles, ellipses, several components, a
// hole, nearly touching circles, zeros on tree vertices, no zero, the boundary and ill-posed
// errors, option validation, evaluation counting and thread independence.
#include "slc/contour/contour.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <utility>

#include "contour_checks.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/tree/triangulation.hpp"

namespace slc {
namespace {

using testing::expect_outside_on_right;
using testing::expect_simple;
using testing::residuals;

const Box unit_domain = Box::centered_square(1.0);
/// Root-finding tolerance of every test: the library default.
constexpr double eta = 1e-10;
constexpr double pi = std::numbers::pi;
/// Area tolerance after two or three refinement passes at K = 6: the chords' sagitta is then
/// below about 1e−4 (cells 1/32, three halvings), and the enclosed area moves by at most
/// perimeter (< 4 per curve here) × sagitta, so 1e−3 is safe and still catches a lost arc.
constexpr double refined_area_tolerance = 1e-3;

/// Signed distance to the circle of radius r about c: exact, |∇G| = 1.
auto circle(Vec2 c, double r) {
    return [=](Vec2 p) { return distance(p, c) - r; };
}

ContourOptions options(int depth, int passes, std::optional<double> eps = std::nullopt) {
    ContourOptions o;
    o.depth = depth;
    o.refine_passes = passes;
    o.eps = eps;
    return o;
}

TEST(Contour, CircleIsOneCounterclockwiseCurveWithVerticesWithinEta) {
    const auto g = pointwise(circle({0.1, -0.05}, 0.6));
    const ContourResult r = contour(g, unit_domain, options(5, 0));
    ASSERT_EQ(r.curves.curve_count(), 1u);
    // Chords of a circle of radius R and length ≤ L enclose πR² less O(L²) of area; L ≤ the
    // finest cell diagonal 2·2^−5·√2 ≈ 0.09, so 1% is generous and still catches a lost arc.
    EXPECT_NEAR(signed_area(r.curves.curve(0)), pi * 0.36, 0.01 * pi * 0.36);
    EXPECT_LE(residuals(r.curves, g).vertices, eta);
    expect_simple(r.curves);
    expect_outside_on_right(r.curves, g, 0.25);
    EXPECT_EQ(r.stats.vertices, r.curves.size());
    EXPECT_EQ(r.stats.cells, r.tree.size());
    EXPECT_FALSE(r.stats.max_midpoint_value.has_value());
}

TEST(Contour, RefinementBringsEveryMidpointWithinEps) {
    const auto g = pointwise(circle({0.1, -0.05}, 0.6));
    for (double eps : {1e-3, 1e-5, 1e-7}) {
        SCOPED_TRACE(::testing::Message() << "eps " << eps);
        const ContourResult r =
            contour(g, unit_domain, options(4, ContourOptions::until_converged, eps));
        const auto res = residuals(r.curves, g);
        // G is the exact distance, so these are the contour's errors, with no slack: the library
        // evaluated the same G at the same midpoints.
        EXPECT_LE(res.vertices, eta);
        EXPECT_LE(res.midpoints, eps);
        ASSERT_TRUE(r.stats.max_midpoint_value.has_value());
        EXPECT_EQ(*r.stats.max_midpoint_value, res.midpoints);
        EXPECT_EQ(r.stats.rejected, 0u);
        expect_simple(r.curves);
        expect_outside_on_right(r.curves, g, 0.25);
    }
}

TEST(Contour, FixedPassesStopEarlyWhenConverged) {
    const auto g = pointwise(circle({0.0, 0.0}, 0.5));
    const ContourResult r = contour(g, unit_domain, options(5, 50, 1e-4));
    EXPECT_LT(r.stats.passes, 50);
    EXPECT_LE(residuals(r.curves, g).midpoints, 1e-4);
}

TEST(Contour, EllipseOfANonDistanceFunctionIsWithinEtaAndEps) {
    // G = x²/a² + y²/b² − 1 is no distance (|∇G| from 2/a·… varies by a factor 4 on the curve):
    // the tree needs a larger γ and the brackets must work from G alone.
    const double a = 0.8, b = 0.3;
    const auto g =
        pointwise([=](Vec2 p) { return p.x * p.x / (a * a) + p.y * p.y / (b * b) - 1.0; });
    const ContourResult r =
        contour(g, unit_domain, options(6, ContourOptions::until_converged, 1e-6));
    ASSERT_EQ(r.curves.curve_count(), 1u);
    const auto res = residuals(r.curves, g);
    EXPECT_LE(res.vertices, eta);
    EXPECT_LE(res.midpoints, 1e-6);
    // |G| ≤ 1e-6 at the midpoints bounds the chords' sagitta by about 1e-6·b/2; the polygon's
    // area is within perimeter × sagitta ≈ 1e-5 of πab.
    EXPECT_NEAR(signed_area(r.curves.curve(0)), pi * a * b, 1e-4);
    expect_simple(r.curves);
    expect_outside_on_right(r.curves, g, 0.25);
}

TEST(Contour, SeveralComponentsAreSeveralCounterclockwiseCurves) {
    const auto g = pointwise([](Vec2 p) {
        return std::min({distance(p, {-0.5, -0.5}) - 0.3, distance(p, {0.5, -0.4}) - 0.25,
                         distance(p, {0.0, 0.5}) - 0.35});
    });
    const ContourResult r = contour(g, unit_domain, options(6, 3));
    ASSERT_EQ(r.curves.curve_count(), 3u);
    double total = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
        EXPECT_GT(signed_area(r.curves.curve(c)), 0.0);
        total += signed_area(r.curves.curve(c));
    }
    EXPECT_NEAR(total, pi * (0.09 + 0.0625 + 0.1225), refined_area_tolerance);
    EXPECT_LE(residuals(r.curves, g).vertices, eta);
    expect_simple(r.curves);
    expect_outside_on_right(r.curves, g, 0.25);
}

TEST(Contour, HoleIsAClockwiseCurve) {
    // G < 0 in the annulus 0.3 < |x| < 0.7: outer circle counterclockwise, inner one clockwise.
    const auto g = pointwise([](Vec2 p) { return std::max(norm(p) - 0.7, 0.3 - norm(p)); });
    const ContourResult r = contour(g, unit_domain, options(6, 2));
    ASSERT_EQ(r.curves.curve_count(), 2u);
    std::vector<double> areas{signed_area(r.curves.curve(0)), signed_area(r.curves.curve(1))};
    std::sort(areas.begin(), areas.end());
    EXPECT_NEAR(areas[0], -pi * 0.09, refined_area_tolerance);
    EXPECT_NEAR(areas[1], pi * 0.49, refined_area_tolerance);
    EXPECT_NEAR(area(r.curves), pi * (0.49 - 0.09), 2.0 * refined_area_tolerance);
    expect_simple(r.curves);
    expect_outside_on_right(r.curves, g, 0.25);
}

TEST(Contour, NearlyTouchingCirclesGiveSimpleCurvesAtEveryResolution) {
    // Gaps from far below a cell to several cells: the linear interpolant may merge the circles
    // or not (paper Fig. 4), but the contour must stay simple, closed and within η, also after
    // refinement pushes vertices towards the true circles.
    for (double gap : {1e-6, 1e-3, 0.01, 0.05}) {
        const double r0 = 0.4;
        const auto g = pointwise([=](Vec2 p) {
            return std::min(distance(p, {-r0 - 0.5 * gap, 0.013}) - r0,
                            distance(p, {r0 + 0.5 * gap, 0.013}) - r0);
        });
        for (int depth = 3; depth <= 7; ++depth) {
            for (int passes : {0, 2, ContourOptions::until_converged}) {
                SCOPED_TRACE(::testing::Message()
                             << "gap " << gap << " K " << depth << " P " << passes);
                const ContourResult r = contour(g, unit_domain, options(depth, passes, 1e-6));
                EXPECT_GE(r.curves.curve_count(), 1u);
                EXPECT_LE(r.curves.curve_count(), 2u);
                EXPECT_LE(residuals(r.curves, g).vertices, eta);
                expect_simple(r.curves);
                if (gap > 4.0 * unit_domain.width() / (1 << depth)) {
                    EXPECT_EQ(r.curves.curve_count(), 2u);
                }
            }
        }
    }
}

TEST(Contour, ItsTriangulationIsTheOneTriangulateGivesItsTree) {
    // The contour numbers the triangulation's vertices from its table of samples, where a leaf's
    // edge midpoint is a vertex exactly where the neighbour across is finer; triangulate() asks
    // the tree for the neighbours. Graded trees: a distance, and a steep function for which γ is
    // doubled until the tree balances.
    const auto g = pointwise(circle({0.05, -0.02}, 0.33));
    const auto steep = pointwise([](Vec2 p) { return std::exp(12.0 * p.x) * (norm(p) - 0.3); });
    double largest_gamma = 0.0;
    for (const BatchFunctionRef f : {BatchFunctionRef(g), BatchFunctionRef(steep)}) {
        for (int depth = 3; depth <= 7; ++depth) {
            SCOPED_TRACE(::testing::Message() << "K " << depth);
            const ContourResult r = contour(f, unit_domain, options(depth, 0));
            EXPECT_EQ(r.stats.triangles, triangulate(r.tree).triangles.size());
            largest_gamma = std::max(largest_gamma, r.stats.gamma);
        }
    }
    EXPECT_GE(largest_gamma, 1024.0);  // the steep function's trees needed γ doubled
}

TEST(Contour, ZerosOnTreeVerticesArePerturbed) {
    // |x|² − 1/4 vanishes exactly at (±1/2, 0) and (0, ±1/2), which are tree vertices from K = 2
    // on; max(|x|, |y|) − 1/2 vanishes at every tree vertex on the square's sides.
    const auto circle_g = pointwise([](Vec2 p) { return p.x * p.x + p.y * p.y - 0.25; });
    const auto square_g =
        pointwise([](Vec2 p) { return std::max(std::abs(p.x), std::abs(p.y)) - 0.5; });
    for (int depth = 2; depth <= 6; ++depth) {
        SCOPED_TRACE(::testing::Message() << "K " << depth);
        const ContourResult c = contour(circle_g, unit_domain, options(depth, 1));
        EXPECT_GE(c.stats.perturbed, 4u);
        EXPECT_EQ(c.curves.curve_count(), 1u);
        EXPECT_LE(residuals(c.curves, circle_g).vertices, eta);
        expect_simple(c.curves);
        const ContourResult s = contour(square_g, unit_domain, options(depth, 2));
        EXPECT_GE(s.stats.perturbed, std::size_t{8} << (depth - 2));
        EXPECT_EQ(s.curves.curve_count(), 1u);
        EXPECT_GT(signed_area(s.curves.curve(0)), 0.0);
        EXPECT_LE(residuals(s.curves, square_g).vertices, eta);
        expect_simple(s.curves);
    }
}

// The resolution docs/contouring.md states: a component holding a disk of radius h/2, h the
// finest cell, holds a vertex or a centre of the finest triangulation (their lattice leaves no
// empty disk larger), so it is never lost. Seeded disks of radius 0.51 h all survive; at 0.3 h
// some fall between the samples, which shows the test measures the stated bound.
TEST(Contour, EveryComponentHoldingADiskOfHalfACellIsResolved) {
    constexpr int depth = 6;
    const double h = unit_domain.width() / (1 << depth);
    for (const double fraction : {0.51, 0.3}) {
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(-0.9, 0.9);
        std::vector<Vec2> centres;
        const double r = fraction * h;
        while (centres.size() < 120) {
            const Vec2 c{u(rng), u(rng)};
            if (std::none_of(centres.begin(), centres.end(),
                             [&](Vec2 o) { return distance(o, c) < 4.0 * h; }))
                centres.push_back(c);
        }
        const auto disks = pointwise([&](Vec2 p) {
            double d = std::numeric_limits<double>::infinity();
            for (Vec2 c : centres) d = std::min(d, distance(p, c) - r);
            return d;
        });
        const ContourResult res = contour(disks, unit_domain, options(depth, 0));
        SCOPED_TRACE(::testing::Message() << "r = " << fraction << " h");
        if (fraction > 0.5)
            EXPECT_EQ(res.curves.curve_count(), centres.size());
        else
            EXPECT_LT(res.curves.curve_count(), centres.size());
    }
}

// G below zero only on a segment of tree vertices, jumping there with no root: the zero-width
// loop around it is not a component, and the contour drops it as a sliver.
TEST(Contour, ALoopThinnerThanEtaIsASliverNotAComponent) {
    const auto line =
        pointwise([](Vec2 p) { return p.y == 0.0 && std::abs(p.x) < 0.3 ? -1.0 : 1.0; });
    const ContourResult r = contour(line, unit_domain, options(5, 0));
    EXPECT_TRUE(r.curves.empty());
    EXPECT_EQ(r.stats.slivers, 1u);
    // A disk beside it is kept.
    const auto both = pointwise([](Vec2 p) {
        const double disk = distance(p, {0.0, 0.5}) - 0.2;
        return p.y == 0.0 && std::abs(p.x) < 0.3 ? -1.0 : disk;
    });
    const ContourResult k = contour(both, unit_domain, options(5, 0));
    EXPECT_EQ(k.curves.curve_count(), 1u);
    EXPECT_EQ(k.stats.slivers, 1u);
}

TEST(Contour, ACurveLessThanAFinestCellAcrossIsDroppedWhereCellsWentBeyondK) {
    // A disk, and a speck of radius 0.003 about a vertex of the thin cells' finest level (cells
    // of 2/128 at K = 5 with two thin levels): the cone of its distance bends the cells there,
    // which split to the finest level and see G < 0 at the speck's centre. Less than a finest
    // cell across, it is below what the mesh resolves and is dropped, as a surface's specks are;
    // the uniform tree at K = 7 (cells of the same size, no thin cells) keeps it.
    const Vec2 speck{0.5 + 1.0 / 64.0, 0.25};
    const auto g = pointwise([&](Vec2 p) {
        return std::min(distance(p, {-0.3, 0.0}) - 0.4, distance(p, speck) - 0.003);
    });
    ContourOptions thin = options(5, 2);
    thin.thin_depth = 2;
    const ContourResult r = contour(g, unit_domain, thin);
    ASSERT_GT(r.stats.thin_cells, 0u);
    EXPECT_EQ(r.stats.finest_cell, 2.0 / 128.0);
    EXPECT_EQ(r.stats.specks, 1u);
    ASSERT_EQ(r.curves.curve_count(), 1u);
    EXPECT_NEAR(signed_area(r.curves.curve(0)), pi * 0.16, refined_area_tolerance);
    const ContourResult uniform = contour(g, unit_domain, options(7, 2));
    EXPECT_EQ(uniform.stats.specks, 0u);
    EXPECT_EQ(uniform.curves.curve_count(), 2u);
}

/// max over the sides of a convex polygon (counterclockwise) of the signed distance to the
/// side's line: zero exactly on the polygon, |∇G| = 1, with its corners sharp.
auto convex_polygon(std::vector<Vec2> corners) {
    return [corners = std::move(corners)](Vec2 p) {
        double g = -std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < corners.size(); ++i) {
            const Vec2 a = corners[i], b = corners[(i + 1) % corners.size()];
            g = std::max(g, cross(b - a, p - a) / -norm(b - a));
        }
        return g;
    };
}

// The tree's triangles cut the corners of a polygon; where both neighbours of a segment lie on
// the zero set's sides and it does not, refinement aims at the meeting of their lines and finds
// the corner itself, convex or reflex, in one pass (the paper's triangle safeguard on).
TEST(Contour, CornersOfPolygonsAreFoundInOnePass) {
    const double turn = 0.3;
    std::vector<Vec2> triangle;
    for (int i = 0; i < 3; ++i)
        triangle.push_back(
            {0.7 * std::cos(turn + 2 * pi * i / 3), 0.7 * std::sin(turn + 2 * pi * i / 3)});
    const auto tri = convex_polygon(triangle);
    // An L: the union of two rectangles, turned, with one reflex corner.
    const auto rotate = [&](Vec2 p) {
        return Vec2{std::cos(turn) * p.x - std::sin(turn) * p.y,
                    std::sin(turn) * p.x + std::cos(turn) * p.y};
    };
    std::vector<Vec2> a{{-0.5, -0.5}, {0.5, -0.5}, {0.5, -0.1}, {-0.5, -0.1}};
    std::vector<Vec2> b{{-0.5, -0.5}, {-0.1, -0.5}, {-0.1, 0.5}, {-0.5, 0.5}};
    for (Vec2& p : a) p = rotate(p);
    for (Vec2& p : b) p = rotate(p);
    const auto ga = convex_polygon(a), gb = convex_polygon(b);
    const auto ell = [&](Vec2 p) { return std::min(ga(p), gb(p)); };
    std::vector<Vec2> ell_corners{a[0], a[1], a[2], rotate({-0.1, -0.1}), b[2], b[3]};

    const auto check = [](auto f, const std::vector<Vec2>& corners) {
        const auto g = pointwise(f);
        const ContourResult linear = contour(g, unit_domain, options(5, 0, 1e-10));
        const ContourResult r = contour(g, unit_domain, options(5, 1, 1e-10));
        ASSERT_EQ(r.curves.curve_count(), 1u);
        EXPECT_GT(residuals(linear.curves, g).midpoints, 1e-3);  // the corners cut
        EXPECT_LE(residuals(r.curves, g).midpoints, 1e-12);
        for (Vec2 c : corners) {
            double nearest = std::numeric_limits<double>::infinity();
            for (Vec2 p : r.curves.points()) nearest = std::min(nearest, distance(p, c));
            EXPECT_LE(nearest, 1e-12) << "corner (" << c.x << ", " << c.y << ")";
        }
        expect_simple(r.curves);
    };
    check(tri, triangle);
    check(ell, ell_corners);
}

// A tip narrower than a cell at its neck: the interpolant parts it from its body (two curves),
// G between them says they are one, and refinement starts from them joined: one curve, exact to
// rounding, with the tip's corner (the paper's shrinking triangle at t = 0.2, Fig. 13).
TEST(Contour, ATipPartedByTheInterpolantIsJoinedToItsBody) {
    const double tilt = 10.0 * pi / 180.0;
    std::vector<Vec2> corners;
    for (int i = 0; i < 3; ++i) {
        const double a = tilt + pi / 2 + 2 * pi * i / 3;
        corners.push_back({0.6 * std::cos(a), 0.6 * std::sin(a)});
    }
    const auto g = pointwise(convex_polygon(corners));
    const Box domain = Box::centered_square(2.5);
    const ContourResult linear = contour(g, domain, options(5, 0));
    EXPECT_EQ(linear.curves.curve_count(), 2u);
    EXPECT_EQ(linear.stats.joined, 0u);  // the linear contour is the interpolant's
    const ContourResult r = contour(g, domain, options(5, 2, 1e-10));
    ASSERT_EQ(r.curves.curve_count(), 1u);
    EXPECT_EQ(r.stats.joined, 1u);
    EXPECT_LE(residuals(r.curves, g).midpoints, 1e-12);
    EXPECT_NEAR(signed_area(r.curves.curve(0)), 0.75 * std::sqrt(3.0) * 0.36, 1e-12);
    expect_simple(r.curves);
}

/// The signed distance to two discs outside them (their union's zero set), and their union's
/// inside.
auto two_discs(Vec2 c1, double r1, Vec2 c2, double r2) {
    return [=](Vec2 p) { return std::min(distance(p, c1) - r1, distance(p, c2) - r2); };
}

// Two discs a gap narrower than a cell apart, whose triangles the interpolant links across the
// gap at K = 4 (cells 0.125): the paper's refinement keeps the bridge (its safeguards refuse the
// splits that would cross it), and slc's parts it where G between its sides is positive
// (ContourOptions::part_bridges). Three of the 65 of 92 such pairs of a seeded sweep that come out
// two; each disc then keeps its area to the chords' sagitta.
TEST(Contour, TwoDiscsTheInterpolantJoinsArePartedWhereGSaysTheyAreTwo) {
    struct Pair {
        Vec2 c1;
        double r1;
        Vec2 c2;
        double r2;
    };
    for (const Pair& d : {Pair{{-0.1827, -0.1866}, 0.3666, {-0.3569, 0.4529}, 0.2169},
                          Pair{{-0.0677, -0.1495}, 0.2987, {-0.5786, -0.3900}, 0.2373},
                          Pair{{0.0632, 0.1827}, 0.3168, {-0.0810, -0.3434}, 0.1556}}) {
        SCOPED_TRACE(::testing::Message() << "discs at " << d.c1.x << ", " << d.c1.y);
        const auto g = pointwise(two_discs(d.c1, d.r1, d.c2, d.r2));
        EXPECT_EQ(contour(g, unit_domain, options(4, 0)).curves.curve_count(), 1u);
        ContourOptions paper = options(4, 2);
        paper.part_bridges = false;
        const ContourResult kept = contour(g, unit_domain, paper);
        EXPECT_EQ(kept.curves.curve_count(), 1u);
        EXPECT_EQ(kept.stats.parted, 0u);
        const ContourResult r = contour(g, unit_domain, options(4, 2));
        ASSERT_EQ(r.curves.curve_count(), 2u);
        EXPECT_GE(r.stats.parted, 1u);
        expect_simple(r.curves);
        EXPECT_LE(residuals(r.curves, g).vertices, eta);
        // Each curve counterclockwise about one disc, enclosing its area less the chords'
        // segments: K = 4 and two passes leave chords of at most about 0.04, whose segments
        // take under 1% of these discs' areas.
        std::vector<double> areas;
        for (std::size_t c = 0; c < 2; ++c) areas.push_back(signed_area(r.curves.curve(c)));
        std::sort(areas.begin(), areas.end());
        const double small = std::min(d.r1, d.r2), large = std::max(d.r1, d.r2);
        EXPECT_NEAR(areas[0] / (pi * small * small), 1.0, 1e-2);
        EXPECT_NEAR(areas[1] / (pi * large * large), 1.0, 1e-2);
    }
}

// Below two ulps of the domain's coordinates no root can be found: a given ε there is refused
// (every split would be rejected, silently), η and the default ε are raised to it.
TEST(Contour, ToleranceBelowRoundingIsRefusedOrRaised) {
    // A square: refinement converges in a few passes once the corners are found.
    const auto g =
        pointwise([](Vec2 p) { return std::max(std::abs(p.x - 0.1), std::abs(p.y)) - 0.5; });
    EXPECT_THROW(contour(g, unit_domain, options(5, 1000, 1e-16)), InvalidInput);
    ContourOptions fine = options(5, 1000, 1e-15);
    fine.eta = 1e-17;
    fine.triangle_safeguard = false;  // so that the corners are found again
    const ContourResult r = contour(g, unit_domain, fine);
    EXPECT_LE(residuals(r.curves, g).midpoints, 1e-15);
    EXPECT_EQ(r.stats.rejected, 0u);
}

// Refinement that would pass max_vertices stops with LimitExceeded naming eps, before the
// pass that would: a circle refined to 1e-12 needs about 2.2e6 vertices.
TEST(Contour, RefinementBeyondTheVertexLimitNamesEps) {
    const auto g = pointwise(circle({0.1, 0.0}, 0.5));
    ContourOptions o = options(5, ContourOptions::until_converged, 1e-12);
    o.eta = 1e-13;
    o.max_vertices = 5000;
    try {
        contour(g, unit_domain, o);
        FAIL() << "refining past max_vertices must throw";
    } catch (const LimitExceeded& e) {
        EXPECT_NE(std::string(e.what()).find("raise eps"), std::string::npos) << e.what();
    }
    o.eps = 1e-6;  // about 1,100 vertices
    EXPECT_NO_THROW(contour(g, unit_domain, o));
}

TEST(Contour, NoZeroGivesAnEmptyInterface) {
    for (double sign : {1.0, -1.0}) {
        const auto g = pointwise([=](Vec2 p) { return sign * (0.5 + norm2(p)); });
        const ContourResult r = contour(g, unit_domain, options(5, 3));
        EXPECT_TRUE(r.curves.empty());
        EXPECT_EQ(r.stats.vertices, 0u);
        EXPECT_EQ(r.stats.g_evals_per_vertex, 0.0);
        EXPECT_GT(r.stats.g_evals, 0u);
    }
}

TEST(Contour, ZeroSetReachingTheBoundaryIsAFailureNamingThePlace) {
    const auto line = pointwise([](Vec2 p) { return p.x - 0.1; });
    try {
        contour(line, unit_domain, options(4, 0));
        FAIL() << "a contour crossing the boundary must throw";
    } catch (const NumericalFailure& e) {
        EXPECT_NE(std::string(e.what()).find("boundary near (0.1, "), std::string::npos)
            << e.what();
    }
    // A circle through a boundary vertex touches the boundary.
    const auto touching = pointwise(circle({0.0, 0.0}, 1.0));
    EXPECT_THROW(contour(touching, unit_domain, options(3, 0)), NumericalFailure);
}

TEST(Contour, VanishingOnARegionIsIllPosed) {
    const auto flat = pointwise([](Vec2 p) { return std::max(0.0, norm(p) - 0.3); });
    try {
        contour(flat, unit_domain, options(5, 0));
        FAIL() << "G = 0 on a disk must throw";
    } catch (const NumericalFailure& e) {
        EXPECT_NE(std::string(e.what()).find("ill-posed"), std::string::npos) << e.what();
    }
}

TEST(Contour, NonFiniteValueIsAFailureNamingThePoint) {
    const auto g = pointwise([](Vec2 p) { return p.x > 0.7 ? std::nan("") : norm(p) - 0.5; });
    try {
        contour(g, unit_domain, options(4, 0));
        FAIL() << "NaN must throw";
    } catch (const NumericalFailure& e) {
        EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
    }
}

TEST(Contour, InvalidOptionsAreRejected) {
    const auto g = pointwise(circle({0.0, 0.0}, 0.5));
    auto with = [](auto change) {
        ContourOptions o;
        change(o);
        return o;
    };
    EXPECT_THROW(contour(g, unit_domain, with([](auto& o) { o.depth = -1; })), InvalidInput);
    EXPECT_THROW(contour(g, unit_domain, with([](auto& o) { o.depth = 31; })), InvalidInput);
    EXPECT_THROW(contour(g, unit_domain, with([](auto& o) { o.refine_passes = -2; })),
                 InvalidInput);
    EXPECT_THROW(contour(g, unit_domain, with([](auto& o) { o.eta = 0.0; })), InvalidInput);
    EXPECT_THROW(contour(g, unit_domain, with([](auto& o) { o.eps = 1e-12; })), InvalidInput);
    EXPECT_THROW(contour(g, unit_domain, with([](auto& o) { o.rho = 1.0; })), InvalidInput);
    EXPECT_THROW(contour(g, unit_domain, with([](auto& o) { o.gamma = -1.0; })), InvalidInput);
    // Creases are the surfaces' own option (one options type for both dimensions).
    EXPECT_THROW(contour(g, unit_domain, with([](auto& o) { o.creases = true; })), InvalidInput);
    EXPECT_THROW(contour(g, Box{{0, 0}, {1, 2}}, ContourOptions{}), InvalidInput);
    EXPECT_DOUBLE_EQ(with([](auto& o) { o.depth = 7; }).resolved_eps(), 1e-7);
}

TEST(Contour, CountsEveryEvaluationAndNeverEvaluatesAPointTwice) {
    std::vector<Vec2> seen;
    const auto g = [&seen](std::span<const Vec2> x, std::span<double> v) {
        for (std::size_t i = 0; i < x.size(); ++i) {
            seen.push_back(x[i]);
            v[i] = x[i].x * x[i].x + 2.0 * x[i].y * x[i].y - 0.3 + 0.1 * std::sin(5.0 * x[i].x);
        }
    };
    const ContourResult r =
        contour(g, unit_domain, options(6, ContourOptions::until_converged, 1e-7));
    EXPECT_EQ(r.stats.g_evals, seen.size());
    EXPECT_EQ(r.stats.g_evals,
              r.stats.g_evals_tree + r.stats.g_evals_roots + r.stats.g_evals_refine);
    std::set<std::pair<double, double>> distinct;
    for (const Vec2 p : seen) distinct.insert({p.x, p.y});
    EXPECT_EQ(distinct.size(), seen.size());
    EXPECT_DOUBLE_EQ(r.stats.g_evals_per_vertex,
                     static_cast<double>(r.stats.g_evals) / static_cast<double>(r.stats.vertices));
}

TEST(Contour, LinearContourErrorIsSecondOrderInTheCellSize) {
    // Paper Table 2: the midpoint error of the linear interpolant is O(h²).
    const auto g = pointwise(circle({0.03, 0.01}, 0.55));
    std::vector<double> errors;
    for (int depth = 5; depth <= 8; ++depth)
        errors.push_back(residuals(contour(g, unit_domain, options(depth, 0)).curves, g).midpoints);
    const double order = std::log2(errors.front() / errors.back()) / 3.0;
    EXPECT_GT(order, 1.7);
    EXPECT_LT(order, 2.3);
}

TEST(Contour, SameContourForOneAndTwoThreads) {
    const auto g = pointwise([](Vec2 p) {
        const double r = norm(p), theta = std::atan2(p.y, p.x);
        return r - 0.5 * (1.0 + 0.5 * std::cos(3.0 * theta));
    });
    std::vector<ContourResult> results;
    for (int threads : {1, 2}) {
        set_thread_count(threads);
        results.push_back(
            contour(g, unit_domain, options(7, ContourOptions::until_converged, 1e-6)));
    }
    set_thread_count(0);
    ASSERT_EQ(results[0].curves.size(), results[1].curves.size());
    EXPECT_EQ(results[0].curves.curves(), results[1].curves.curves());
    EXPECT_EQ(results[0].stats.g_evals, results[1].stats.g_evals);
    EXPECT_EQ(results[0].stats.cells, results[1].stats.cells);
}

}  // namespace
}  // namespace slc
