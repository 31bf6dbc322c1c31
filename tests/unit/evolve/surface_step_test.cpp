// Tests of the surface step: a user's lambdas give the built-in laws' results, the same surface
// for any thread count, bad input. Its accuracy against exact motions over several steps is in
// tests/accuracy/surface_step_test.cpp.
#include "slc/evolve/surface_step.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <type_traits>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/velocity/surface_laws.hpp"

namespace slc {
namespace {

const Box3 unit_domain{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}};

/// Refinement until every midpoint and centroid is within tolerance.
SurfaceStepOptions refined(int depth, double tolerance) {
    return {.contour = {.depth = depth,
                        .refine_passes = SurfaceContourOptions::until_converged,
                        .eps = tolerance}};
}

TEST(SurfaceStep, UsersLambdasInSpace) {
    // A field and a normal speed written as lambdas taking Vec3: the same motions as the
    // built-in laws, to rounding of the contours.
    const auto spin = field_law("spin", [](double, Vec3 x) { return Vec3{-x.y, x.x, 0.0}; });
    const auto grow = normal_law("grow", [](double, Vec3, Vec3) { return 1.0; });
    static_assert(std::is_same_v<decltype(spin)::element_type, SurfaceVelocityLaw>);
    const Surface start = sphere({0.3, 0.0, 0.0}, 0.2, 3);
    const SurfaceStepOptions o = refined(4, 1e-3);
    const Surface a = advance(start, 0.0, 0.1, *spin, unit_domain, o).surface;
    const Surface b = advance(start, 0.0, 0.1, SurfaceRotation(), unit_domain, o).surface;
    EXPECT_EQ(a.vertices, b.vertices);
    const Surface c = advance(start, 0.0, 0.1, *grow, unit_domain, o).surface;
    const Surface d = advance(start, 0.0, 0.1, SurfaceNormalSpeed(), unit_domain, o).surface;
    EXPECT_EQ(c.vertices, d.vertices);
}

TEST(SurfaceStep, AConstantSpeedsStepIsItsPredictorToTheLastBit) {
    // As for curves: the built-in constant speed ends at the predicted contour, the lambda of the
    // same speed (no constant speed claimed) runs the corrector too, and the surfaces agree.
    const auto lambda = normal_law("shrink", [](double, Vec3, Vec3) { return -1.0; });
    ASSERT_FALSE(lambda->constant_speed());
    const Surface start = box_surface({-0.45, -0.52, -0.47}, {0.55, 0.48, 0.53}, 4);
    const SurfaceStepOptions o = refined(4, 1e-3);
    const SurfaceStepResult whole = advance(start, 0.0, 0.1, *lambda, unit_domain, o);
    const SurfaceStepResult predicted =
        advance(start, 0.0, 0.1, SurfaceNormalSpeed(-1.0), unit_domain, o);
    EXPECT_EQ(predicted.surface.vertices, whole.surface.vertices);
    EXPECT_EQ(predicted.surface.triangles, whole.surface.triangles);
    EXPECT_GT(whole.stats.predictor.g_evals, 0u);
    EXPECT_EQ(predicted.stats.predictor.g_evals, 0u);
    EXPECT_LT(predicted.stats.g_evals(), whole.stats.g_evals());
}

TEST(SurfaceStep, SameSurfaceForAnyThreadCount) {
    const SurfaceMeanCurvatureFlow law;
    const Surface start = torus({}, 0.5, 0.2, 32, 16);
    set_thread_count(1);
    const Surface one = advance(start, 0.0, 1e-3, law, unit_domain, refined(4, 1e-3)).surface;
    set_thread_count(2);
    const Surface two = advance(start, 0.0, 1e-3, law, unit_domain, refined(4, 1e-3)).surface;
    set_thread_count(0);
    EXPECT_EQ(one.vertices, two.vertices);
    EXPECT_EQ(one.triangles, two.triangles);
}

TEST(SurfaceStep, EtaUnsetPutsTheVerticesOnTheZeroSetToTenToTheMinusTen) {
    // The next step differentiates the vertices, so a step does not take contour_surface's
    // ε/100 for η unset: the same surface as η = 10⁻¹⁰ given.
    const SurfaceStepOptions unset = refined(4, 1e-3);
    EXPECT_EQ(unset.resolved_eta(), 1e-10);
    EXPECT_DOUBLE_EQ(unset.contour.resolved_eta(), 1e-5);
    SurfaceStepOptions given = unset;
    given.contour.eta = 1e-10;
    const Surface start = sphere({0.3, 0.0, 0.0}, 0.2, 3);
    const SurfaceRotation rotation;
    const Surface a = advance(start, 0.0, 0.1, rotation, unit_domain, unset).surface;
    const Surface b = advance(start, 0.0, 0.1, rotation, unit_domain, given).surface;
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.triangles, b.triangles);
}

TEST(SurfaceStep, BadInput) {
    const Surface s = sphere({}, 0.3, 2);
    const SurfaceStepOptions o{.contour = {.depth = 3}};
    const SurfaceRotation rotation;
    EXPECT_THROW(advance(s, 0.0, 0.0, rotation, unit_domain, o), InvalidInput);
    EXPECT_THROW(advance(s, 0.0, NAN, rotation, unit_domain, o), InvalidInput);
    EXPECT_THROW(advance(Surface{}, 0.0, 0.1, rotation, unit_domain, o), InvalidInput);
    SurfaceStepOptions whitney = o;
    whitney.extension = Extension::whitney;
    EXPECT_THROW(advance(s, 0.0, 0.1, rotation, unit_domain, whitney), InvalidInput);
    SurfaceStepOptions direct = o;
    direct.extension = Extension::direct;
    EXPECT_THROW(advance(s, 0.0, 0.1, SurfaceMeanCurvatureFlow(), unit_domain, direct),
                 InvalidInput);
    // A surface carried out of the domain is a numerical failure that names the boundary.
    EXPECT_THROW(advance(s, 0.0, 1.0, SurfaceTranslation({1.0, 0.0, 0.0}), unit_domain, o),
                 LeftDomain);
    const auto bad = field_law("bad", [](double, Vec3 x) { return Vec3{1.0 / x.x, 0.0, 0.0}; });
    EXPECT_THROW(advance(s, 0.0, 0.1, *bad, unit_domain, o), NumericalFailure);
}

TEST(SurfaceStep, StepVolumeAddsThePatchesBulges) {
    // An icosphere's triangles cut inside the sphere they sample; its patches give all but 2% of
    // the difference back (measured: 320 triangles 3.4% low, their patches 0.051%; 1,280
    // triangles 0.86% and 0.0034%). Without patches the step reads the triangles.
    const double exact = 4.0 / 3.0 * std::numbers::pi * 0.125;
    for (const int subdivisions : {2, 3}) {
        const Surface s = sphere({0.1, -0.2, 0.3}, 0.5, subdivisions);
        const double chords = volume(s), patches = step_volume(s, {});
        SurfaceStepOptions flat;
        flat.patches = false;
        EXPECT_EQ(step_volume(s, flat), chords);
        EXPECT_LT(chords, patches);
        EXPECT_LT(std::abs(patches - exact), 0.02 * (exact - chords)) << subdivisions;
    }
}

}  // namespace
}  // namespace slc
