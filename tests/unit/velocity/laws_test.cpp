// Tests of the built-in velocity laws on simple cases with known answers: a rotating point, a
// translation, the single vortex, normal speeds on circles, anisotropy by normal angle, curvature
// flow, and the zero mean normal speed of the volume-preserving law.
#include "slc/velocity/laws.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/velocity/factory.hpp"

namespace slc {
namespace {

using std::numbers::pi;

/// Rounding in a few operations on values of size ~1.
constexpr double rounding_tolerance = 1e-12;

TEST(Rotation, TurnsPointsCounterclockwiseAboutItsCentre) {
    const Rotation rotation(2.0, {1.0, 1.0});
    const std::vector<Vec2> points = {{2.0, 1.0}, {1.0, 3.0}, {1.0, 1.0}};
    const auto u = field_velocities(rotation, 0.0, points);
    EXPECT_EQ(u[0], (Vec2{0.0, 2.0}));   // east of the centre moves north
    EXPECT_EQ(u[1], (Vec2{-4.0, 0.0}));  // two north moves west at twice the speed
    EXPECT_EQ(u[2], (Vec2{0.0, 0.0}));
    // At the vertices, the same values as sampled.
    const Interface curves({shapes::propeller(30)});
    EXPECT_EQ(vertex_velocities(rotation, 0.5, curves),
              field_velocities(rotation, 0.5, curves.points()));
    EXPECT_FALSE(rotation.needs().any());
}

TEST(Translation, IsTheSameEverywhereAndAtAllTimes) {
    const Translation translation({0.25, -1.5});
    const Interface curves({shapes::circle({}, 0.5, 9)});
    for (const Vec2 u : vertex_velocities(translation, 3.0, curves))
        EXPECT_EQ(u, (Vec2{0.25, -1.5}));
    EXPECT_TRUE(translation.is_field());
}

TEST(SingleVortex, MatchesLeVequesFormulaAndReversesAtHalfPeriod) {
    const SingleVortex vortex(8.0);
    const std::vector<Vec2> points = {{0.5, 0.75}, {0.25, 0.5}, {0.3, 0.6}};
    const auto u0 = field_velocities(vortex, 0.0, points);
    // At (0.5, 0.75): u = sin²(π/2)·sin(3π/2) = −1, v = −sin²(3π/4)·sin(π) = 0.
    EXPECT_NEAR(u0[0].x, -1.0, rounding_tolerance);
    EXPECT_NEAR(u0[0].y, 0.0, rounding_tolerance);
    // At (0.25, 0.5): u = ½·sin(π) = 0, v = −1·sin(π/2) = −1.
    EXPECT_NEAR(u0[1].x, 0.0, rounding_tolerance);
    EXPECT_NEAR(u0[1].y, -1.0, rounding_tolerance);
    const auto quarter = field_velocities(vortex, 2.0, points),
               half = field_velocities(vortex, 4.0, points),
               full = field_velocities(vortex, 8.0, points);
    for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_NEAR(norm(quarter[i] - std::cos(pi / 4) * u0[i]), 0.0, rounding_tolerance);
        EXPECT_NEAR(norm(half[i]), 0.0, rounding_tolerance);
        EXPECT_NEAR(norm(full[i] + u0[i]), 0.0, rounding_tolerance);
    }
    EXPECT_THROW(SingleVortex(0.0), InvalidInput);
}

TEST(SingleVortex, IsDivergenceFree) {
    // Central differences of a smooth field: error O(δ²) ~ 1e-8 times second derivatives ~ 40.
    constexpr double delta = 1e-4, divergence_tolerance = 1e-6;
    const SingleVortex vortex;
    for (const Vec2 p : {Vec2{0.3, 0.6}, Vec2{0.71, 0.12}, Vec2{0.5, 0.5}}) {
        const auto u = field_velocities(vortex, 1.0,
                                        std::vector<Vec2>{p + Vec2{delta, 0}, p - Vec2{delta, 0},
                                                          p + Vec2{0, delta}, p - Vec2{0, delta}});
        EXPECT_NEAR((u[0].x - u[1].x + u[2].y - u[3].y) / (2 * delta), 0.0, divergence_tolerance);
    }
}

TEST(NormalSpeed, OnACircleIsRadial) {
    const Vec2 centre{0.2, -0.1};
    const Interface curves({shapes::circle(centre, 0.4, 64)});
    for (const double s : {1.0, -0.5}) {
        const auto u = vertex_velocities(NormalSpeed(s), 0.0, curves);
        for (std::size_t i = 0; i < u.size(); ++i)
            EXPECT_NEAR(norm(u[i] - s * (curves.point(i) - centre) / 0.4), 0.0, rounding_tolerance);
    }
}

TEST(AnisotropicNormalSpeed, DependsOnTheNormalAngle) {
    // On a regular polygon about the origin the intrinsic normal at vertex k is exactly radial,
    // θ_k = 2πk/n, so u_k = (R + ε cos(mθ_k))·N_k.
    const double r = -1.0, m = 4.0, eps = 5.0 / 15.0;
    const int n = 48;
    const Interface curves({shapes::circle({}, 0.5, n)});
    const auto u = vertex_velocities(AnisotropicNormalSpeed(r, m, eps), 0.0, curves);
    for (int k = 0; k < n; ++k) {
        const double theta = 2 * pi * k / n;
        const Vec2 normal{std::cos(theta), std::sin(theta)};
        EXPECT_NEAR(norm(u[static_cast<std::size_t>(k)] - (r + eps * std::cos(m * theta)) * normal),
                    0.0, rounding_tolerance);
    }
}

TEST(AnisotropicNormalSpeed, TiltTurnsTheAnisotropy) {
    // v(θ) = R + ε cos(m(θ − α)): the tilted law at θ is the untilted one at θ − α.
    const double r = -1.0, m = 3.0, eps = 5.0 / 8.0, tilt = 10.0 * pi / 180.0;
    const int n = 36;
    const Interface curves({shapes::circle({}, 0.5, n)});
    const auto u = vertex_velocities(AnisotropicNormalSpeed(r, m, eps, tilt), 0.0, curves);
    for (int k = 0; k < n; ++k) {
        const double theta = 2 * pi * k / n;
        const Vec2 normal{std::cos(theta), std::sin(theta)};
        EXPECT_NEAR(norm(u[static_cast<std::size_t>(k)] -
                         (r + eps * std::cos(m * (theta - tilt))) * normal),
                    0.0, rounding_tolerance);
    }
    // Through the factory, in degrees.
    const auto law = make_velocity("anisotropic", {{"m", 3.0}, {"tilt", 10.0}});
    const auto v = vertex_velocities(*law, 0.0, curves);
    for (std::size_t k = 0; k < u.size(); ++k)
        EXPECT_NEAR(norm(v[k] - u[k]), 0.0, rounding_tolerance);
}

TEST(CurvatureFlow, ShrinksACircleAtSpeedOneOverR) {
    // Embedded module, E = 3 at M = 128: C = −1/R to ~1e-3 relative (see the geometry tests).
    constexpr double relative_tolerance = 5e-3;
    const Vec2 centre{0.01, 0.02};
    const double r = 0.6;
    const Interface curves({shapes::circle(centre, r, 3000)});
    const DistanceTree tree(curves, Box::centered_square(1.0), {.depth = 8, .triangulate = false});
    const auto u =
        vertex_velocities(CurvatureFlow(), 0.0, curves, {.tree = &tree, .embedded = {.mesh = 128}});
    for (std::size_t i = 0; i < u.size(); ++i)
        EXPECT_NEAR(norm(u[i] + (curves.point(i) - centre) / (r * r)), 0.0, relative_tolerance / r);
    // The intrinsic module gives −1/R exactly on a regular polygon, up to rounding of the
    // vertices (1e-16) divided twice by the segment length ℓ = 1.3e-3 (Eq. 8 differences normals,
    // which are themselves differences of vertices).
    constexpr double twice_differenced_rounding = 1e-9;
    const auto v = vertex_velocities(CurvatureFlow(GeometryModule::intrinsic), 0.0, curves);
    for (std::size_t i = 0; i < v.size(); ++i)
        EXPECT_NEAR(norm(v[i] + (curves.point(i) - centre) / (r * r)), 0.0,
                    twice_differenced_rounding);
}

TEST(VolumePreservingCurvatureFlow, HasZeroMeanNormalSpeed) {
    // Σ w_i (u_i · N_i) = Σ w_i (C_i − C̄) = 0 by the definition of C̄, up to rounding of the sum.
    constexpr double mean_tolerance = 1e-12;
    const Interface curves(
        {shapes::circle({-0.5, 0.0}, 0.2, 400),
         shapes::polar(
             {0.4, 0.1}, [](double t) { return 0.4 * (1 + 0.3 * std::cos(3 * t)); }, 1500)});
    const DistanceTree tree(curves, Box::centered_square(1.0), {.depth = 8, .triangulate = false});
    const auto w = vertex_arc_lengths(curves);
    for (const GeometryModule module : {GeometryModule::intrinsic, GeometryModule::embedded}) {
        const VolumePreservingCurvatureFlow law(module);
        const VertexGeometry g = vertex_geometry(law.needs(), curves, {.tree = &tree});
        const auto u = law.velocities(0.0, curves, g);
        double flux = 0.0, length = 0.0, small_circle = 0.0;
        for (std::size_t i = 0; i < u.size(); ++i) {
            flux += w[i] * dot(u[i], g.normals[i]);
            length += w[i];
            if (i < curves.offsets()[1]) small_circle += w[i] * dot(u[i], g.normals[i]);
        }
        EXPECT_NEAR(flux / length, 0.0, mean_tolerance);
        // The small circle, more curved than the mean, shrinks: it gives its area away.
        EXPECT_LT(small_circle, 0.0);
    }
}

TEST(VolumePreservingCurvatureFlow, LeavesASingleCircleAtRest) {
    const Interface curves({shapes::circle({0.1, 0.0}, 0.5, 200)});
    for (const Vec2 u :
         vertex_velocities(VolumePreservingCurvatureFlow(GeometryModule::intrinsic), 0.0, curves))
        EXPECT_NEAR(norm(u), 0.0, rounding_tolerance);
}

TEST(NormalSpeed, RefusesToRunWithoutItsGeometry) {
    const Interface curves({shapes::circle({}, 0.5, 20)});
    EXPECT_THROW(NormalSpeed(1.0).velocities(0.0, curves, {}), InvalidInput);
    EXPECT_THROW(CurvatureFlow().velocities(0.0, curves,
                                            {.normals = std::vector<Vec2>(20), .curvature = {}}),
                 InvalidInput);
}

}  // namespace
}  // namespace slc
