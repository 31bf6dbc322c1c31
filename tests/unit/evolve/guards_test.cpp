// invariant_violation: each claim of Invariants against steps that keep it within the budget and
// steps that break it.
#include "slc/evolve/guards.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "slc/geometry/shapes.hpp"
#include "slc/geometry/surface_shapes.hpp"

namespace slc {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double eps = 1e-9;  // small: the budgets below are the area fractions

Interface disk(double r, Vec2 c = {}) {
    return Interface(std::vector<std::vector<Vec2>>{shapes::circle(c, r, 256)});
}

Interface two_disks(double r) {
    return Interface(std::vector<std::vector<Vec2>>{shapes::circle({0.0, 0.0}, r, 256),
                                                    shapes::circle({3.0, 0.0}, r, 256)});
}

std::optional<std::string> check(const Invariants& law, const Interface& before,
                                 const Interface& after, double k = 0.01,
                                 const GuardBudget& budget = {}) {
    return invariant_violation(law, before, {area(before), length(before)}, after,
                               {area(after), length(after)}, k, eps, budget);
}

TEST(Guards, AreaKeptWithinOnePercent) {
    const Invariants keeps{.keeps_area = true};
    EXPECT_FALSE(check(keeps, disk(1.0), disk(1.004)));  // +0.8%
    const auto v = check(keeps, disk(1.0), disk(1.01));  // +2%
    ASSERT_TRUE(v);
    EXPECT_NE(v->find("under a law that keeps it"), std::string::npos) << *v;
    EXPECT_TRUE(check(keeps, disk(1.0), Interface{}));
}

TEST(Guards, RigidMotionKeepsTheNumberOfCurves) {
    const Invariants rigid{.keeps_area = true, .rigid = true, .cannot_split = true};
    EXPECT_FALSE(check(rigid, two_disks(1.0), two_disks(1.0)));
    const auto v = check(rigid, two_disks(0.5), disk(std::sqrt(0.5)));  // same area, one curve
    ASSERT_TRUE(v);
    EXPECT_NE(v->find("from 2 to 1"), std::string::npos) << *v;
}

// A rigid motion's area may drift by 5% over the run, and by 1% in a step: a step that keeps
// within its 1% is still refused once the run has drifted by more than 5% since its start.
TEST(Guards, RigidMotionAreaDriftsAtMostFivePercentOverTheRun) {
    const Invariants rigid{.keeps_area = true, .rigid = true, .cannot_split = true};
    const double start = area(disk(1.0));
    const GuardBudget run{.run_length = 1.0, .start_area = start};
    // +0.8% in the step, +4.5% since the start (r² = 1.045): kept.
    EXPECT_FALSE(check(rigid, disk(std::sqrt(1.037)), disk(std::sqrt(1.045)), 0.1, run));
    // +0.8% in the step, +5.3% since the start: refused.
    const auto v = check(rigid, disk(std::sqrt(1.045)), disk(std::sqrt(1.053)), 0.1, run);
    ASSERT_TRUE(v);
    EXPECT_NE(v->find("drifted by 5.3% since the start"), std::string::npos) << *v;
    // +1.5% in one step: refused however little the run has drifted.
    const auto w = check(rigid, disk(1.0), disk(std::sqrt(1.015)), 0.1, run);
    ASSERT_TRUE(w);
    EXPECT_NE(w->find("in one step of a rigid motion, more than 1%"), std::string::npos) << *w;
    EXPECT_FALSE(check(rigid, disk(std::sqrt(1.045)), disk(std::sqrt(1.053)), 0.1));  // no start
}

/// The unit circle with a ripple r = 1 + a cos(m θ): area π(1 + a²/2), length about
/// 2π(1 + (m a)²/4).
Interface rippled_disk(double a, int m) {
    std::vector<Vec2> points;
    for (int i = 0; i < 2048; ++i) {
        const double t = 2.0 * pi * i / 2048, r = 1.0 + a * std::cos(m * t);
        points.push_back({r * std::cos(t), r * std::sin(t)});
    }
    return Interface(std::vector<std::vector<Vec2>>{points});
}

TEST(Guards, RigidMotionCannotLengthenTheCurves) {
    const Invariants rigid{.keeps_area = true, .rigid = true, .cannot_split = true};
    const GuardBudget run{.run_length = 1.0};
    // Area +0.005%, length +0.1% and +1%: a step of 0.1 of the run may move it by 0.5%.
    EXPECT_FALSE(check(rigid, disk(1.0), rippled_disk(0.0032, 20), 0.1, run));
    const auto v = check(rigid, disk(1.0), rippled_disk(0.01, 20), 0.1, run);
    ASSERT_TRUE(v);
    EXPECT_NE(v->find("the length grew by"), std::string::npos) << *v;
    // Shorter is allowed: a contour's chords cut the corners of what it contours.
    EXPECT_FALSE(check(rigid, rippled_disk(0.01, 20), disk(1.0), 0.1, run));
    // Without a run length a step may move it by 1%.
    EXPECT_FALSE(check(rigid, disk(1.0), rippled_disk(0.0095, 20), 0.1));
    EXPECT_TRUE(check(rigid, disk(1.0), rippled_disk(0.011, 20), 0.1));
}

TEST(Guards, AGrowingRegionCannotLoseAreaOrVanish) {
    const Invariants grows{.cannot_vanish = true};
    EXPECT_FALSE(check(grows, disk(1.0), disk(2.0)));
    EXPECT_FALSE(check(grows, disk(1.0), disk(0.999)));  // −0.2%: within the budget
    const auto v = check(grows, disk(1.0), disk(0.05));
    ASSERT_TRUE(v);
    EXPECT_NE(v->find("only grows it"), std::string::npos) << *v;
    EXPECT_TRUE(check(grows, disk(1.0), Interface{}));
}

// A growing region's parts merge and never split; a shrinking one's holes merge and never split
// or appear. The rule is one for curves and surfaces: region_parts reads both.
TEST(Guards, AGrowingRegionsPartsAndAShrinkingRegionsHolesCannotMultiply) {
    const Invariants grows{.cannot_vanish = true}, shrinks{.cannot_grow = true};
    // A disk with a hole (a clockwise circle inside), and the disk alone.
    std::vector<Vec2> hole = shapes::circle({}, 0.5, 256);
    std::reverse(hole.begin(), hole.end());
    const Interface ring(std::vector<std::vector<Vec2>>{shapes::circle({}, 2.0, 256), hole});
    const Interface solid = disk(2.0);
    EXPECT_EQ(region_parts(ring).parts, 1U);
    EXPECT_EQ(region_parts(ring).holes, 1U);
    // Growing: two disks may become one, not one two; a hole may close or appear.
    EXPECT_FALSE(check(grows, two_disks(1.0), disk(3.0)));
    const auto torn = check(grows, disk(1.0), two_disks(1.0));
    ASSERT_TRUE(torn);
    EXPECT_NE(torn->find("the region's parts rose from 1 to 2 under a law that only grows it"),
              std::string::npos)
        << *torn;
    EXPECT_FALSE(region_parts_violation(grows, region_parts(solid), region_parts(ring)));
    // Shrinking: a hole may open to the outside or vanish, not appear; parts may split.
    EXPECT_FALSE(region_parts_violation(shrinks, region_parts(ring), region_parts(solid)));
    EXPECT_FALSE(
        region_parts_violation(shrinks, region_parts(disk(3.0)), region_parts(two_disks(1.0))));
    const auto pierced = region_parts_violation(shrinks, region_parts(solid), region_parts(ring));
    ASSERT_TRUE(pierced);
    EXPECT_NE(pierced->find("the region's holes rose from 0 to 1 under a law that only shrinks it"),
              std::string::npos)
        << *pierced;
    // The same counts for surfaces: a sphere with a cavity (an inward sphere inside it).
    Surface cavity = sphere({}, 0.2, 2);
    for (auto& t : cavity.triangles) std::swap(t[1], t[2]);
    const Surface ball = sphere({}, 0.5, 2);
    const Surface hollow = join({ball, cavity});
    const Surface pair = join({sphere({-0.6, 0, 0}, 0.3, 2), sphere({0.6, 0, 0}, 0.3, 2)});
    EXPECT_EQ(region_parts(hollow).parts, 1U);
    EXPECT_EQ(region_parts(hollow).holes, 1U);
    EXPECT_EQ(region_parts(pair).parts, 2U);
    EXPECT_TRUE(region_parts_violation(grows, region_parts(ball), region_parts(pair)));
    EXPECT_FALSE(region_parts_violation(grows, region_parts(pair), region_parts(ball)));
    EXPECT_FALSE(region_parts_violation(grows, region_parts(ball), region_parts(hollow)));
    EXPECT_TRUE(region_parts_violation(shrinks, region_parts(ball), region_parts(hollow)));
    EXPECT_FALSE(region_parts_violation(shrinks, region_parts(hollow), region_parts(ball)));
    // A law that claims neither is not checked.
    EXPECT_FALSE(region_parts_violation({}, region_parts(ball), region_parts(pair)));
}

TEST(Guards, CurvatureFlowLosesTwoPiPerCurve) {
    const Invariants curvature{.cannot_split = true, .area_rate_per_curve = -2.0 * pi};
    const double k = 0.01;
    // R² − 2k exactly; then a step that loses 40% too much.
    EXPECT_FALSE(check(curvature, disk(1.0), disk(std::sqrt(1.0 - 2.0 * k)), k));
    EXPECT_TRUE(check(curvature, disk(1.0), disk(std::sqrt(1.0 - 2.8 * k)), k));
    // Two curves lose twice as much.
    EXPECT_FALSE(check(curvature, two_disks(1.0), two_disks(std::sqrt(1.0 - 2.0 * k)), k));
    EXPECT_TRUE(check(curvature, two_disks(1.0), two_disks(std::sqrt(1.0 - 1.0 * k)), k));
    // No curve may split.
    EXPECT_TRUE(check(curvature, disk(1.0), two_disks(0.69), k));
}

TEST(Guards, CurvatureFlowVanishesOnlyWhenTheStepTakesTheArea) {
    const Invariants curvature{.cannot_split = true, .area_rate_per_curve = -2.0 * pi};
    const double k = 0.01;  // the step takes 2πk = 0.0628 of area: R² = 0.02
    EXPECT_FALSE(check(curvature, disk(std::sqrt(0.019)), Interface{}, k));
    const auto v = check(curvature, disk(std::sqrt(0.03)), Interface{}, k);
    ASSERT_TRUE(v);
    EXPECT_NE(v->find("which the law takes"), std::string::npos) << *v;
    // Below a cell's area the tree need not resolve it.
    EXPECT_FALSE(check(curvature, disk(std::sqrt(0.03)), Interface{}, k,
                       GuardBudget{.resolved_area = pi * 0.04}));
}

// Curvature flows shorten the curves: a step may lengthen them by 1% (a refined contour's chords
// grow towards their arcs), not more, which is how noise that roughens a curve shows first.
TEST(Guards, AShorteningFlowCannotLengthenTheCurves) {
    const Invariants shortens{.keeps_area = true, .shortens = true};
    const Interface circle = disk(1.0);
    std::vector<Vec2> rough = shapes::circle({}, 1.0, 256);
    for (std::size_t i = 0; i < rough.size(); ++i)  // a zigzag of ±1%, keeping the area
        rough[i] = (i % 2 == 0 ? 1.01 : 0.99) * rough[i];
    const Interface roughened(std::vector<std::vector<Vec2>>{rough});
    ASSERT_LT(std::abs(area(roughened) - area(circle)), 0.01 * area(circle));
    const auto v = check(shortens, circle, roughened);
    ASSERT_TRUE(v);
    EXPECT_NE(v->find("the length grew"), std::string::npos) << *v;
    EXPECT_FALSE(check(shortens, roughened, circle));
}

TEST(Guards, ALawThatClaimsNothingIsNeverChecked) {
    EXPECT_FALSE(check(Invariants{}, disk(1.0), Interface{}));
    EXPECT_FALSE(check(Invariants{}, disk(1.0), two_disks(0.1)));
}

}  // namespace
}  // namespace slc
