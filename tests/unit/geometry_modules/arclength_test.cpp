// Tests of the arclength geometry module: curvature exact on circles however unevenly sampled
// and whatever the width, a corner's curvature integrating to its turn, signs on holes, the bias of
// the averaging shrinking as σ⁴ on an ellipse, and its errors.
#include "slc/geometry_modules/arclength.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include "slc/core/error.hpp"
#include "slc/geometry/shapes.hpp"

namespace slc {
namespace {

using std::numbers::pi;

/// n points on the circle of radius r about centre at angles jittered by up to 40% of a step.
std::vector<Vec2> uneven_circle(Vec2 centre, double r, int n, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> jitter(-0.4, 0.4);
    std::vector<Vec2> points;
    for (int i = 0; i < n; ++i) {
        const double angle = 2.0 * pi * (i + jitter(random)) / n;
        points.push_back(centre + r * Vec2{std::cos(angle), std::sin(angle)});
    }
    return points;
}

TEST(ArclengthGeometry, CurvatureIsExactOnCirclesHoweverUnevenAndWhateverTheWidth) {
    // The circle through three points of a circle is that circle, and averaging a constant
    // returns it: C = −1/R at every vertex, to rounding, for any σ (also one wider than the
    // curve, where the averaging reaches around it once).
    const Vec2 centre{0.3, -0.2};
    for (const double r : {0.05, 0.5, 3.0}) {
        const Interface curves({uneven_circle(centre, r, 300, 7)});
        for (const double width : {0.0, 0.01 * r, 0.3 * r, 20.0 * r}) {
            const VertexGeometry g = arclength_geometry(curves, width);
            for (std::size_t i = 0; i < curves.size(); ++i)
                ASSERT_NEAR(g.curvature[i] * r, -1.0, 1e-9) << "r = " << r << ", σ = " << width;
        }
    }
}

TEST(ArclengthGeometry, ACornersCurvatureIntegratesToItsTurn) {
    // A square of side 1 sampled 8 points an edge, and an L with a square hole sampled unevenly:
    // each corner's κ ds is its turn (±π/2), the sides' vertices have κ = 0, and Σ κ ds is −2π
    // for each counterclockwise curve and +2π for the hole, as for a smooth curve. The circle
    // through a corner and its neighbours would give √2 where the turn is π/2.
    const auto sampled = [](std::vector<Vec2> corners, std::vector<int> per_edge) {
        std::vector<Vec2> points;
        for (std::size_t c = 0; c < corners.size(); ++c) {
            const Vec2 a = corners[c], b = corners[(c + 1) % corners.size()];
            const int n = per_edge[c % per_edge.size()];
            for (int k = 0; k < n; ++k)
                points.push_back(a + (static_cast<double>(k) / n) * (b - a));
        }
        return points;
    };
    const Interface square({sampled({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {8})});
    const Interface l_with_hole(
        {sampled({{0, 0}, {1, 0}, {1, 0.4}, {0.4, 0.4}, {0.4, 1}, {0, 1}}, {40, 7, 23, 9, 3, 11}),
         sampled({{0.1, 0.1}, {0.1, 0.35}, {0.3, 0.35}, {0.3, 0.1}}, {5, 4, 6, 3})});
    for (const Interface* curves : {&square, &l_with_hole}) {
        const VertexGeometry g = arclength_geometry(*curves, 0.0);
        for (std::size_t c = 0; c < curves->curve_count(); ++c) {
            double total = 0.0;
            for (std::size_t i = curves->offsets()[c]; i < curves->offsets()[c + 1]; ++i) {
                const double ds = 0.5 * (norm(curves->point(i) - curves->point(curves->prev(i))) +
                                         norm(curves->point(curves->next(i)) - curves->point(i)));
                const double turn = std::abs(g.curvature[i] * ds);
                EXPECT_TRUE(turn < 1e-12 || std::abs(turn - pi / 2) < 1e-12) << turn;
                total += g.curvature[i] * ds;
            }
            EXPECT_NEAR(total, c == 0 ? -2.0 * pi : 2.0 * pi, 1e-12);
        }
    }
    // A turn at most corner_turn is read as a smooth curve's: the circle's curvature.
    const Vec2 u{1.0, 0.0}, v{std::cos(0.4), std::sin(0.4)};
    EXPECT_DOUBLE_EQ(vertex_curvature(u, v), circle_curvature(u, v));
    EXPECT_DOUBLE_EQ(vertex_curvature(u, {0.0, 2.0}), -2.0 * (pi / 2) / 3.0);
}

TEST(ArclengthGeometry, NormalsAreRadialOnRegularPolygonsAndHolesCurveTheOtherWay) {
    // An annulus: outer circle counterclockwise, hole clockwise. The hole's outward normal
    // (towards F > 0) points at its centre, and its curvature is +1/R.
    std::vector<Vec2> hole = shapes::circle({}, 0.5, 64, 0.2);
    std::reverse(hole.begin(), hole.end());
    const Interface curves({shapes::circle({}, 2.0, 200), hole});
    const VertexGeometry g = arclength_geometry(curves, 0.1);
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const bool outer = curves.curve_of(i) == 0;
        const Vec2 radial = curves.point(i) / norm(curves.point(i));
        EXPECT_NEAR(norm(g.normals[i] - (outer ? radial : -1.0 * radial)), 0.0, 1e-12);
        EXPECT_NEAR(g.curvature[i], outer ? -0.5 : 2.0, 1e-9);
    }
}

/// Largest curvature error on the ellipse x = cos t, y = 0.6 sin t (n points evenly in t).
double ellipse_error(double width) {
    const int n = 4000;
    const double a = 1.0, b = 0.6;
    std::vector<Vec2> points;
    std::vector<double> exact;
    for (int i = 0; i < n; ++i) {
        const double t = 2.0 * pi * i / n, s = std::sin(t), c = std::cos(t);
        points.push_back({a * c, b * s});
        exact.push_back(-a * b / std::pow(a * a * s * s + b * b * c * c, 1.5));
    }
    const Interface curves({points});
    const VertexGeometry g = arclength_geometry(curves, width);
    double worst = 0.0;
    for (int i = 0; i < n; ++i) worst = std::max(worst, std::abs(g.curvature[i] - exact[i]));
    return worst;
}

TEST(ArclengthGeometry, AveragingBiasShrinksAsTheFourthPowerOfTheWidth) {
    // Twicing (2G − G·G) cancels the σ² term of a Gaussian average: halving σ divides the bias by
    // about 16 (a plain average would divide it by 4). Measured: order 3.2, then 3.7 as σ → 0.
    const double raw = ellipse_error(0.0);
    EXPECT_LT(raw, 1e-5);  // the circles through neighbours alone: O(h²), h ≈ 1.3e−3
    const double e1 = ellipse_error(0.1), e2 = ellipse_error(0.05), e3 = ellipse_error(0.025);
    const double order = std::log2(e2 / e3);
    std::printf(
        "arclength curvature on an ellipse: sigma 0.1, 0.05, 0.025: %.3e %.3e %.3e, "
        "observed orders %.2f %.2f\n",
        e1, e2, e3, std::log2(e1 / e2), order);
    EXPECT_GT(std::log2(e1 / e2), 3.0);
    EXPECT_GT(order, 3.5);
    EXPECT_LT(e3, 1e-3);
}

TEST(ArclengthGeometry, RejectsBadWidthsAndRepeatedVertices) {
    const Interface circle({shapes::circle({}, 1.0, 16)});
    EXPECT_THROW(arclength_geometry(circle, -0.1), InvalidInput);
    EXPECT_THROW(arclength_geometry(circle, std::numeric_limits<double>::quiet_NaN()),
                 InvalidInput);
    EXPECT_THROW(arclength_geometry(circle, std::numeric_limits<double>::infinity()), InvalidInput);
    const Interface repeated({{{0, 0}, {1, 0}, {1, 0}, {0, 1}}});
    EXPECT_THROW(arclength_geometry(repeated, 0.1), InvalidInput);
}

}  // namespace
}  // namespace slc
