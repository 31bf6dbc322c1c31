// The Mullins–Sekerka law against its linear rates on perturbed circles and its steady circle.
#include "slc/velocity/potential_laws.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/geometry_modules/vertex_geometry.hpp"
#include "slc/potential/boundary_integral.hpp"
#include "slc/velocity/factory.hpp"

namespace slc {
namespace {

using std::numbers::pi;

/// r = R(1 + δ cos mθ) about centre, n vertices counterclockwise.
Interface perturbed_circle(Vec2 centre, double r, int m, double delta, std::size_t n) {
    std::vector<Vec2> p;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = 2 * pi * static_cast<double>(i) / static_cast<double>(n);
        p.push_back(centre + r * (1 + delta * std::cos(m * a)) * Vec2{std::cos(a), std::sin(a)});
    }
    return Interface({p});
}

TEST(MullinsSekerka, APerturbedCirclesSpeedIsItsLinearRate) {
    // V = R dδ/dt cos mθ = −σ (D_in + D_out) m(m² − 1) δ / R² cos mθ, to O(δ²).
    const double r = 0.8, delta = 1e-4, sigma = 0.5;
    for (int m : {2, 3, 6}) {
        for (const auto& [din, dout] : {std::pair{1.0, 1.0}, {0.5, 2.0}}) {
            const MullinsSekerka law(sigma, din, dout);
            const Interface curves = perturbed_circle({0.1, 0.2}, r, m, delta, 256);
            const std::vector<double> v = law.normal_speeds(curves, 0.0);
            const double amplitude = sigma * (din + dout) * m * (m * m - 1) * delta / (r * r);
            double worst = 0;
            for (std::size_t i = 0; i < v.size(); ++i) {
                const Vec2 d = curves.point(i) - Vec2{0.1, 0.2};
                worst = std::max(worst,
                                 std::abs(v[i] + amplitude * std::cos(m * std::atan2(d.y, d.x))));
            }
            EXPECT_LT(worst, 0.01 * amplitude) << "m " << m << " din " << din;
        }
    }
}

TEST(MullinsSekerka, TheSpeedsConvergeInTheNumberOfPoints) {
    // A three-lobed curve (r = 1 + 0.2 cos 3θ) through n vertices, against 1024 vertices. The
    // spline's curvature is second order in the spacing h, with an error that oscillates at the
    // vertices' scale, where V, a derivative of the curvature, multiplies it by 1/h: V at the
    // vertices converges at first order (a step filters those modes, docs/algorithms/potential.md);
    // its lobes' mode cos 3θ is within 1e−5 of the reference's from 128 vertices on (measured:
    // 9.1e−3, 3.1e−7, 9.4e−6 at 64, 128, 256: the reference's own error).
    const MullinsSekerka law;
    const auto speeds = [&](std::size_t n) {
        return law.normal_speeds(perturbed_circle({0, 0}, 1.0, 3, 0.2, n), 0.0);
    };
    const auto lobes = [](const std::vector<double>& v) {
        double c = 0;
        for (std::size_t i = 0; i < v.size(); ++i)
            c += 2.0 / static_cast<double>(v.size()) *
                 std::cos(3 * 2 * pi * static_cast<double>(i) / static_cast<double>(v.size())) *
                 v[i];
        return c;
    };
    const std::vector<double> reference = speeds(1024);
    double scale = 0;
    for (double v : reference) scale = std::max(scale, std::abs(v));
    std::vector<double> at_vertices, of_lobes;
    for (std::size_t n : {64u, 128u, 256u}) {
        const std::vector<double> v = speeds(n);
        double worst = 0;
        for (std::size_t i = 0; i < n; ++i)
            worst = std::max(worst, std::abs(v[i] - reference[i * (1024 / n)]));
        at_vertices.push_back(worst / scale);
        of_lobes.push_back(std::abs(lobes(v) / lobes(reference) - 1));
    }
    const double pointwise = std::log2(at_vertices[1] / at_vertices[2]);
    RecordProperty("pointwise_order", std::to_string(pointwise));
    EXPECT_GT(pointwise, 0.8) << at_vertices[0] << " " << at_vertices[1] << " " << at_vertices[2];
    EXPECT_LT(at_vertices[2], 0.03);
    EXPECT_LT(of_lobes[1], 2e-5) << of_lobes[0] << " " << of_lobes[1] << " " << of_lobes[2];
    EXPECT_LT(of_lobes[2], 2e-5);
}

TEST(HeleShaw, APerturbedCirclesSpeedIsItsLinearRateAndASourceFeedsItsRegion) {
    // V = −σ m(m² − 1) δ / R² cos mθ; on a circle, a source Q at the centre gives Q/(2πR).
    const double r = 0.8, delta = 1e-4, sigma = 0.5;
    for (int m : {2, 5}) {
        const Interface curves = perturbed_circle({0.1, 0.2}, r, m, delta, 256);
        const std::vector<double> v = HeleShaw(sigma).normal_speeds(curves, 0.0);
        const double amplitude = sigma * m * (m * m - 1) * delta / (r * r);
        double worst = 0;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const Vec2 d = curves.point(i) - Vec2{0.1, 0.2};
            worst =
                std::max(worst, std::abs(v[i] + amplitude * std::cos(m * std::atan2(d.y, d.x))));
        }
        EXPECT_LT(worst, 0.01 * amplitude) << "m " << m;
    }
    const Interface circle = perturbed_circle({0.1, 0.2}, r, 0, 0.0, 256);
    for (double v : HeleShaw(sigma, 0.3, {0.1, 0.2}).normal_speeds(circle, 0.0))
        EXPECT_NEAR(v, 0.3 / (2 * pi * r), 1e-9);
}

TEST(HeleShaw, EachRegionIsSolvedAloneAndKeepsItsArea) {
    // Two bubbles, one with a hole: the speeds integrate to zero over each region's curves.
    // The vertices' trapezoidal rule integrates to O(h²): 1024 vertices a curve.
    std::vector<Vec2> hole = perturbed_circle({0, 0}, 0.3, 3, 0.05, 1024).curves()[0];
    std::reverse(hole.begin(), hole.end());
    const Interface curves({perturbed_circle({0, 0}, 0.8, 2, 0.1, 1024).curves()[0], hole,
                            perturbed_circle({2, 0}, 0.4, 3, 0.1, 1024).curves()[0]});
    EXPECT_EQ(curve_regions(curves), (std::vector<std::size_t>{0, 0, 1}));
    const std::vector<double> v = HeleShaw(1.0).normal_speeds(curves, 0.0);
    const std::vector<double> w = vertex_arc_lengths(curves);
    double flux[2] = {0, 0}, scale = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        flux[curves.curve_of(i) == 2 ? 1 : 0] += v[i] * w[i];
        scale = std::max(scale, std::abs(v[i]));
    }
    EXPECT_LT(std::abs(flux[0]), 1e-4 * scale * length(curves));
    EXPECT_LT(std::abs(flux[1]), 1e-4 * scale * length(curves));
    EXPECT_THROW(HeleShaw(1.0, 1.0, {5, 5}).normal_speeds(curves, 0.0), InvalidInput);
    EXPECT_THROW(HeleShaw(1.0, 1.0, {0, 0}).normal_speeds(curves, 0.0), InvalidInput);  // the hole
    EXPECT_THROW(HeleShaw(-1.0), InvalidInput);
}

}  // namespace
}  // namespace slc
