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

/// The points where r = 1 + 0.2 cos 3θ crosses the lines x = 0.0123 + i·cell and y = 0.0123 +
/// j·cell, in order of θ: vertices spaced as a contour's are (from a rounding error to √2 cells).
Interface lobes_crossing_grid(double cell) {
    const auto at = [](double a) {
        return (1 + 0.2 * std::cos(3 * a)) * Vec2{std::cos(a), std::sin(a)};
    };
    const auto line = [&](double v) { return std::floor((v - 0.0123) / cell); };
    std::vector<Vec2> p;
    constexpr int pieces = 100000;
    for (int i = 0; i < pieces; ++i) {
        const double a = 2 * pi * i / pieces, b = 2 * pi * (i + 1) / pieces;
        std::vector<double> roots;
        for (int axis = 0; axis < 2; ++axis) {
            const auto coordinate = [&](double s) { return axis == 0 ? at(s).x : at(s).y; };
            if (line(coordinate(a)) == line(coordinate(b))) continue;
            const double v = 0.0123 + cell * std::max(line(coordinate(a)), line(coordinate(b)));
            double lo = a, hi = b;
            for (int k = 0; k < 60; ++k) {
                const double mid = 0.5 * (lo + hi);
                ((coordinate(mid) - v) * (coordinate(a) - v) > 0 ? lo : hi) = mid;
            }
            roots.push_back(0.5 * (lo + hi));
        }
        std::sort(roots.begin(), roots.end());
        for (double r : roots) p.push_back(at(r));
    }
    return Interface({p});
}

TEST(MullinsSekerka, TheSpeedsConvergeInTheNumberOfPoints) {
    // The three-lobed curve through the points where it crosses a grid of cell h (as a contour's
    // vertices), against 2,048 vertices evenly spaced in θ (read between them linearly in θ).
    // The curvature is fitted by a polynomial of degree 6 through nine points, O(h⁵); V, which
    // multiplies the vertex-scale part of its error by about 1/h, converges at third order
    // (measured: 9.1e−3, 1.5e−3, 1.8e−4 of max |V| at h = 1/16, 1/32, 1/64; the cubic spline's
    // curvature gave 5.4e−2, 5.3e−2, 2.2e−2).
    const MullinsSekerka law;
    constexpr std::size_t n = 2048;
    const std::vector<double> reference =
        law.normal_speeds(perturbed_circle({0, 0}, 1.0, 3, 0.2, n), 0.0);
    double scale = 0;
    for (double v : reference) scale = std::max(scale, std::abs(v));
    std::vector<double> error;
    for (double cell : {1.0 / 16, 1.0 / 32, 1.0 / 64}) {
        const Interface curves = lobes_crossing_grid(cell);
        const std::vector<double> v = law.normal_speeds(curves, 0.0);
        double worst = 0;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const double a = std::atan2(curves.point(i).y, curves.point(i).x);
            const double u = (a < 0 ? a + 2 * pi : a) / (2 * pi) * n;
            const std::size_t j = static_cast<std::size_t>(u);
            const double w = u - static_cast<double>(j);
            worst = std::max(
                worst, std::abs(v[i] - (1 - w) * reference[j % n] - w * reference[(j + 1) % n]));
        }
        error.push_back(worst / scale);
    }
    const double order = std::log2(error[1] / error[2]);
    RecordProperty("order", std::to_string(order));
    EXPECT_GT(order, 2.5) << error[0] << " " << error[1] << " " << error[2];
    EXPECT_LT(error[2], 5e-4);
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
