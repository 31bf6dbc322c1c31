// The smooth sampling of curves and the single-layer equation, against potentials known exactly
// on circles.
#include "slc/potential/boundary_integral.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

using std::numbers::pi;

/// A counterclockwise circle of n vertices, the first at angle `phase`.
std::vector<Vec2> circle(Vec2 centre, double r, std::size_t n, double phase = 0.0) {
    std::vector<Vec2> p;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = phase + 2 * pi * static_cast<double>(i) / static_cast<double>(n);
        p.push_back(centre + r * Vec2{std::cos(a), std::sin(a)});
    }
    return p;
}

/// The angle of each sample about centre.
double angle(Vec2 x, Vec2 centre) { return std::atan2(x.y - centre.y, x.x - centre.x); }

TEST(SmoothCurves, ACirclesSplineHasItsCurvatureNormalAndSpeed) {
    const double r = 0.7;
    const Interface curves({circle({0.2, -0.1}, r, 200)});
    const SmoothCurves s = smooth_curves(curves);
    ASSERT_EQ(s.curve_count(), 1u);
    EXPECT_EQ(s.count(0), 200u);
    double worst_c = 0, worst_n = 0, worst_x = 0;
    for (std::size_t j = 0; j < s.x.size(); ++j) {
        const Vec2 radial = (s.x[j] - Vec2{0.2, -0.1}) / r;
        worst_x = std::max(worst_x, std::abs(norm(s.x[j] - Vec2{0.2, -0.1}) - r));
        worst_c = std::max(worst_c, std::abs(s.curvature[j] + 1.0 / r));
        worst_n = std::max(worst_n, norm(s.normal[j] - radial));
        EXPECT_NEAR(s.speed[j], s.length[0] / (2 * pi), 1e-3 * r);
    }
    // h = 0.022: the spline's position error ~h⁴/R³, its curvature's h²/12R³ = 1.2e−4.
    const double h = 2 * pi * r / 200;
    EXPECT_LT(worst_x, 1e-7);
    EXPECT_LT(worst_c, 0.1 * h * h / (r * r * r));
    EXPECT_LT(worst_n, 1e-6);
    for (std::size_t v = 0; v < curves.size(); ++v)
        EXPECT_LT(norm(s.vertex_normal[v] - (curves.point(v) - Vec2{0.2, -0.1}) / r), 1e-6);
}

TEST(SmoothCurves, TrigonometricInterpolationIsExactForResolvedModes) {
    // Vertices unevenly spaced along an ellipse; g = a trigonometric polynomial of τ.
    std::vector<Vec2> p;
    for (int i = 0; i < 90; ++i) {
        const double a = 2 * pi * (i + 0.3 * std::sin(i)) / 90.0;
        p.push_back({1.5 * std::cos(a), 0.6 * std::sin(a)});
    }
    const Interface curves({p});
    const SmoothCurves s = smooth_curves(curves);
    auto g = [](double t) { return 0.3 + std::cos(3 * t) - 0.5 * std::sin(17 * t); };
    std::vector<double> samples;
    for (std::size_t j = 0; j < s.count(0); ++j)
        samples.push_back(g(2 * pi * static_cast<double>(j) / static_cast<double>(s.count(0))));
    const std::vector<double> at = interpolate_at_vertices(s, 0, samples);
    ASSERT_EQ(at.size(), p.size());
    for (std::size_t v = 0; v < p.size(); ++v) EXPECT_NEAR(at[v], g(s.vertex_tau[v]), 1e-12);

    // The filter multiplies mode m by filter(2π m / L).
    std::vector<double> filtered = samples;
    filter_modes(s, 0, filtered, [&](double xi) { return xi == 0 ? 1.0 : 0.5; });
    for (std::size_t j = 0; j < s.count(0); ++j)
        EXPECT_NEAR(filtered[j], 0.3 + 0.5 * (samples[j] - 0.3), 1e-12);
}

TEST(SingleLayer, OnACircleTheDensityIsTheFluxJumpOfEachMode) {
    // f = cos mθ on a circle of radius R: u = (r/R)^m cos mθ inside, (R/r)^m cos mθ outside,
    // so μ = −[∂u/∂N] = 2m/R cos mθ and u∞ = 0; f = 1: u = 1 everywhere, μ = 0, u∞ = 1.
    const double r = 0.8;
    const Vec2 c{0.3, 0.1};
    const Interface curves({circle(c, r, 128, 0.1)});
    const SmoothCurves s = smooth_curves(curves);
    for (int m : {0, 1, 3, 7}) {
        std::vector<double> f;
        for (Vec2 x : s.x) f.push_back(std::cos(m * angle(x, c)));
        const SingleLayerSolution sol = solve_single_layer(s, f);
        double worst = 0;
        for (std::size_t j = 0; j < s.x.size(); ++j)
            worst = std::max(worst,
                             std::abs(sol.density[j] - 2 * m / r * std::cos(m * angle(s.x[j], c))));
        EXPECT_LT(worst, 1e-6 * (m + 1)) << "mode " << m;
        EXPECT_NEAR(sol.u_infinity, m == 0 ? 1.0 : 0.0, 1e-9) << "mode " << m;

        // K'μ for μ = cos mθ: ∂u_in/∂N = K'μ + μ/2 = 0 for m = 0 and μ/2 for m ≥ 1.
        std::vector<double> mu;
        for (Vec2 x : s.x) mu.push_back(std::cos(m * angle(x, c)));
        const std::vector<double> k = adjoint_double_layer(s, mu);
        for (std::size_t j = 0; j < s.x.size(); ++j)
            EXPECT_NEAR(k[j], m == 0 ? -0.5 : 0.0, 1e-6) << "mode " << m;
    }
}

TEST(SingleLayer, OfTwoCirclesOnlyTheOneHoldingThePoleCarriesDensity) {
    // f = Re 1/(z − c1): outside both circles and inside circle 2 it is its own harmonic
    // extension; inside circle 1 the extension is r cos θ / R1². So μ = 2 cos θ / R1² on circle 1,
    // 0 on circle 2, and u∞ = 0. The unit circle 2 (capacity 1) would make S alone singular.
    const Vec2 c1{-1.2, 0.3}, c2{1.0, -0.2};
    const double r1 = 0.5;
    for (std::size_t n : {48u, 400u}) {  // the direct solve, and GMRES beyond 600 samples
        const Interface curves({circle(c1, r1, n), circle(c2, 1.0, 2 * n)});
        const SmoothCurves s = smooth_curves(curves);
        std::vector<double> f;
        for (Vec2 x : s.x) {
            const Vec2 d = x - c1;
            f.push_back(d.x / norm2(d));
        }
        const SingleLayerSolution sol = solve_single_layer(s, f);
        EXPECT_EQ(sol.iterations > 0, s.x.size() > 600);
        double worst = 0;
        for (std::size_t j = 0; j < s.x.size(); ++j) {
            const double exact =
                j < s.offsets[1] ? 2 * std::cos(angle(s.x[j], c1)) / (r1 * r1) : 0.0;
            worst = std::max(worst, std::abs(sol.density[j] - exact));
        }
        EXPECT_LT(worst, n == 48 ? 1e-3 : 1e-8) << n;
        EXPECT_NEAR(sol.u_infinity, 0.0, n == 48 ? 1e-6 : 1e-8) << n;
    }
}

TEST(SingleLayer, ManyParticlesConvergeInAFewIterationsToTheDirectSolution) {
    // 24 three-lobed particles of radii 0.05–0.15 a few radii apart, 32 samples each (768: the
    // GMRES path). Each particle's own system and the particles' charges are solved exactly by the
    // preconditioner, so GMRES only resolves the dipoles and beyond: few iterations, however many
    // particles. Compared with the augmented system solved directly.
    std::vector<std::vector<Vec2>> particles;
    for (int i = 0; i < 24; ++i) {
        const Vec2 c{-1.0 + 0.4 * (i % 6) + 0.05 * std::sin(i),
                     -0.6 + 0.4 * (i / 6.0 - i % 6 / 6.0)};
        const double r = 0.05 + 0.1 * (0.5 + 0.5 * std::sin(3.0 * i));
        std::vector<Vec2> p = circle(c, r, 32, 0.3 * i);
        for (Vec2& x : p) x = c + (1.0 + 0.1 * std::cos(3 * angle(x, c))) * (x - c);
        particles.push_back(p);
    }
    const Interface curves(particles);
    const SmoothCurves s = smooth_curves(curves);
    const std::size_t n = s.x.size();
    ASSERT_GT(n, 600u);
    std::vector<double> f(n);
    for (std::size_t i = 0; i < n; ++i) f[i] = -s.curvature[i];
    const SingleLayerSolution sol = solve_single_layer(s, f);
    EXPECT_GT(sol.iterations, 0);
    EXPECT_LE(sol.iterations, 30) << sol.iterations;

    const std::vector<double> a = single_layer_matrix(s);
    std::vector<double> full((n + 1) * (n + 1), 0.0), b(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n; ++j) full[i * (n + 1) + j] = a[i * n + j];
        full[i * (n + 1) + n] = 1.0;
        full[n * (n + 1) + i] = 2 * pi / 32;
        b[i] = f[i];
    }
    const std::optional<std::vector<double>> direct = solve_dense(full, b);
    ASSERT_TRUE(direct);
    double worst = 0, scale = 0;
    for (std::size_t j = 0; j < n; ++j) {
        worst = std::max(worst, std::abs(sol.density[j] - (*direct)[j] / s.speed[j]));
        scale = std::max(scale, std::abs(sol.density[j]));
    }
    EXPECT_LT(worst, 1e-10 * scale);
    EXPECT_NEAR(sol.u_infinity, (*direct)[n], 1e-10 * std::abs((*direct)[n]));

    // GMRES's products run on the worker threads, each row in one order: one thread gives the
    // same solution to the last bit.
    set_thread_count(1);
    const SingleLayerSolution one = solve_single_layer(s, f);
    set_thread_count(0);
    EXPECT_EQ(one.density, sol.density);
    EXPECT_EQ(one.u_infinity, sol.u_infinity);

    // Each particle its own interior problem: the preconditioner is the inverse.
    std::vector<std::size_t> group(curves.curve_count());
    for (std::size_t c = 0; c < group.size(); ++c) group[c] = c;
    const std::vector<double> f_all[] = {f};
    EXPECT_LE(SingleLayerSystem(s, group).solve(f_all).front().iterations, 2);
}

TEST(SmoothCurves, AVertexARoundingErrorFromTheNextIsLeftOutOfTheSpline) {
    // A contour can place two vertices 1e−12 apart; the spline through both would turn there.
    std::vector<Vec2> p = circle({0, 0}, 0.5, 100);
    p.insert(p.begin() + 40, p[40] + Vec2{1e-12, -1e-12});
    const Interface curves({p});
    const SmoothCurves s = smooth_curves(curves);
    for (double c : s.curvature) EXPECT_NEAR(c, -2.0, 1e-2);
    EXPECT_NEAR(s.vertex_tau[40], s.vertex_tau[41], 1e-10);
    EXPECT_LT(norm(s.vertex_normal[41] - p[41] / 0.5), 1e-5);
}

}  // namespace
}  // namespace slc
