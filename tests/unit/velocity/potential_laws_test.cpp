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
