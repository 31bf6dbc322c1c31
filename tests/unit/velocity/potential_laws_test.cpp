// The Mullins–Sekerka law against its linear rates on perturbed circles and its steady circle.
#include "slc/velocity/potential_laws.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"
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

}  // namespace
}  // namespace slc
