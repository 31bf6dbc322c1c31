// The fast summation of the boundary integral operators, against brute force and the dense
// matrices.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "log_sum.hpp"
#include "slc/core/parallel.hpp"
#include "slc/potential/boundary_integral.hpp"

namespace slc {
namespace {

using std::numbers::pi;

/// A counterclockwise three-lobed particle of n vertices about c.
std::vector<Vec2> particle(Vec2 c, double r, std::size_t n, double phase) {
    std::vector<Vec2> p;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = phase + 2 * pi * static_cast<double>(i) / static_cast<double>(n);
        p.push_back(c + r * (1.0 + 0.15 * std::cos(3 * a)) * Vec2{std::cos(a), std::sin(a)});
    }
    return p;
}

/// p particles on a jittered lattice, radii from 0.02 to 0.08, 64 vertices each.
Interface particles(int p) {
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::vector<Vec2>> curves;
    for (int i = 0; i < p; ++i) {
        const Vec2 c{0.2 * (i % 16) + 0.03 * u(random), 0.2 * (i / 16) + 0.03 * u(random)};
        curves.push_back(particle(c, 0.02 + 0.06 * u(random), 64, 6 * u(random)));
    }
    return Interface(curves);
}

TEST(LogSum, AgreesWithTheDirectSumOverPointsAtEveryScale) {
    // Clusters of points from 1e−7 to 10 across, charges of both signs, three groups.
    std::mt19937_64 random(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec2> x;
    std::vector<double> q;
    std::vector<std::size_t> group;
    for (int cluster = 0; cluster < 9; ++cluster) {
        const double size = std::pow(10.0, 1.0 - cluster);
        const Vec2 c{3.0 * u(random), 3.0 * u(random)};
        for (int k = 0; k < 400; ++k) {
            x.push_back(c + size * Vec2{u(random), u(random)});
            q.push_back(u(random));
            group.push_back(static_cast<std::size_t>(cluster % 3));
        }
    }
    const std::size_t n = x.size();
    // With the three groups, and with one (no groups given).
    for (const bool grouped : {true, false}) {
        std::vector<double> potential(n);
        std::vector<Vec2> field(n);
        detail::LogSum(
            x, grouped ? std::span<const std::size_t>(group) : std::span<const std::size_t>())
            .sum(q, potential, field);
        double worst_p = 0, worst_f = 0;
        for (std::size_t i = 0; i < n; ++i) {
            double p = 0, scale_p = 0, scale_f = 0;
            Vec2 f{};
            for (std::size_t j = 0; j < n; ++j) {
                if (j == i || (grouped && group[j] != group[i])) continue;
                const Vec2 d = x[i] - x[j];
                p += q[j] * std::log(norm(d));
                scale_p += std::abs(q[j] * std::log(norm(d)));
                f += q[j] / norm2(d) * d;
                scale_f += std::abs(q[j]) / norm(d);
            }
            worst_p = std::max(worst_p, std::abs(potential[i] - p) / scale_p);
            worst_f = std::max(worst_f, norm(field[i] - f) / scale_f);
        }
        EXPECT_LT(worst_p, 1e-14) << grouped;
        EXPECT_LT(worst_f, 1e-14) << grouped;
    }
}

TEST(FastSummation, TheSingleLayersProductIsTheDenseMatrixs) {
    const SmoothCurves s = smooth_curves(particles(24));
    const std::size_t n = s.x.size();
    std::vector<double> phi(n);
    for (std::size_t j = 0; j < n; ++j) phi[j] = std::sin(3.0 * s.x[j].x) + s.curvature[j];
    const std::vector<double> a = single_layer_matrix(s);
    const std::vector<double> fast = apply_single_layer(s, phi);
    double worst = 0, scale = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double dense = 0, size = 0;
        for (std::size_t j = 0; j < n; ++j) {
            dense += a[i * n + j] * phi[j];
            size += std::abs(a[i * n + j] * phi[j]);
        }
        worst = std::max(worst, std::abs(fast[i] - dense));
        scale = std::max(scale, size);
    }
    EXPECT_LT(worst, 1e-13 * scale);
}

TEST(FastSummation, SolvesAndDifferentiatesAsTheDenseSystem) {
    // 96 particles, 6,144 samples: the dense system by GMRES beside the fast one.
    const SmoothCurves s = smooth_curves(particles(96));
    const std::size_t n = s.x.size();
    std::vector<double> f(n);
    for (std::size_t i = 0; i < n; ++i) f[i] = -s.curvature[i];
    const std::vector<double> f_all[] = {f};
    const SingleLayerSystem dense(s, {}, Summation::dense), fast(s, {}, Summation::fast);
    ASSERT_FALSE(dense.sums_fast());
    ASSERT_TRUE(fast.sums_fast());
    const SingleLayerSolution a = dense.solve(f_all).front(), b = fast.solve(f_all).front();
    EXPECT_LE(b.iterations, 40);
    double worst = 0, scale = 0;
    for (std::size_t j = 0; j < n; ++j) {
        worst = std::max(worst, std::abs(a.density[j] - b.density[j]));
        scale = std::max(scale, std::abs(a.density[j]));
    }
    EXPECT_LT(worst, 1e-9 * scale);
    EXPECT_NEAR(a.u_infinity, b.u_infinity, 1e-10 * std::abs(a.u_infinity));
    const std::vector<double> k_dense = adjoint_double_layer(s, a.density, {}, Summation::dense);
    const std::vector<double> k_fast = adjoint_double_layer(s, a.density, {}, Summation::fast);
    worst = scale = 0;
    for (std::size_t j = 0; j < n; ++j) {
        worst = std::max(worst, std::abs(k_dense[j] - k_fast[j]));
        scale = std::max(scale, std::abs(k_dense[j]));
    }
    EXPECT_LT(worst, 1e-12 * scale);

    // Each particle its own group (Hele-Shaw's interior problems).
    std::vector<std::size_t> group(s.curve_count());
    for (std::size_t c = 0; c < group.size(); ++c) group[c] = c % 5;
    const SingleLayerSolution ga = SingleLayerSystem(s, group, Summation::dense).solve(f_all)[0];
    const SingleLayerSolution gb = SingleLayerSystem(s, group, Summation::fast).solve(f_all)[0];
    worst = scale = 0;
    for (std::size_t j = 0; j < n; ++j) {
        worst = std::max(worst, std::abs(ga.density[j] - gb.density[j]));
        scale = std::max(scale, std::abs(ga.density[j]));
    }
    EXPECT_LT(worst, 1e-9 * scale);
    for (std::size_t g = 0; g < 5; ++g)
        EXPECT_NEAR(ga.constants[g], gb.constants[g], 1e-10 * std::abs(ga.constants[g]));

    // The same to the last bit on one thread.
    set_thread_count(1);
    const SingleLayerSolution one = SingleLayerSystem(s, {}, Summation::fast).solve(f_all)[0];
    set_thread_count(0);
    EXPECT_EQ(one.density, b.density);
}

}  // namespace
}  // namespace slc
