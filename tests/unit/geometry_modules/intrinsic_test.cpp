// Tests of the intrinsic geometry module (paper §3.1, Eqs. 7 and 8): exact values on regular
// polygons and straight sides, signs on holes, first-order normals on uneven samplings, and the
// total curvature of a closed convex curve.
#include "slc/geometry_modules/intrinsic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/geometry/shapes.hpp"

namespace slc {
namespace {

using std::numbers::pi;

/// Rounding in a handful of operations on unit vectors and lengths ~1.
constexpr double rounding_tolerance = 1e-12;

TEST(IntrinsicGeometry, CurvatureIsExactOnRegularPolygons) {
    // Eq. 8 gives C_i = −cos(α/2)/R / cos(α/2) = −1/R exactly, α = 2π/n, and Eq. 7 the radius.
    const Vec2 centre{0.3, -0.2};
    for (const double r : {0.1, 0.5, 2.0}) {
        for (const int n : {5, 16, 200}) {
            const Interface curves({shapes::circle(centre, r, n, 0.1)});
            const VertexGeometry g = intrinsic_geometry(curves);
            for (std::size_t i = 0; i < curves.size(); ++i) {
                EXPECT_NEAR(g.curvature[i], -1.0 / r, rounding_tolerance / r);
                const Vec2 radial = (curves.point(i) - centre) / r;
                EXPECT_NEAR(norm(g.normals[i] - radial), 0.0, rounding_tolerance);
            }
        }
    }
}

TEST(IntrinsicGeometry, HolesHaveInwardNormalsAndPositiveCurvature) {
    // An annulus: outer circle counterclockwise, hole clockwise. Outward (towards F > 0) on the
    // hole points at its centre, and C = −∇·N = +1/R there.
    auto hole = shapes::circle({}, 0.25, 40);
    std::reverse(hole.begin(), hole.end());
    const Interface curves({shapes::circle({}, 0.75, 60), hole});
    const VertexGeometry g = intrinsic_geometry(curves);
    for (std::size_t i = curves.offsets()[1]; i < curves.size(); ++i) {
        EXPECT_NEAR(g.curvature[i], 4.0, rounding_tolerance);
        EXPECT_NEAR(norm(g.normals[i] + curves.point(i) / 0.25), 0.0, rounding_tolerance);
    }
    EXPECT_NEAR(g.curvature[0], -1.0 / 0.75, rounding_tolerance);
}

TEST(IntrinsicGeometry, NormalsOnPolygonsWithCornersAreExactOnSidesAndBisectCorners) {
    // Rectangle [0, 2] × [0, 1], four vertices per side. Eq. 7 uses only the two segments at a
    // vertex: side vertices get the side's normal, corners the bisector. Eq. 8 also uses the
    // neighbours' normals: zero curvature away from corners, negative (convex) at a corner and
    // beside it, the discrete trace of the corner's turn.
    const Interface curves({shapes::rectangle({0, 0}, {2, 1}, 4)});
    const VertexGeometry g = intrinsic_geometry(curves);
    auto is_corner = [&](std::size_t i) {
        const Vec2 p = curves.point(i);
        return (p.x == 0.0 || p.x == 2.0) && (p.y == 0.0 || p.y == 1.0);
    };
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const Vec2 p = curves.point(i);
        const Vec2 side_normal{p.x == 0.0   ? -1.0
                               : p.x == 2.0 ? 1.0
                                            : 0.0,
                               p.y == 0.0   ? -1.0
                               : p.y == 1.0 ? 1.0
                                            : 0.0};
        if (is_corner(i)) {
            EXPECT_NEAR(norm(g.normals[i] - side_normal / std::numbers::sqrt2), 0.0,
                        rounding_tolerance);
            EXPECT_LT(g.curvature[i], -1.0);
        } else if (is_corner(curves.prev(i)) || is_corner(curves.next(i))) {
            EXPECT_NEAR(norm(g.normals[i] - side_normal), 0.0, rounding_tolerance);
            EXPECT_LT(g.curvature[i], 0.0);
        } else {
            EXPECT_NEAR(norm(g.normals[i] - side_normal), 0.0, rounding_tolerance);
            EXPECT_NEAR(g.curvature[i], 0.0, rounding_tolerance);
        }
    }
}

/// The ellipse x = a cos t, y = b sin t sampled at n parameters alternately a third of a step
/// early and late: unequal neighbouring segments, as contouring produces. Returns the largest
/// normal error.
double uneven_ellipse_normal_error(int n) {
    const double a = 0.7, b = 0.4;
    std::vector<Vec2> pts;
    std::vector<Vec2> exact;
    for (int k = 0; k < n; ++k) {
        const double t = 2 * pi * (k + (k % 2 == 0 ? 0.3 : -0.3)) / n;
        pts.push_back({a * std::cos(t), b * std::sin(t)});
        const Vec2 nn{b * std::cos(t), a * std::sin(t)};
        exact.push_back(nn / norm(nn));
    }
    const VertexGeometry g = intrinsic_geometry(Interface({pts}));
    double e = 0.0;
    for (std::size_t i = 0; i < pts.size(); ++i) e = std::max(e, norm(g.normals[i] - exact[i]));
    return e;
}

TEST(IntrinsicGeometry, NormalOnUnevenSamplingsConvergesAtOrder1) {
    // The bisector of two chords of lengths ℓ± points along the tangent at the parameter shifted
    // by (ℓ+ − ℓ−)/4: first order when neighbouring segments differ in length.
    constexpr double expected_order = 1.0, order_slack = 0.1;
    double previous = uneven_ellipse_normal_error(64);
    for (int n = 128; n <= 1024; n *= 2) {
        const double e = uneven_ellipse_normal_error(n);
        const double observed = std::log2(previous / e);
        std::printf("intrinsic normals, uneven ellipse, n = %d: error %.3e, observed order %.2f\n",
                    n, e, observed);
        EXPECT_NEAR(observed, expected_order, order_slack);
        previous = e;
    }
}

TEST(IntrinsicGeometry, TotalCurvatureIsMinusTwoPiPerConvexCurve) {
    // Σ C_i w_i over a closed convex curve approximates ∫ C ds = −2π (the turning number) to
    // second order in the spacing: on the regular 50-gon C_i = −1/R exactly and Σ w_i, the
    // perimeter, falls short of 2πR by the factor sin(π/n)/(π/n), a relative 6.6e-4: 4.1e-3.
    constexpr double integral_tolerance = 5e-3;
    const Interface curves(
        {shapes::circle({-0.5, 0}, 0.3, 50),
         shapes::polar(
             {0.5, 0.2},
             [](double t) { return 0.3 / std::sqrt(1 + 2 * std::sin(t) * std::sin(t)); }, 400)});
    const VertexGeometry g = intrinsic_geometry(curves);
    const auto w = vertex_arc_lengths(curves);
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        double total = 0.0;
        for (std::size_t i = curves.offsets()[c]; i < curves.offsets()[c + 1]; ++i)
            total += g.curvature[i] * w[i];
        EXPECT_NEAR(total, -2 * pi, integral_tolerance) << "curve " << c;
    }
    std::vector<double> ones(curves.size(), 1.0);
    EXPECT_NEAR(arc_length_mean(curves, ones), 1.0, rounding_tolerance);
}

TEST(IntrinsicGeometry, RejectsRepeatedVertices) {
    const Interface curves({{{0, 0}, {1, 0}, {1, 0}, {0, 1}}});
    EXPECT_THROW(intrinsic_geometry(curves), InvalidInput);
}

}  // namespace
}  // namespace slc
