// A step that changes the topology, one rule for curves and surfaces (time_loop.hpp,
// thin_parts.hpp): the change is confirmed by the same step with thin cells two levels deeper, or
// the step is taken deeper where the coarser contours tore a wall, the next step starting again
// from the run's own depth; a change the deepest cannot
// confirm ends the run unstable, naming the place. The parts a step split off are measured by
// their thickness, a disc's or a ball's radius.
#include "thin_parts.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "slc/evolve/defaults.hpp"
#include "slc/evolve/self_convergence.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/evolve/surface_run.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/velocity/laws.hpp"
#include "slc/velocity/surface_laws.hpp"

namespace slc::detail {
namespace {

TEST(ThinParts, ANewPartIsMeasuredByItsThicknessAndPlace) {
    const Interface one({shapes::circle({}, 1.0, 256)});
    const Interface two({shapes::circle({}, 1.0, 256), shapes::circle({3.0, 0.0}, 0.05, 64)});
    const auto curve = thinnest_new_part<2>(one, two);
    ASSERT_TRUE(curve);
    EXPECT_NEAR(curve->thickness, 0.05, 1e-4);  // 2 A / L of a circle: its radius
    EXPECT_NEAR(curve->where.x, 3.0, 1e-12);
    EXPECT_NEAR(curve->where.y, 0.0, 1e-12);
    EXPECT_FALSE(thinnest_new_part<2>(two, one));
    EXPECT_FALSE(thinnest_new_part<2>(two, two));

    const Surface ball = slc::sphere({}, 0.3, 3);
    const Surface pair = join({slc::sphere({}, 0.3, 3), slc::sphere({0.6, 0.1, 0.0}, 0.05, 3)});
    const auto part = thinnest_new_part<3>(ball, pair);
    ASSERT_TRUE(part);
    EXPECT_NEAR(part->thickness, 0.05, 1e-3);  // 3 V / A of a ball: its radius
    EXPECT_NEAR(part->where.x, 0.6, 1e-9);
    EXPECT_NEAR(part->where.y, 0.1, 1e-9);
    EXPECT_FALSE(thinnest_new_part<3>(pair, ball));
}

/// A ring of radii 0.5 and 0.44 (a wall 0.06 wide) shrunk at unit speed in `steps` steps to t:
/// its wall 0.06 − 2t wide, at K = 4 (cells 0.094) with one level of thin cells.
Interface ring() {
    Interface r({shapes::circle({}, 0.5, 256), shapes::circle({}, 0.44, 256)});
    r.reverse_curve(1);  // the hole clockwise
    return r;
}

RunOptions ring_options(double t, int steps) {
    RunOptions o = default_run_options(ring(), NormalSpeed(-1.0), 0.0, t);
    o.steps = steps;
    o.step.contour.depth = 4;
    o.step.contour.thin_depth = 1;
    return o;
}

RunResult shrunk_ring(double t, int steps = 1, const Observer& observer = {}) {
    return run(ring(), NormalSpeed(-1.0), default_domain(ring().curves()), ring_options(t, steps),
               observer);
}

TEST(TopologyChange, ATornWallIsTakenAgainDeeper) {
    // The wall 0.01 wide: one level of thin cells (0.047) tears it into pieces, three join it
    // into one curve, five keep the ring; the step is taken at five, the run's own depth staying
    // one.
    const RunResult r = shrunk_ring(0.025);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.curves.curve_count(), 2U);
    EXPECT_EQ(region_parts(r.curves).holes, 1U);
    EXPECT_EQ(r.thin_depth, 1);
    EXPECT_EQ(r.deepest_thin_depth, 5);
    EXPECT_EQ(r.deeper_at, 0.0);
    EXPECT_NE(r.deeper_why.find("thin cells 1 level deep made "), std::string::npos)
        << r.deeper_why;
    EXPECT_NE(r.deeper_why.find("of 2 components with 1 hole near ("), std::string::npos)
        << r.deeper_why;
    const double exact = std::numbers::pi * (0.475 * 0.475 - 0.465 * 0.465);
    EXPECT_NEAR(area(r.curves) / exact, 1.0, 2e-3);
}

TEST(TopologyChange, AChangeTheDeepestCannotConfirmIsUnstable) {
    // The wall 0.004 wide: thin cells reach their budget of cells before they resolve it, and
    // the contours at 5 and 7 levels tear it alike, which confirms nothing.
    const RunResult r = shrunk_ring(0.028);
    EXPECT_EQ(r.status, RunStatus::unstable);
    EXPECT_EQ(r.steps_done, 0);
    EXPECT_NE(r.message.find("do not confirm it: a part is thinner than they resolve; raise -K"),
              std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find("of 2 components with 1 hole near ("), std::string::npos) << r.message;
}

/// A lens 2 long between two arcs of radius r (0.05 thick for r = 20, its tips 5.7° wide; 0.0125
/// and 1.4° for r = 80), turned by phi about the origin and moved to (0.2, 0.1).
Interface lens(double r, double phi) {
    const double half = std::asin(1.0 / r), c = std::sqrt(r * r - 1.0);
    std::vector<Vec2> points;
    for (const double side : {1.0, -1.0}) {
        for (int i = 0; i < 100; ++i) {
            const double a = side * std::numbers::pi / 2 - half + 2.0 * half * i / 100.0;
            const Vec2 p{r * std::cos(a), -side * c + r * std::sin(a)};
            points.push_back(Vec2{0.2 + std::cos(phi) * p.x - std::sin(phi) * p.y,
                                  0.1 + std::sin(phi) * p.x + std::cos(phi) * p.y});
        }
    }
    return Interface({points});
}

/// The run of a full turn of `given` about the origin at the defaults.
RunResult full_turn(const Interface& given) {
    const Rotation law;
    return run(given, law, default_domain(given.curves()),
               default_run_options(given, law, 0.0, 2.0 * std::numbers::pi));
}

TEST(TopologyChange, ARigidMotionThatNoThinDepthResolvesStopsWithoutShorterSteps) {
    // A lens 0.0125 thick whose tips are thinner than cells 6 or 8 levels deep over 0.009 of
    // their length: the first step's contours cut one off, and thin cells two levels deeper do
    // not confirm it. A rigid motion keeps the topology at any step, so the run stops there,
    // naming the place, rather than taking the step again in halves down to 1/256 of it.
    const RunResult r = full_turn(lens(80.0, 2.0 * std::numbers::pi * 8.0 / 12.0 * 0.37 + 0.8));
    EXPECT_EQ(r.status, RunStatus::unstable);
    EXPECT_EQ(r.steps_done, 0);
    EXPECT_NE(r.message.find("do not confirm it: a part is thinner than they resolve"),
              std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find(" near ("), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("so shorter steps cannot mend it"), std::string::npos) << r.message;
    EXPECT_EQ(r.split_steps, 0);
}

TEST(TopologyChange, ALensWithSharpTipsTurnsAFullTurnAtTheDefaults) {
    // Lenses 0.05 thick with tips 5.7° wide (r = 20) in two orientations whose first steps cut a
    // tip off or left a fleck beside it: the thin cells' test now reads the grid lines through
    // the centres of coarser cells, and pieces of a tip thinner than half a finest cell beside it
    // are dropped. Each turns a full turn as one curve, its area kept, back where it started.
    for (const double phi : {2.0 * std::numbers::pi * 3.0 / 12.0 * 0.37 + 0.3,
                             2.0 * std::numbers::pi * 2.0 / 12.0 * 0.37 + 0.2}) {
        const Interface given = lens(20.0, phi);
        const RunResult r = full_turn(given);
        ASSERT_EQ(r.status, RunStatus::ok) << r.message;
        EXPECT_EQ(r.curves.curve_count(), 1U);
        EXPECT_NEAR(area(r.curves) / area(given), 1.0, 2e-3);
        EXPECT_LT(interface_distance(r.curves, given), 0.02);
    }
}

TEST(TopologyChange, EachStepStartsFromTheRunsOwnThinDepth) {
    // Two steps to t = 0.024: each tears the wall at one level of thin cells and keeps it at
    // three, and each is taken at three, the run's own depth staying one; a run resumed after
    // the first steps as the whole run does, to the bit.
    std::optional<RunResult> after_first;
    const RunResult whole = shrunk_ring(0.024, 2, [&](const StepReport& s) {
        if (s.step == 1) after_first = *s.run;
        return true;
    });
    ASSERT_EQ(whole.status, RunStatus::ok) << whole.message;
    ASSERT_TRUE(after_first);
    EXPECT_EQ(after_first->thin_depth, 1);
    EXPECT_EQ(after_first->deepest_thin_depth, 3);
    EXPECT_EQ(after_first->deeper_steps, 1);
    EXPECT_EQ(after_first->deeper_at, 0.0);
    EXPECT_EQ(whole.thin_depth, 1);
    EXPECT_EQ(whole.deeper_steps, 2);
    const RunResult rest = resume(*after_first, NormalSpeed(-1.0), default_domain(ring().curves()),
                                  ring_options(0.024, 2));
    ASSERT_EQ(rest.status, RunStatus::ok) << rest.message;
    EXPECT_EQ(rest.thin_depth, whole.thin_depth);
    EXPECT_EQ(rest.deepest_thin_depth, whole.deepest_thin_depth);
    EXPECT_EQ(rest.deeper_steps, whole.deeper_steps);
    EXPECT_EQ(rest.deeper_why, whole.deeper_why);
    ASSERT_EQ(rest.curves.size(), whole.curves.size());
    for (std::size_t i = 0; i < rest.curves.size(); ++i) {
        EXPECT_EQ(rest.curves.point(i).x, whole.curves.point(i).x);
        EXPECT_EQ(rest.curves.point(i).y, whole.curves.point(i).y);
    }
}

TEST(TopologyChange, AChangeTheLawMakesIsKeptAtAnyThinDepth) {
    // Two circles 0.1 apart grown at unit speed by 0.1 merge: confirmed two levels deeper, or at
    // the most thin depth two levels shallower, and the run stays at the depth it was given.
    const Interface pair(
        {shapes::circle({-0.55, 0.0}, 0.5, 256), shapes::circle({0.55, 0.0}, 0.5, 256)});
    const NormalSpeed law(1.0);
    for (const int thin : {6, 8}) {
        RunOptions o = default_run_options(pair, law, 0.0, 0.1);
        o.steps = 1;
        o.step.contour.thin_depth = thin;
        const RunResult r = run(pair, law, default_domain(pair.curves()), o);
        ASSERT_EQ(r.status, RunStatus::ok) << thin << ": " << r.message;
        EXPECT_EQ(r.curves.curve_count(), 1U) << thin;
        EXPECT_EQ(r.thin_depth, thin);
        EXPECT_TRUE(std::isnan(r.deeper_at)) << r.deeper_why;
    }
}

TEST(TopologyChange, SurfacesFollowTheSameRule) {
    // A torus of radii 0.55 and 0.2 shrunk at unit speed to a tube 0.02 thick in one step, at
    // K = 4 (cells 0.14) with one level of thin cells: torn into pieces there, one torus at
    // three levels.
    const Surface tube = slc::torus({}, 0.55, 0.2, 96, 48);
    const SurfaceNormalSpeed law(-1.0);
    SurfaceRunOptions o = default_surface_run_options(tube, law, 0.0, 0.18);
    o.steps = 1;
    o.step.contour.depth = 4;
    o.step.contour.eps = 2e-3;
    o.step.contour.thin_depth = 1;
    const SurfaceRunResult r = run(tube, law, default_domain(bounding_box(tube)), o);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(component_count(r.surface), 1U);
    EXPECT_EQ(genus(r.surface), 1);
    EXPECT_EQ(r.thin_depth, 1);
    EXPECT_EQ(r.deepest_thin_depth, 3);
    EXPECT_NE(r.deeper_why.find("of 1 component with 1 handle"), std::string::npos) << r.deeper_why;
    const double exact = 2.0 * std::numbers::pi * std::numbers::pi * 0.55 * 0.02 * 0.02;
    EXPECT_NEAR(volume(r.surface) / exact, 1.0, 0.03);
}

TEST(TopologyChange, TwoCirclesOfOnesOwnMergeAtTheDefaults) {
    // Radii 0.3 and 0.25, 0.08 apart, grown at unit speed to t = 0.1 at the defaults (K 5, thin
    // depth 6): where they meet, the contours bridge the gap narrowing to nothing at places and
    // leave holes between the bridges, thinner than half a finest cell, which are dropped as
    // flecks. One curve, on the union of the grown circles to the polygons' sag (9e-5).
    const Vec2 a{-0.3, 0.0}, b{0.33, 0.03};
    const Interface pair({shapes::circle(a, 0.3, 200, 0.1), shapes::circle(b, 0.25, 120, 0.3)});
    const NormalSpeed law(1.0);
    const RunResult r =
        run(pair, law, default_domain(pair.curves()), default_run_options(pair, law, 0.0, 0.1));
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.curves.curve_count(), 1U);
    EXPECT_EQ(region_parts(r.curves).holes, 0U);
    double farthest = 0.0;
    for (std::size_t c = 0; c < r.curves.curve_count(); ++c)
        for (const Vec2 x : r.curves.curve(c))
            farthest =
                std::max(farthest, std::abs(std::min(distance(x, a) - 0.4, distance(x, b) - 0.35)));
    EXPECT_LT(farthest, 1e-4);
}

TEST(TopologyChange, PartsThatMeetKeepTheShallowerDepthThatAddsNoHandle) {
    // Two icospheres of one's own (radius 0.3, 5,120 triangles; radius 0.25, 1,280; 0.1008
    // apart) grown at unit speed to t = 0.1 at the defaults (K 5, thin depth 2). Where they
    // meet, the gap between them narrows to nothing, and thin cells 2 and 4 levels deep make
    // tens of handles of the one part there (46 at 4 levels at t = 0.05), no two alike; those
    // steps keep one level, which makes none.
    const Vec3 a{-0.3, 0.0, 0.0}, b{0.35, 0.03, 0.01};
    const Surface pair = join({slc::sphere(a, 0.3, 4), slc::sphere(b, 0.25, 3)});
    const SurfaceNormalSpeed law(1.0);
    SurfaceRunOptions o = default_surface_run_options(pair, law, 0.0, 0.1);
    const Box3 domain = default_domain(bounding_box(pair));
    const Surface read = surface_as_read(pair, domain, o);
    const SurfaceRunResult r = run(read, law, domain, o);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(component_count(r.surface), 1U);
    EXPECT_EQ(genus(r.surface), 0);
    EXPECT_EQ(r.thin_depth, 2);
    EXPECT_FALSE(std::isnan(r.shallower_at));
    EXPECT_LT(r.shallowest_thin_depth, 2);
    EXPECT_GT(r.shallower_substeps, 0);
    EXPECT_NE(r.shallower_why.find(" of 1 component with 0 handles near ("), std::string::npos)
        << r.shallower_why;
    EXPECT_NE(r.shallower_why.find(" deep 1 component with 0 handles"), std::string::npos)
        << r.shallower_why;
    // Within 1% of the pair's size (1.2) of the union of the grown balls (the icospheres' own
    // offsets lie within their sag, 5e-4, inside them): the farthest vertex lies where the
    // concave edge between them is filled in.
    double farthest = 0.0;
    for (const Vec3& x : r.surface.vertices)
        farthest =
            std::max(farthest, std::abs(std::min(distance(x, a) - 0.4, distance(x, b) - 0.35)));
    EXPECT_LT(farthest, 0.012);
}

}  // namespace
}  // namespace slc::detail
