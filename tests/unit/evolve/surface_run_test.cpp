// Tests of the run loop of surfaces: a run to the end, a sphere that vanishes under mean
// curvature, an observer that stops the run, a failure inside a step, a law that breaks what it
// claims to keep (unstable), bad options; and the named problems and laws by name.
#include "slc/evolve/surface_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/velocity/surface_laws.hpp"
#include "turned.hpp"

namespace slc {
namespace {

const Box3 domain{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}};

SurfaceRunOptions coarse(double t_end, int steps) {
    SurfaceRunOptions o;
    o.t_end = t_end;
    o.steps = steps;
    o.step.contour = {
        .depth = 4, .refine_passes = SurfaceContourOptions::until_converged, .eps = 1e-3};
    return o;
}

TEST(SurfaceRun, RunsToTheEndAndReportsEveryStep) {
    int seen = 0;
    const SurfaceRunResult r = run(sphere({0.2, 0.0, 0.0}, 0.3, 3), SurfaceRotation(), domain,
                                   coarse(1.0, 4), [&](const SurfaceStepReport& s) {
                                       ++seen;
                                       EXPECT_EQ(s.step, seen);
                                       EXPECT_NEAR(s.t, 0.25 * seen, 1e-15);
                                       return true;
                                   });
    EXPECT_EQ(r.status, RunStatus::ok);
    EXPECT_EQ(seen, 4);
    EXPECT_EQ(r.steps_done, 4);
    EXPECT_EQ(r.t, 1.0);
    EXPECT_GT(r.g_evals, 0u);
    EXPECT_NEAR(volume(r.surface) / (4.0 / 3.0 * std::numbers::pi * 0.027), 1.0, 5e-3);
    EXPECT_EQ(r.unconverged_steps, 0);  // a smooth surface refines to ε
}

TEST(SurfaceRun, ContoursLeftBeyondEpsAreCounted) {
    // A box turned off the octree's axes: refinement cannot split the triangles that cut its
    // edges (each split turns its children too far), so its contours stop beyond ε there.
    const SurfaceRunOptions o = coarse(0.5, 2);
    const SurfaceRunResult r =
        run(box_surface({-0.4, -0.3, -0.35}, {0.4, 0.3, 0.35}, 2), SurfaceRotation(), domain, o);
    ASSERT_EQ(r.status, RunStatus::ok);
    EXPECT_EQ(r.unconverged_steps, 2);
    EXPECT_GT(r.largest_residual, 2.0 * *o.step.contour.eps);
    // And the surface is that far from the exact one: the box turned by ωt = 0.5 about z.
    const Vec3 half{0.4, 0.3, 0.35};
    auto exact = [&](Vec3 x) {  // signed distance to the turned box, x turned back first
        const double c = std::cos(0.5), s = std::sin(0.5);
        const Vec3 q{c * x.x + s * x.y, -s * x.x + c * x.y, x.z};
        const Vec3 d{std::abs(q.x) - half.x, std::abs(q.y) - half.y, std::abs(q.z) - half.z};
        const Vec3 out{std::max(d.x, 0.0), std::max(d.y, 0.0), std::max(d.z, 0.0)};
        return norm(out) + std::min(std::max({d.x, d.y, d.z}), 0.0);
    };
    double worst = 0.0;
    for (const TriangleIndices& t : r.surface.triangles) {
        const Vec3 c =
            (r.surface.vertices[t[0]] + r.surface.vertices[t[1]] + r.surface.vertices[t[2]]) / 3.0;
        worst = std::max(worst, std::abs(exact(c)));
    }
    EXPECT_GT(worst, 2.0 * *o.step.contour.eps);
}

TEST(SurfaceRun, ResumeContinuesBitForBit) {
    const Surface start = sphere({0.2, 0.0, 0.0}, 0.3, 3);
    const SurfaceRunOptions o = coarse(1.0, 4);
    const SurfaceRunResult whole = run(start, SurfaceRotation(), domain, o);
    const SurfaceRunResult half = run(start, SurfaceRotation(), domain, o,
                                      [](const SurfaceStepReport& s) { return s.step < 2; });
    ASSERT_EQ(half.status, RunStatus::interrupted);
    ASSERT_EQ(half.steps_done, 2);
    EXPECT_EQ(half.volume_initial, volume(start));
    int seen = 0;
    const SurfaceRunResult rest =
        resume(half, SurfaceRotation(), domain, o, [&](const SurfaceStepReport& s) {
            EXPECT_EQ(s.step, 3 + seen++);
            return true;
        });
    EXPECT_EQ(seen, 2);
    EXPECT_EQ(rest.status, RunStatus::ok);
    EXPECT_EQ(rest.steps_done, 4);
    EXPECT_EQ(rest.t, whole.t);
    EXPECT_EQ(rest.surface.vertices, whole.surface.vertices);
    EXPECT_EQ(rest.surface.triangles, whole.surface.triangles);
    EXPECT_EQ(rest.g_evals, whole.g_evals);
    EXPECT_GE(rest.cpu_s, half.cpu_s);
    // Not after the last step, nor at a time that is not the step's.
    EXPECT_THROW(resume(whole, SurfaceRotation(), domain, o), InvalidInput);
    SurfaceRunResult shifted = half;
    shifted.t += 1e-9;
    EXPECT_THROW(resume(shifted, SurfaceRotation(), domain, o), InvalidInput);
}

TEST(SurfaceRun, EndsWhenNoMoreComponentsThanAskedAreLeft) {
    SurfaceRunOptions o = coarse(1.0, 4);
    o.stop_components = 1;  // one sphere: after the first step
    const SurfaceRunResult r = run(sphere({0.2, 0.0, 0.0}, 0.3, 3), SurfaceRotation(), domain, o);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.steps_done, 1);
    EXPECT_NE(r.message.find("1 components left"), std::string::npos) << r.message;
}

TEST(SurfaceRun, SphereVanishesUnderMeanCurvature) {
    // R0 = 0.3 vanishes at t = 0.09/4 = 0.0225. The observer sees every step, the one that
    // vanished too (as for curves): its history ends with the empty surface.
    std::vector<std::pair<int, std::size_t>> seen;  // step, triangles
    const SurfaceRunResult r = run(sphere({}, 0.3, 3), SurfaceMeanCurvatureFlow(), domain,
                                   coarse(0.03, 6), [&seen](const SurfaceStepReport& s) {
                                       seen.emplace_back(s.step, s.surface->size());
                                       return true;
                                   });
    EXPECT_EQ(r.status, RunStatus::vanished);
    EXPECT_TRUE(r.surface.empty());
    EXPECT_GE(r.t, 0.0225 - 0.005);
    EXPECT_LE(r.t, 0.0225 + 0.005 + 1e-12);
    ASSERT_EQ(seen.size(), static_cast<std::size_t>(r.steps_done));
    EXPECT_EQ(seen.back().second, 0u);
    for (std::size_t i = 0; i + 1 < seen.size(); ++i) EXPECT_GT(seen[i].second, 0u);
}

// A user's sphere of radius 4.9e-91 grows at unit speed as one of radius 0.5 does: every length
// of the defaults (ε, η) scales with the surface, and the nearest points on its triangles scale
// their arithmetic (whose fourth powers underflow there). Before, it "vanished under a law that
// only grows it".
TEST(SurfaceRun, ATinySphereGrowsAsALargeOne) {
    double ratio[2] = {0.0, 0.0};
    int i = 0;
    for (const double r : {0.5, 0x1p-300}) {  // 2^-300: 4.9e-91
        const Surface ball = prepare_surface(sphere({}, r, 1)).surface;
        const Box3 box = default_domain(bounding_box(ball));
        SurfaceRunOptions o = default_surface_run_options(ball, SurfaceNormalSpeed(), 0.0, 0.1 * r);
        o.steps = 2;
        o.step.contour.depth = 3;
        o.step.contour.eps = 4e-2 * r;
        const Surface start = surface_as_read(ball, box, o);
        const SurfaceRunResult run_r = run(start, SurfaceNormalSpeed(), box, o);
        ASSERT_EQ(run_r.status, RunStatus::ok) << r << ": " << run_r.message;
        ratio[i++] = volume(run_r.surface) / volume(ball);
    }
    // (1.1)^3 = 1.331 for the exact sphere; the coarse contours' own error is the same at both
    // sizes.
    EXPECT_NEAR(ratio[0], 1.331, 0.05);
    EXPECT_NEAR(ratio[1], ratio[0], 1e-9);
}

TEST(SurfaceRun, ObserverStops) {
    const SurfaceRunResult r =
        run(sphere({}, 0.3, 2), SurfaceNormalSpeed(0.5), domain, coarse(0.1, 5),
            [](const SurfaceStepReport& s) { return s.step < 2; });
    EXPECT_EQ(r.status, RunStatus::interrupted);
    EXPECT_EQ(r.steps_done, 2);
    EXPECT_FALSE(r.surface.empty());
}

TEST(SurfaceRun, FailureInsideAStepEndsWithError) {
    const SurfaceRunResult r =
        run(sphere({}, 0.3, 2), SurfaceTranslation({2.0, 0.0, 0.0}), domain, coarse(1.0, 2));
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_NE(r.message.find("at t = 0"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("domain boundary"), std::string::npos) << r.message;
    EXPECT_EQ(r.steps_done, 0);
    EXPECT_FALSE(r.surface.empty());  // the last surface reached is kept
}

TEST(SurfaceRun, ASurfaceCarriedOutOfTheDomainWithinAStepIsAnErrorNotAVanishing) {
    // The sphere moves 5 in the one step (none split): the contour in the domain is empty, but
    // the surface left it; it did not vanish under a law that keeps its volume.
    SurfaceRunOptions whole = coarse(1.0, 1);
    whole.max_substep_halvings = 0;
    const SurfaceRunResult r =
        run(sphere({}, 0.3, 2), SurfaceTranslation({5.0, 0.0, 0.0}), domain, whole);
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_NE(r.message.find("the flow carries the surface out of the domain"), std::string::npos)
        << r.message;
    EXPECT_EQ(r.steps_done, 0);
    // Split into sub-steps, as a failing step is in both dimensions, the finest split's contour
    // reaches the domain's edge: an error still, naming the domain.
    const SurfaceRunResult split =
        run(sphere({}, 0.3, 2), SurfaceTranslation({5.0, 0.0, 0.0}), domain, coarse(1.0, 1));
    EXPECT_EQ(split.status, RunStatus::error);
    EXPECT_EQ(split.steps_done, 0);
    EXPECT_NE(split.message.find("enlarge the domain"), std::string::npos) << split.message;
    // A surface the contours cannot see is bad input, not an empty start.
    SurfaceRunOptions o = coarse(1.0, 1);
    // (A sphere of radius 10⁻³ between the mesh vertices of K = 4.)
    EXPECT_THROW(surface_as_read(sphere({0.03, 0.04, 0.05}, 1e-3, 2), domain, o), InvalidInput);
}

TEST(SurfaceRun, TheDomainGrowsWhereTheSurfaceNearsItsEdge) {
    // The same run with doublings allowed: the domain doubles as the sphere nears its edge, and
    // the sphere ends where the translation takes it, its radius kept.
    SurfaceRunOptions o = coarse(1.0, 2);
    o.max_domain_doublings = 3;
    const SurfaceRunResult r =
        run(sphere({}, 0.3, 3), SurfaceTranslation({2.0, 0.0, 0.0}), domain, o);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_GE(r.domain_doublings, 1);
    EXPECT_LE(r.domain_doublings, 3);
    EXPECT_EQ(r.domain_grown_at, 0.0);
    for (const Vec3& v : r.surface.vertices) EXPECT_NEAR(norm(v - Vec3{2.0, 0.0, 0.0}), 0.3, 2e-3);
    EXPECT_TRUE(doubled_domain(domain, r.domain_doublings).contains(bounding_box(r.surface)));
    EXPECT_EQ(doubled_domain(domain, 2).width(), 8.0);
    EXPECT_EQ(doubled_domain(domain, 2).center(), domain.center());
}

TEST(SurfaceRun, ACoarseSurfaceIsReadAsTheStepsReadIt) {
    // An icosphere of 320 triangles: its volume is 3.4% below the sphere's, which its vertex
    // normals describe and the steps read. Moved as it is, its first step jumps to that volume
    // and the guards end the run; read first, it is carried with its volume kept.
    const Surface coarse_sphere = sphere({}, 0.3, 2);
    const double exact = 4.0 / 3.0 * std::numbers::pi * 0.027;
    EXPECT_LT(volume(coarse_sphere), 0.97 * exact);
    SurfaceRunOptions o = coarse(0.5, 2);
    const SurfaceTranslation along_x({0.2, 0.0, 0.0});
    EXPECT_EQ(run(coarse_sphere, along_x, domain, o).status, RunStatus::unstable);
    const Surface read = surface_as_read(coarse_sphere, domain, o);
    // Within what its contour may sag, ε A.
    EXPECT_NEAR(volume(read), exact, *o.step.contour.eps * area(read));
    const SurfaceRunResult r = run(read, along_x, domain, o);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_NEAR(volume(r.surface) / volume(read), 1.0, 1e-3);
}

TEST(SurfaceRun, ABoxIsReadWithItsEdgesAndCornersSharp) {
    // A user's box turned off the axes, at the default settings: the start a run moves is within
    // ε of the box, its edges and corners too, and holds its volume. (Read with the steps' plain
    // refinement, the edges were chamfered by 3.4e−3 against ε = 5.7e−4.)
    const Surface box =
        prepare_surface(
            test_support::turned(box_surface({-0.4, -0.4, -0.4}, {0.4, 0.4, 0.4}, 1), 0.3, 0.2))
            .surface;
    const Box3 around = default_domain(bounding_box(box));
    SurfaceRunOptions o = default_surface_run_options(box, SurfaceRotation(), 0.0, 1.0);
    const double eps = o.step.contour.resolved_eps();
    const Surface read = surface_as_read(box, around, o);
    const SurfaceDistanceTree tree(box, around, {.depth = 4});
    double farthest = 0.0;
    for (const TriangleIndices& t : read.triangles) {
        const Vec3 a = read.vertices[t[0]], b = read.vertices[t[1]], c = read.vertices[t[2]];
        for (const Vec3 x : {(a + b + c) / 3.0, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)})
            farthest = std::max(farthest, std::abs(tree.closest_point(x).distance));
    }
    EXPECT_LE(farthest, eps);
    EXPECT_NEAR(volume(read), 0.512, eps * area(box));
    EXPECT_EQ(euler_characteristic(read), 2);
}

TEST(SurfaceRun, APyramidInAGeneralTurnStartsWhole) {
    // A hexagonal pyramid (apex 0.8 above a base of radius 0.5) in a general turn, at the default
    // settings: thin cells follow its 60° base edges and its apex, thinner than any cell near
    // them, and their corners catch them unevenly, giving the signs' contour a handle beside a
    // base edge at thin depths 1 and 2 (and 5 components with 10 handles at 8, where the start
    // refused it), each decided by a mesh vertex a hair from the zero set. Told the pyramid's
    // topology, the start's contour moves such vertices across it and keeps the default thin
    // depth (before, it kept the shallower 0): one component, genus 0, its volume within what ε
    // allows.
    constexpr int n = 6;
    Surface pyramid;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * std::numbers::pi * k / n;
        pyramid.vertices.push_back({0.5 * std::cos(a), 0.5 * std::sin(a), -0.3});
        pyramid.triangles.push_back({static_cast<std::uint32_t>(k),
                                     static_cast<std::uint32_t>((k + 1) % n), std::uint32_t{n}});
    }
    pyramid.vertices.push_back({0, 0, 0.5});
    for (std::uint32_t k = 1; k + 1 < n; ++k) pyramid.triangles.push_back({0, k + 1, k});
    pyramid = prepare_surface(test_support::turned(test_support::turned(pyramid, 0.8442354444173306,
                                                                        5.324583204732311),
                                                   4.798937463950548, 0.0))
                  .surface;
    const double exact = 0.5 * n * 0.25 * std::sin(2 * std::numbers::pi / n) * 0.8 / 3;
    const Box3 around = default_domain(bounding_box(pyramid));
    SurfaceRunOptions o = default_surface_run_options(pyramid, SurfaceNormalSpeed(1.0), 0.0, 0.01);
    const int thin = o.step.contour.thin_depth;
    const Surface read = surface_as_read(pyramid, around, o);
    EXPECT_EQ(component_count(read), 1u);
    EXPECT_EQ(genus(read), 0);
    EXPECT_NEAR(volume(read), exact, 2 * o.step.contour.resolved_eps() * area(pyramid));
    EXPECT_EQ(o.step.contour.thin_depth, thin);
}

/// A law that grows the surface while claiming to keep its volume.
class FalseClaim final : public SurfaceNormalLaw {
public:
    std::string name() const override { return "false-claim"; }
    Invariants invariants() const override { return {.keeps_area = true}; }
    void normal_speeds(double, std::span<const Vec3> x, std::span<const Vec3>,
                       std::span<double> out) const override {
        std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(x.size()), 1.0);
    }
};

TEST(SurfaceRun, BrokenInvariantIsUnstable) {
    SurfaceRunOptions o = coarse(0.1, 1);
    o.max_substep_halvings = 1;
    const SurfaceRunResult r = run(sphere({}, 0.3, 2), FalseClaim(), domain, o);
    EXPECT_EQ(r.status, RunStatus::unstable);
    EXPECT_NE(r.message.find("the volume changed by"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("also in 2 sub-steps"), std::string::npos) << r.message;
    // Without guards the same run goes on to the end, each step whole, and ends broken, its
    // message the first step that broke the law; the surface is the unguarded step's.
    o.guards = false;
    const SurfaceRunResult whole = run(sphere({}, 0.3, 2), FalseClaim(), domain, o);
    EXPECT_EQ(whole.status, RunStatus::broken);
    EXPECT_STREQ(to_string(whole.status), "broken");
    EXPECT_EQ(whole.steps_done, 1);
    EXPECT_EQ(whole.split_steps, 0);
    EXPECT_EQ(whole.message, whole.broken);
    EXPECT_EQ(whole.message.rfind("at t = 0: the volume changed by", 0), 0) << whole.message;
    const SurfaceStepResult step =
        advance(sphere({}, 0.3, 2), 0.0, 0.1, FalseClaim(), domain, o.step);
    EXPECT_EQ(whole.surface.vertices, step.surface.vertices);
}

/// A law that grows the surface slowly, at speed 0.3, while claiming to shrink its area.
class SlowGrowth final : public SurfaceNormalLaw {
public:
    std::string name() const override { return "slow-growth"; }
    Invariants invariants() const override { return {.shortens = true}; }
    void normal_speeds(double, std::span<const Vec3> x, std::span<const Vec3>,
                       std::span<double> out) const override {
        std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(x.size()), 0.3);
    }
};

TEST(SurfaceRun, AreaGrowingOverTheRunUnderAShrinkingLawIsUnstable) {
    // Steps of k = 0.01 grow the sphere of radius 0.3 by 2% of its area each, within a step's
    // budget (1% and 20 ε √A, 2.9% here); over the run the area may exceed its least by 0.5%
    // and 20 ε √A, which the third step passes.
    SurfaceRunOptions o = coarse(0.06, 6);
    const SurfaceRunResult r = run(sphere({}, 0.3, 3), SlowGrowth(), domain, o);
    EXPECT_EQ(r.status, RunStatus::unstable);
    EXPECT_NE(r.message.find("the area has grown by"), std::string::npos) << r.message;
    EXPECT_EQ(r.split_steps, 0);  // no step broke the step's budget
    EXPECT_LE(r.t, 0.04 + 1e-12);
    o.area_growth = 1.0;
    EXPECT_EQ(run(sphere({}, 0.3, 3), SlowGrowth(), domain, o).status, RunStatus::ok);
    // Without guards: to the end, broken where the area first grew too far.
    o.area_growth = 5e-3;
    o.guards = false;
    const SurfaceRunResult all = run(sphere({}, 0.3, 3), SlowGrowth(), domain, o);
    EXPECT_EQ(all.status, RunStatus::broken);
    EXPECT_EQ(all.steps_done, 6);
    EXPECT_EQ(all.message, r.message);
}

/// A flow field u = f(x) claiming the given invariants.
template <class F>
class ClaimingField final : public SurfaceFlowFieldLaw {
public:
    ClaimingField(Invariants claims, F f) : claims_(claims), f_(f) {}
    std::string name() const override { return "claiming"; }
    Invariants invariants() const override { return claims_; }
    void sample(double, std::span<const Vec3> x, std::span<Vec3> out) const override {
        for (std::size_t i = 0; i < x.size(); ++i) out[i] = f_(x[i]);
    }

private:
    Invariants claims_;
    F f_;
};

TEST(SurfaceRun, GuardsOfTheLawsInvariants) {
    // A smooth flow cannot split a surface: one that tore under the contours is caught.
    const Surface one = sphere({}, 0.3, 2);
    const Surface two = join({sphere({-0.4, 0, 0}, 0.2, 2), sphere({0.4, 0, 0}, 0.2, 2)});
    const auto torn = surface_invariant_violation({.cannot_split = true}, one, two, 0.1, 1e-3);
    ASSERT_TRUE(torn);
    EXPECT_NE(torn->find("the number of components rose from 1 to 2"), std::string::npos);
    EXPECT_FALSE(surface_invariant_violation({.cannot_split = true}, two, one, 0.1, 1e-3));
    // A rigid motion keeps components and genus; a growing surface does not vanish.
    EXPECT_TRUE(surface_invariant_violation({.rigid = true}, one, two, 0.1, 1e-3));
    const Surface ring = torus({}, 0.5, 0.2, 24, 12);
    EXPECT_TRUE(surface_invariant_violation({.rigid = true}, one, ring, 0.1, 1e-3));
    // Nor does a smooth flow pierce one: a hole opened or closed is caught.
    for (const auto& [before, after] : {std::pair{&one, &ring}, std::pair{&ring, &one}}) {
        const auto pierced =
            surface_invariant_violation({.cannot_split = true}, *before, *after, 0.1, 1e-3);
        ASSERT_TRUE(pierced);
        EXPECT_NE(pierced->find("the genus changed from"), std::string::npos) << *pierced;
    }
    EXPECT_TRUE(surface_invariant_violation({.cannot_vanish = true}, one, Surface{}, 0.1, 1e-3));
    // The area of a shrinking flow may not grow by more than 1%.
    const Surface bigger = sphere({}, 0.31, 2);
    EXPECT_TRUE(surface_invariant_violation({.shortens = true}, one, bigger, 0.1, 1e-6));
    EXPECT_FALSE(surface_invariant_violation({.shortens = true}, bigger, one, 0.1, 1e-6));
    // A constant normal speed s moves the volume by s k A: the sphere of radius 0.3 grown to
    // 0.33 keeps it at s = 1 over k = 0.03, not at s = 0.5 nor over k = 0.06, and shrinks back
    // at s = −1. Where the components change, the rule is not applied.
    const Surface grown = sphere({}, 0.33, 3), fine = sphere({}, 0.3, 3);
    EXPECT_FALSE(
        surface_invariant_violation({.volume_rate_per_area = 1.0}, fine, grown, 0.03, 1e-6));
    EXPECT_FALSE(
        surface_invariant_violation({.volume_rate_per_area = -1.0}, grown, fine, 0.03, 1e-6));
    const auto slow =
        surface_invariant_violation({.volume_rate_per_area = 0.5}, fine, grown, 0.03, 1e-6);
    ASSERT_TRUE(slow);
    EXPECT_NE(slow->find("where the law's speed moves it by"), std::string::npos) << *slow;
    EXPECT_TRUE(
        surface_invariant_violation({.volume_rate_per_area = 1.0}, fine, grown, 0.06, 1e-6));
    EXPECT_FALSE(surface_invariant_violation({.volume_rate_per_area = 1.0}, two, one, 0.06, 1e-6));
}

TEST(SurfaceRun, ThinnestNewComponentIsThreeVolumesOverArea) {
    // One sphere become two: the new component is the thinner, 3V/A about its radius (an
    // icosphere's centroids lie inside the sphere by their sag).
    const Surface one = sphere({}, 0.3, 3);
    const Surface two = join({sphere({-0.5, 0, 0}, 0.3, 3), sphere({0.5, 0.1, 0}, 0.05, 3)});
    const std::optional<double> thin = thinnest_new_component(one, two);
    ASSERT_TRUE(thin);
    EXPECT_NEAR(*thin, 0.05, 1e-3);
    EXPECT_FALSE(thinnest_new_component(two, one));
    EXPECT_FALSE(thinnest_new_component(one, one));
    EXPECT_FALSE(thinnest_new_component(one, Surface{}));
    // From nothing, every component is new.
    EXPECT_NEAR(*thinnest_new_component(Surface{}, one), 0.3, 5e-3);
}

TEST(SurfaceRun, VolumeDriftOverTheRunIsUnstable) {
    // A slow contraction loses 0.75% of the volume a step, within a step's budget; after two
    // steps the run has lost more than 1% of it. (A fine start: a coarse icosphere's own
    // deficit would hide a step's loss.) The run ends with the surface before the step that
    // took it beyond its budget, as a run of curves does: the last its history holds.
    const ClaimingField squeeze({.keeps_area = true}, [](Vec3 x) { return -0.05 * x; });
    const Surface start = sphere({}, 0.5, 5);
    const SurfaceRunResult r = run(start, squeeze, domain, coarse(0.2, 4));
    EXPECT_EQ(r.status, RunStatus::unstable);
    EXPECT_EQ(r.steps_done, 1) << r.message;
    EXPECT_EQ(r.t, 0.05);
    EXPECT_GT(volume(r.surface), 0.99 * volume(start));
    EXPECT_NE(r.message.find("the volume drifted by -1."), std::string::npos) << r.message;
    // Without guards: to the end, broken where the drift first passed 1%.
    SurfaceRunOptions o = coarse(0.2, 4);
    o.guards = false;
    const SurfaceRunResult all = run(sphere({}, 0.5, 5), squeeze, domain, o);
    EXPECT_EQ(all.status, RunStatus::broken);
    EXPECT_EQ(all.steps_done, 4);
    EXPECT_EQ(all.message, r.message);
}

TEST(SurfaceRun, BadOptions) {
    const Surface s = sphere({}, 0.3, 1);
    EXPECT_THROW(run(s, SurfaceRotation(), domain, coarse(1.0, 0)), InvalidInput);
    EXPECT_THROW(run(s, SurfaceRotation(), domain, coarse(-1.0, 2)), InvalidInput);
    EXPECT_THROW(run(Surface{}, SurfaceRotation(), domain, coarse(1.0, 2)), InvalidInput);
}

TEST(SurfaceProblems, EveryProblemStartsValidInsideItsDomain) {
    for (const std::string& name : surface_problem_names()) {
        const SurfaceProblem p = make_surface_problem(name);
        EXPECT_EQ(p.name, name);
        EXPECT_FALSE(p.description.empty());
        EXPECT_TRUE(prepare_surface(p.initial).notes.empty()) << name;
        for (const Vec3& v : p.initial.vertices) ASSERT_TRUE(p.domain.contains(v)) << name;
        if (p.exact) {
            // Where the exact surface is known at t = 0, the initial surface lies on it.
            double e = 0.0;
            for (const Vec3& v : p.initial.vertices) e = std::max(e, std::abs(p.exact(0.0, v)));
            EXPECT_LT(e, 1e-6) << name;
        }
    }
    EXPECT_THROW(make_surface_problem("teapot"), InvalidInput);
    EXPECT_THROW(make_surface_problem("sphere-rotation", {{"x", 1.0}}), InvalidInput);
    EXPECT_EQ(make_surface_problem("box-normal", {{"speed", -1.0}}).law->invariants().cannot_vanish,
              false);
}

TEST(SurfaceProblems, LawsByName) {
    for (const char* name : {"rotation", "enright", "unit-normal", "anisotropic", "curvature",
                             "volume-preserving-curvature"})
        EXPECT_EQ(make_surface_velocity(name)->name(), name);
    EXPECT_EQ(make_surface_velocity("translation", {{"ux", 1}, {"uy", 0}, {"uz", 0}})->name(),
              "translation");
    EXPECT_THROW(make_surface_velocity("translation", {{"ux", 1}}), InvalidInput);
    EXPECT_THROW(make_surface_velocity("spin"), InvalidInput);
    EXPECT_THROW(make_surface_velocity("rotation", {{"omega", NAN}}), InvalidInput);
    EXPECT_THROW(make_surface_velocity("rotation", {{"ax", 0}, {"az", 0}}), InvalidInput);
}

}  // namespace
}  // namespace slc
