// Tests of the one-dimensional ENO kernels (paper §3.2): exactness on polynomials, observed orders
// of differentiation and interpolation, stencils that avoid kinks and jumps, and the 1-2-1 pass.
#include "slc/geometry_modules/eno.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace slc {
namespace {

/// Rounding of a few dozen operations on values of size ~1, divided by h ~ 0.1: polynomial data
/// must be reproduced to this.
constexpr double polynomial_tolerance = 1e-10;
/// An observed order may fall this far below the formal one on these coarse-to-moderate lines.
constexpr double order_slack = 0.2;

std::vector<double> samples(const std::function<double(double)>& f, double x0, double h, int n) {
    std::vector<double> v(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) v[static_cast<std::size_t>(k)] = f(x0 + k * h);
    return v;
}

/// A polynomial of degree d with coefficients that do not cancel.
double poly(int d, double x) {
    double p = 0.0;
    for (int k = 0; k <= d; ++k) p += (1.0 + 0.3 * k) * std::pow(x, k);
    return p;
}
double poly_derivative(int d, double x) {
    double p = 0.0;
    for (int k = 1; k <= d; ++k) p += k * (1.0 + 0.3 * k) * std::pow(x, k - 1);
    return p;
}

TEST(Eno, DerivativeIsExactForPolynomialsOfItsOrder) {
    const double h = 0.1, x0 = -0.45;
    for (int order = 1; order <= eno::max_order; ++order) {
        const auto f = samples([&](double x) { return poly(order, x); }, x0, h, 12);
        std::vector<double> d(f.size());
        eno::derivative(f, h, order, d);
        for (std::size_t k = 0; k < f.size(); ++k)
            EXPECT_NEAR(d[k], poly_derivative(order, x0 + static_cast<double>(k) * h),
                        polynomial_tolerance)
                << "order " << order << " node " << k;
    }
}

TEST(Eno, InterpolationIsExactForPolynomialsOfItsOrder) {
    const double h = 0.1, x0 = -0.45;
    for (int order = 1; order <= eno::max_order; ++order) {
        const auto f = samples([&](double x) { return poly(order, x); }, x0, h, 10);
        for (std::size_t i = 0; i + 1 < f.size(); ++i) {
            for (double theta : {0.0, 0.3, 0.77, 1.0}) {
                const double x = x0 + (static_cast<double>(i) + theta) * h;
                EXPECT_NEAR(eno::interpolate(f, i, theta, order), poly(order, x),
                            polynomial_tolerance);
            }
        }
    }
}

/// Maximum error of the ENO derivative of sin(3x) + x² on [0, 1] with n intervals.
double derivative_error(int order, int n) {
    const double h = 1.0 / n;
    const auto f = samples([](double x) { return std::sin(3 * x) + x * x; }, 0.0, h, n + 1);
    std::vector<double> d(f.size());
    eno::derivative(f, h, order, d);
    double e = 0.0;
    for (int k = 0; k <= n; ++k)
        e = std::max(
            e, std::abs(d[static_cast<std::size_t>(k)] - (3 * std::cos(3 * k * h) + 2 * k * h)));
    return e;
}

/// Maximum error of ENO interpolation of the same function at cell midpoints.
double interpolation_error(int order, int n) {
    const double h = 1.0 / n;
    const auto f = samples([](double x) { return std::sin(3 * x) + x * x; }, 0.0, h, n + 1);
    double e = 0.0;
    for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) * h;
        e = std::max(e, std::abs(eno::interpolate(f, static_cast<std::size_t>(i), 0.5, order) -
                                 (std::sin(3 * x) + x * x)));
    }
    return e;
}

TEST(Eno, DerivativeOfOrderEConvergesAtOrderE) {
    for (int order = 1; order <= 4; ++order) {
        const double observed =
            std::log2(derivative_error(order, 32) / derivative_error(order, 64));
        std::printf("ENO derivative, order %d: observed order %.2f\n", order, observed);
        EXPECT_GT(observed, order - order_slack) << "order " << order;
    }
}

TEST(Eno, InterpolationOfOrderEConvergesAtOrderEPlus1) {
    for (int order = 1; order <= 4; ++order) {
        const double observed =
            std::log2(interpolation_error(order, 32) / interpolation_error(order, 64));
        std::printf("ENO interpolation, order %d: observed order %.2f\n", order, observed);
        EXPECT_GT(observed, order + 1 - order_slack) << "order " << order;
    }
}

TEST(Eno, DerivativeAvoidsAKinkThatCentredDifferencesCross) {
    // F = |x − x0| − 1, a distance function with its kink between nodes 7 and 8. Nodes two or
    // more steps from the kink's cell have an ENO stencil on their own side: slope exactly ±1.
    const double h = 0.1, x0 = 0.73;
    const auto f = samples([&](double x) { return std::abs(x - x0) - 1.0; }, 0.0, h, 16);
    for (int order = 2; order <= 3; ++order) {
        std::vector<double> d(f.size());
        eno::derivative(f, h, order, d);
        for (std::size_t k = 0; k < f.size(); ++k) {
            if (k + 1 >= 7 && k <= 9) continue;  // nodes 6..9 touch the kink's neighbourhood
            EXPECT_NEAR(d[k], k <= 7 ? -1.0 : 1.0, polynomial_tolerance)
                << "order " << order << " node " << k;
        }
    }
    // Eq. 10 at node 7 straddles the kink: slope −0.3 instead of −1.
    EXPECT_GT(std::abs((f[8] - f[6]) / (2 * h) + 1.0), 0.5);
}

TEST(Eno, BiasedDerivativeKeepsOneStencilAcrossASmallKinkAndAvoidsALargeOne) {
    // A kink of small angle on curved data (the distance to a polygon inside it, across a
    // vertex's bisector): slope x then x + 0.05. The plain rule takes the smaller difference, so
    // the stencils of the nodes near the kink step round it or not; with a bias of 2 every
    // interior node keeps the stencil the rule grows on smooth data, {k − 1, k, k + 1} for E = 2.
    const double h = 0.1, x0 = 0.73;
    const auto f =
        samples([&](double x) { return 0.5 * x * x + 0.05 * std::max(0.0, x - x0); }, 0.0, h, 16);
    std::vector<double> biased(f.size()), plain(f.size());
    eno::derivative(f, h, 2, biased, 2.0);
    eno::derivative(f, h, 2, plain);
    int differ = 0;
    for (std::size_t k = 1; k + 1 < f.size(); ++k) {
        const double centred = (f[k + 1] - f[k - 1]) / (2 * h);
        EXPECT_NEAR(biased[k], centred, polynomial_tolerance) << "node " << k;
        if (std::abs(plain[k] - centred) > 1e-3) ++differ;
    }
    EXPECT_GE(differ, 1);  // the plain rule does not
    // A kink of large angle (a medial axis): the biased rule still steps round it.
    const auto g = samples([&](double x) { return std::abs(x - x0) - 1.0; }, 0.0, h, 16);
    for (int order = 2; order <= 3; ++order) {
        std::vector<double> d(g.size());
        eno::derivative(g, h, order, d, 2.0);
        for (std::size_t k = 0; k < g.size(); ++k) {
            if (k + 1 >= 7 && k <= 9) continue;
            EXPECT_NEAR(d[k], k <= 7 ? -1.0 : 1.0, polynomial_tolerance)
                << "order " << order << " node " << k;
        }
    }
    // A bias of 1 is the plain rule.
    std::vector<double> one(f.size());
    eno::derivative(f, h, 2, one, 1.0);
    EXPECT_EQ(one, plain);
}

TEST(Eno, InterpolationAvoidsAJumpInOtherCells) {
    // Piecewise quadratic data with a jump in cell [5, 6]: every other cell is interpolated
    // exactly by order 2, because every stencil containing the jump has a larger difference.
    const double h = 0.1;
    auto g = [](double x) { return x < 0.55 ? x * x : 3.0 - x * x; };
    const auto f = samples(g, 0.0, h, 12);
    for (std::size_t i = 0; i + 1 < f.size(); ++i) {
        if (i == 5) continue;
        const double x = (static_cast<double>(i) + 0.4) * h;
        EXPECT_NEAR(eno::interpolate(f, i, 0.4, 2), g(x), polynomial_tolerance) << "cell " << i;
    }
}

TEST(Eno, StencilsStayInsideShortLines) {
    // Two samples allow only order 1, whatever order is asked: exact for linear data.
    const std::vector<double> f = {1.0, 1.5};
    std::vector<double> d(2);
    eno::derivative(f, 0.5, 3, d);
    EXPECT_DOUBLE_EQ(d[0], 1.0);
    EXPECT_DOUBLE_EQ(d[1], 1.0);
    EXPECT_DOUBLE_EQ(eno::interpolate(f, 0, 0.5, 3), 1.25);
    const eno::Stencil s = eno::stencil(f, 0, 0, 3);
    EXPECT_EQ(s.first, 0u);
    EXPECT_EQ(s.points, 2);
}

TEST(Eno, SmoothingRemovesTheSawtoothAndKeepsLinesAndEnds) {
    std::vector<double> saw(9), linear(9), out(9);
    for (std::size_t k = 0; k < saw.size(); ++k) {
        saw[k] = k % 2 == 0 ? 1.0 : -1.0;
        linear[k] = 2.0 + 0.5 * static_cast<double>(k);
    }
    eno::smooth(saw, out);
    EXPECT_EQ(out.front(), saw.front());
    EXPECT_EQ(out.back(), saw.back());
    for (std::size_t k = 1; k + 1 < out.size(); ++k) EXPECT_EQ(out[k], 0.0);
    eno::smooth(linear, out);
    for (std::size_t k = 0; k < out.size(); ++k) EXPECT_DOUBLE_EQ(out[k], linear[k]);
}

}  // namespace
}  // namespace slc
