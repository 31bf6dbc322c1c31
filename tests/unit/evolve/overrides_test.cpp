#include "slc/evolve/overrides.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "slc/core/error.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/velocity/laws.hpp"
#include "slc/velocity/potential_laws.hpp"
#include "slc/velocity/surface_laws.hpp"

namespace slc {
namespace {

/// The message of the InvalidInput that f throws, or "" when it throws none.
template <class F>
std::string message_of(F&& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

TEST(EpsForDepth, FollowsEachDimensionsRuleAndItsDefaults) {
    // Curves: 10^-K ℓ as the paper's runs N/S/K/P/ε, not below 1e-13 ℓ.
    EXPECT_EQ(eps_for_depth(2, 5, 1.0), 1e-5);
    EXPECT_EQ(eps_for_depth(2, 7, 2.0), 2e-7);
    EXPECT_EQ(eps_for_depth(2, 20, 1.0), 1e-13);
    // Surfaces: 1e-3 ℓ at K = 5, a quarter per level deeper.
    EXPECT_EQ(eps_for_depth(3, 5, 1.0), 1e-3);
    EXPECT_DOUBLE_EQ(eps_for_depth(3, 6, 2.0), 5e-4);
    EXPECT_DOUBLE_EQ(eps_for_depth(3, 3, 1.0), 1.6e-2);
    // A user's own shape defaults to the same rule at its K.
    const Interface curves(std::vector<std::vector<Vec2>>{shapes::circle({0.0, 0.0}, 2.0, 64)});
    const RunOptions c = default_run_options(curves, NormalSpeed(1.0), 0.0, 1.0);
    EXPECT_EQ(*c.step.contour.eps, eps_for_depth(2, c.step.contour.depth, length_scale(curves)));
    const Surface ball = sphere({0.0, 0.0, 0.0}, 2.0, 2);
    const SurfaceRunOptions s = default_surface_run_options(ball, SurfaceNormalSpeed(), 0.0, 1.0);
    EXPECT_EQ(*s.step.contour.eps, eps_for_depth(3, s.step.contour.depth, length_scale(ball)));
}

TEST(DefaultSteps, AStiffLawTakesAsManyAsTheSharpestTurnNeeds) {
    // 40, or 4tσ(D_in + D_out)|C|³ at the start's sharpest turn under the potential laws, up to
    // 2,000: the tips of an ellipse 0.8 × 0.4 turn at C = 5.
    std::vector<Vec2> ellipse;
    for (int i = 0; i < 256; ++i) {
        const double a = 2 * std::numbers::pi * i / 256;
        ellipse.push_back({0.8 * std::cos(a), 0.4 * std::sin(a)});
    }
    const Interface oval(std::vector<std::vector<Vec2>>{ellipse});
    EXPECT_EQ(default_run_options(oval, HeleShaw(), 0.0, 0.5).steps, 250);
    EXPECT_EQ(default_run_options(oval, MullinsSekerka(), 0.0, 0.5).steps, 500);
    EXPECT_EQ(default_run_options(oval, HeleShaw(0.1), 0.0, 0.5).steps, 40);
    EXPECT_EQ(default_run_options(oval, NormalSpeed(1.0), 0.0, 0.5).steps, 40);
    const Interface speck(std::vector<std::vector<Vec2>>{shapes::circle({0.0, 0.0}, 0.01, 64)});
    EXPECT_EQ(default_run_options(speck, HeleShaw(), 0.0, 1.0).steps, 2000);
}

TEST(DefaultSteps, AFlowFieldOfCurvesTakesTen) {
    // A flow field stepped directly adds its contour's error each step, whatever the step's
    // length: curves take ten steps, where the other laws take 40; a surface keeps its 20.
    const Interface curves(std::vector<std::vector<Vec2>>{shapes::circle({0.5, 0.0}, 1.0, 64)});
    EXPECT_EQ(default_run_options(curves, Rotation(), 0.0, 6.0).steps, 10);
    EXPECT_EQ(default_run_options(curves, NormalSpeed(1.0), 0.0, 6.0).steps, 40);
    const Surface ball = sphere({0.5, 0.0, 0.0}, 1.0, 2);
    EXPECT_EQ(default_surface_run_options(ball, SurfaceRotation(), 0.0, 6.0).steps, 20);
    EXPECT_EQ(default_surface_run_options(ball, SurfaceNormalSpeed(), 0.0, 6.0).steps, 20);
}

TEST(RunOptions, AUsersRunTakesAWholeNumberOfStepsAFrame) {
    const Interface curves(std::vector<std::vector<Vec2>>{shapes::circle({0.0, 0.0}, 1.0, 64)});
    const Box domain = default_domain(curves.curves());
    const Problem users = curve_problem("c", curves, domain, 0.0, 6.0, Rotation(), "rotation", {});
    EXPECT_EQ(run_options(users, {}).steps, 10);
    EXPECT_EQ(run_options(users, {.frames = 5}).steps, 10);
    EXPECT_EQ(run_options(users, {.frames = 4}).steps, 12);  // frames at evenly spaced times
    EXPECT_EQ(run_options(users, {.frames = 30}).steps, 30);
    EXPECT_EQ(run_options(users, {.steps = 4, .frames = 30}).steps, 4);  // N given: kept
    // Evaluated otherwise than directly, a flow field's steps have a time error: 40.
    EXPECT_EQ(run_options(users, {.extension = Extension::nearest_point}).steps, 40);
    EXPECT_EQ(run_options(users, {.extension = Extension::direct}).steps, 10);
    // A named problem keeps the paper's N, however many frames.
    const Problem named = make_problem("zalesak");
    EXPECT_EQ(run_options(named, {.frames = 100'000}).steps, problem_run_options(named).steps);

    SurfaceProblem surface;
    surface.initial = sphere({0.0, 0.0, 0.0}, 1.0, 2);
    surface.law = std::make_unique<SurfaceRotation>();
    surface.domain = default_domain(bounding_box(surface.initial));
    surface.t_end = 6.0;
    EXPECT_EQ(surface_run_options(surface, false, 0.0, {}).steps, 20);
    EXPECT_EQ(surface_run_options(surface, false, 0.0, {.frames = 25}).steps, 25);
    EXPECT_EQ(surface_run_options(surface, false, 0.0, {.frames = 3}).steps, 21);
    EXPECT_EQ(surface_run_options(surface, false, 0.0, {.steps = 3, .frames = 25}).steps, 3);
    const SurfaceProblem enright = make_surface_problem("enright");
    EXPECT_EQ(surface_run_options(enright, true, 0.0, {.frames = 100}).steps, enright.steps);
}

TEST(ApplyOverrides, DepthSetsEpsInBothDimensions) {
    const RunOverrides q{.depth = 6};
    const RunOptions c = apply_overrides(q, RunOptions{}, 2.0);
    EXPECT_EQ(c.step.contour.depth, 6);
    EXPECT_EQ(*c.step.contour.eps, eps_for_depth(2, 6, 2.0));
    EXPECT_EQ(c.step.embedded.mesh, 128);  // 2^(K+1)
    const SurfaceRunOptions s = apply_overrides(q, SurfaceRunOptions{}, 2.0);
    EXPECT_EQ(s.step.contour.depth, 6);
    EXPECT_EQ(*s.step.contour.eps, eps_for_depth(3, 6, 2.0));
    // ε given wins over the rule.
    const RunOverrides both{.depth = 6, .eps = 1e-4};
    EXPECT_EQ(*apply_overrides(both, RunOptions{}, 1.0).step.contour.eps, 1e-4);
    EXPECT_EQ(*apply_overrides(both, SurfaceRunOptions{}, 1.0).step.contour.eps, 1e-4);
}

TEST(ApplyOverrides, UnsetSettingsKeepTheDefaults) {
    RunOptions c;
    c.steps = 17;
    c.step.contour.eps = 3e-4;
    const RunOptions got = apply_overrides({}, c, 1.0);
    EXPECT_EQ(got.steps, 17);
    EXPECT_EQ(*got.step.contour.eps, 3e-4);
    EXPECT_EQ(got.step.contour.resolved_eta(), c.step.contour.resolved_eta());
    SurfaceRunOptions s;
    s.steps = 9;
    s.step.contour.thin_depth = 2;
    const SurfaceRunOptions sgot = apply_overrides({}, s, 1.0);
    EXPECT_EQ(sgot.steps, 9);
    EXPECT_EQ(sgot.step.contour.thin_depth, 2);
    EXPECT_FALSE(sgot.step.contour.eta.has_value());
}

TEST(ApplyOverrides, EtaOfCurvesFollowsEpsDownWhenUnset) {
    const RunOptions c = apply_overrides({.eps = 1e-12}, RunOptions{}, 1.0);
    EXPECT_EQ(c.step.contour.eta, 1e-13);
    EXPECT_EQ(message_of([] { apply_overrides({.eps = 1e-12, .eta = 1e-10}, RunOptions{}, 1.0); }),
              "eps (1e-12) must not be below eta (1e-10)");
    EXPECT_EQ(message_of([] {
                  apply_overrides({.eps = 1e-12, .eta = 1e-10}, SurfaceRunOptions{}, 1.0,
                                  SettingNames::tool);
              }),
              "--eps (1e-12) must not be below --eta (1e-10)");
}

TEST(ApplyOverrides, RangesAreTheSameForTheToolAndPython) {
    EXPECT_EQ(message_of([] { apply_overrides({.depth = 25}, RunOptions{}, 1.0); }),
              "depth: must be an integer from 1 to 24 for curves, got 25");
    EXPECT_EQ(message_of([] {
                  apply_overrides({.depth = 21}, SurfaceRunOptions{}, 1.0, SettingNames::tool);
              }),
              "--depth: must be an integer from 1 to 19 for a surface, got 21");
    EXPECT_EQ(message_of([] { apply_overrides({.steps = 0}, RunOptions{}, 1.0); }),
              "steps: must be an integer from 1 to 100000000, got 0");
    EXPECT_EQ(message_of([] { apply_overrides({.refine = 65}, SurfaceRunOptions{}, 1.0); }),
              "refine: must be an integer from 0 to 64 or 'converged', got 65");
    EXPECT_EQ(message_of([] {
                  apply_overrides({.refine = ContourOptions::until_converged}, RunOptions{}, 1.0);
              }),
              "");
    EXPECT_EQ(message_of([] { apply_overrides({.eta = -1.0}, SurfaceRunOptions{}, 1.0); }),
              "eta: must be a positive finite number, got -1");
    EXPECT_EQ(message_of([] { apply_overrides({.thin_depth = 9}, SurfaceRunOptions{}, 1.0); }),
              "thin_depth: must be an integer from 0 to 8, got 9");
    EXPECT_EQ(message_of([] { apply_overrides({.rho = 1.0}, RunOptions{}, 1.0); }),
              "rho: must be in [0, 1), got 1");
}

TEST(ApplyOverrides, SettingsOfTheOtherDimensionAreRefusedByName) {
    EXPECT_EQ(message_of([] { apply_overrides({.volume_drift = 0.1}, RunOptions{}, 1.0); }),
              "volume_drift is for surfaces, not curves");
    EXPECT_EQ(message_of([] {
                  apply_overrides({.mesh = 64}, SurfaceRunOptions{}, 1.0, SettingNames::tool);
              }),
              "--mesh is for curves, not surfaces");
    EXPECT_EQ(message_of([] {
                  apply_overrides({.extension = Extension::whitney}, SurfaceRunOptions{}, 1.0);
              }),
              "extension is for curves, not surfaces");
}

TEST(ApplyOverrides, SurfaceSettingsReachTheirOptions) {
    const SurfaceRunOptions s = apply_overrides({.steps = 3,
                                                 .refine = 2,
                                                 .eta = 1e-9,
                                                 .tree_depth = 7,
                                                 .thin_depth = 1,
                                                 .volume_drift = 0.5,
                                                 .guards = false,
                                                 .area_correction = false},
                                                SurfaceRunOptions{}, 1.0);
    EXPECT_EQ(s.steps, 3);
    EXPECT_EQ(s.step.contour.refine_passes, 2);
    EXPECT_EQ(s.step.resolved_eta(), 1e-9);
    EXPECT_EQ(s.step.tree_depth, 7);
    EXPECT_EQ(s.step.contour.thin_depth, 1);
    EXPECT_EQ(s.volume_drift, 0.5);
    EXPECT_FALSE(s.guards);
    EXPECT_EQ(s.step.volume_correction, false);
}

TEST(NamedSurfaceRunOptions, AreTheProblemsOwn) {
    const SurfaceProblem p = make_surface_problem("box-normal");
    const SurfaceRunOptions o = named_surface_run_options(p);
    EXPECT_EQ(o.steps, p.steps);
    EXPECT_EQ(o.t_end, p.t_end);
    EXPECT_EQ(o.step.contour.depth, p.depth);
    EXPECT_EQ(*o.step.contour.eps, p.eps);
    EXPECT_EQ(o.step.contour.refine_passes, SurfaceContourOptions::until_converged);
    EXPECT_FALSE(sets_contour({.steps = 4}));
    EXPECT_TRUE(sets_contour({.thin_depth = 1}));
}

TEST(DepthForDomain, OneLevelMoreForEachDoublingOfTheDefaultDomain) {
    EXPECT_EQ(depth_for_domain(2, 3.0, 3.0), 5);
    EXPECT_EQ(depth_for_domain(2, 3.0 * (1.0 + 1e-12), 3.0), 5);  // the default, rounded
    EXPECT_EQ(depth_for_domain(2, 1.0, 3.0), 5);                  // smaller: the default K
    EXPECT_EQ(depth_for_domain(2, 6.0, 3.0), 6);
    EXPECT_EQ(depth_for_domain(3, 6.1, 3.0), 7);
    EXPECT_EQ(depth_for_domain(2, 300.0, 3.0), 12);  // --domain 150 around a unit circle
    EXPECT_EQ(depth_for_domain(2, 3e30, 3.0), setting_range::curve_depth.hi);
    EXPECT_EQ(depth_for_domain(3, 3e30, 3.0), setting_range::surface_depth.hi);
}

}  // namespace
}  // namespace slc
