// Tests of the self-convergence pieces: the options of each resolution, the distance between two
// interfaces against brute force, the runs that cannot be compared, the estimate's clamp.
#include "slc/evolve/self_convergence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "random_interfaces.hpp"
#include "slc/core/error.hpp"
#include "slc/geometry/segment.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/velocity/laws.hpp"

namespace slc {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

RunOptions base_options() {
    RunOptions o;
    o.t_end = 0.5;
    o.steps = 10;
    o.step.contour.depth = 4;
    o.step.contour.refine_passes = 2;
    o.step.contour.eps = 1e-3;
    o.step.contour.eta = 1e-10;
    o.step.embedded.mesh = 32;
    return o;
}

/// The symmetric Hausdorff distance at vertices and midpoints, by brute force.
double brute_force_distance(const Interface& a, const Interface& b) {
    double d = 0.0;
    for (Vec2 x : vertices_and_midpoints(a))
        d = std::max(d, std::abs(closest_point_brute_force(b, x).distance));
    for (Vec2 x : vertices_and_midpoints(b))
        d = std::max(d, std::abs(closest_point_brute_force(a, x).distance));
    return d;
}

TEST(ResolutionOptions, RefinesStepsDepthEpsAndMeshTogether) {
    const RunOptions o = resolution_options(base_options(), 2);
    EXPECT_EQ(o.steps, 40);
    EXPECT_EQ(o.step.contour.depth, 6);
    EXPECT_DOUBLE_EQ(*o.step.contour.eps, 1e-3 / 16);
    EXPECT_EQ(o.step.embedded.mesh, 128);
    EXPECT_EQ(o.step.tree_depth, 0);  // the default, resolved from K and P at each level
    EXPECT_EQ(o.step.contour.refine_passes, 2);
    EXPECT_EQ(o.step.contour.eta, 1e-10);
    EXPECT_EQ(o.t_end, 0.5);
}

TEST(ResolutionOptions, HalfResolutionIsLevelMinusOne) {
    RunOptions base = base_options();
    base.step.tree_depth = 7;
    const RunOptions o = resolution_options(base, -1);
    EXPECT_EQ(o.steps, 5);
    EXPECT_EQ(o.step.contour.depth, 3);
    EXPECT_DOUBLE_EQ(*o.step.contour.eps, 4e-3);
    EXPECT_EQ(o.step.embedded.mesh, 16);
    EXPECT_EQ(o.step.tree_depth, 6);
}

TEST(ResolutionOptions, KeepsEpsAboveEta) {
    RunOptions base = base_options();
    base.step.contour.eps = 1e-9;
    EXPECT_EQ(*resolution_options(base, 3).step.contour.eps, 1e-10);
}

TEST(ResolutionOptions, RejectsTooFewStepsOrLevels) {
    RunOptions base = base_options();
    base.steps = 1;
    EXPECT_THROW(resolution_options(base, -1), InvalidInput);
    base = base_options();
    base.step.contour.depth = 1;
    EXPECT_THROW(resolution_options(base, -1), InvalidInput);
}

TEST(InterfaceDistance, AgreesWithBruteForceOnRandomInterfaces) {
    constexpr unsigned seed = 20240611;
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 40; ++trial) {
        const Interface a = testing::random_interface(rng);
        const Interface b = testing::random_interface(rng);
        if (a.empty() || b.empty()) continue;
        // Both are exact distances to the same segments: equal to rounding.
        const double d = interface_distance(a, b);
        EXPECT_NEAR(d, brute_force_distance(a, b), 1e-14) << "seed " << seed << " trial " << trial;
        EXPECT_EQ(d, interface_distance(b, a));
    }
}

TEST(InterfaceDistance, IsTheGapBetweenConcentricCircles) {
    const Interface inner({shapes::circle({0.3, -0.2}, 1.0, 2048)});
    const Interface outer({shapes::circle({0.3, -0.2}, 1.1, 2048)});
    // The outer vertices lie 0.1 from the inner circle, a little more from its chords (by at most
    // R(1 − cos(π/n)) ≈ 1.2e-6).
    EXPECT_NEAR(interface_distance(inner, outer), 0.1, 2e-6);
    EXPECT_NEAR(interface_distance(inner, inner), 0.0, 1e-15);  // midpoints: rounding
}

TEST(InterfaceDistance, EmptyInterfaces) {
    const Interface circle({shapes::circle({}, 1.0, 16)});
    EXPECT_EQ(interface_distance(Interface(), Interface()), 0.0);
    EXPECT_EQ(interface_distance(circle, Interface()), infinity);
    EXPECT_EQ(interface_distance(Interface(), circle), infinity);
}

TEST(FinalDistance, IsInfiniteForRunsThatEndedDifferently) {
    RunResult a, b;
    a.curves = b.curves = Interface({shapes::circle({}, 1.0, 16)});
    a.t = b.t = 1.0;
    EXPECT_NEAR(final_distance(a, b), 0.0, 1e-15);
    b.status = RunStatus::error;
    EXPECT_EQ(final_distance(a, b), infinity);
    b.status = RunStatus::ok;
    b.t = 0.5;
    EXPECT_EQ(final_distance(a, b), infinity);
    a.curves = b.curves = Interface();  // both vanished
    a.status = b.status = RunStatus::vanished;
    EXPECT_EQ(final_distance(a, b), infinity);
}

TEST(ErrorEstimate, ClampsTheOrder) {
    EXPECT_DOUBLE_EQ(error_estimate(0.3, 2.0), 0.1);
    EXPECT_DOUBLE_EQ(error_estimate(0.3, 1.0), 0.3);
    EXPECT_DOUBLE_EQ(error_estimate(1.5, 9.0), 0.1);                          // p = 4
    EXPECT_DOUBLE_EQ(error_estimate(1.0, -3.0), 1.0 / (std::sqrt(2.0) - 1));  // p = 1/2
}

TEST(ObserveOrders, FromTheDistancesOfNeighbours) {
    std::vector<std::optional<double>> orders;
    std::optional<ErrorEstimate> estimate;
    observe_orders(std::vector{0.4, 0.1, 0.025}, orders, estimate);
    ASSERT_EQ(orders.size(), 2u);
    EXPECT_DOUBLE_EQ(*orders[0], 2.0);
    EXPECT_DOUBLE_EQ(*orders[1], 2.0);
    ASSERT_TRUE(estimate);
    EXPECT_DOUBLE_EQ(estimate->error, 0.025 / 3.0);
    EXPECT_TRUE(estimate->observed);
    // No order before the last pair: first order assumed.
    observe_orders(std::vector{infinity, 0.1}, orders, estimate);
    ASSERT_EQ(orders.size(), 1u);
    EXPECT_FALSE(orders[0]);
    ASSERT_TRUE(estimate);
    EXPECT_DOUBLE_EQ(estimate->error, 0.1);
    EXPECT_FALSE(estimate->observed);
    // The last pair not comparable: no estimate.
    observe_orders(std::vector{0.1, infinity}, orders, estimate);
    EXPECT_FALSE(orders[0]);
    EXPECT_FALSE(estimate);
}

TEST(SelfConvergence, RejectsResolutionsOutOfRange) {
    const Interface circle({shapes::circle({}, 0.5, 32)});
    const Rotation law(1.0);
    for (int r : {0, 2, 6})
        EXPECT_THROW(self_convergence(circle, law, Box::centered_square(1), base_options(), r),
                     InvalidInput);
}

TEST(SelfConvergence, ReportsRunsThatCannotBeCompared) {
    // A circle of radius 0.3 under curvature flow vanishes at t = 0.045: every run ends empty.
    const Interface circle({shapes::circle({}, 0.3, 64)});
    const CurvatureFlow law;
    RunOptions base = base_options();
    base.t_end = 0.1;
    base.steps = 4;
    base.step.contour.depth = 3;
    const SelfConvergenceResult s = self_convergence(circle, law, Box::centered_square(1), base, 3);
    ASSERT_EQ(s.runs.size(), 3u);
    ASSERT_EQ(s.distances.size(), 2u);
    ASSERT_EQ(s.orders.size(), 1u);
    for (const ResolutionRun& r : s.runs) EXPECT_EQ(r.result.status, RunStatus::vanished);
    for (double d : s.distances) EXPECT_EQ(d, infinity);
    EXPECT_FALSE(s.orders[0]);
    EXPECT_FALSE(s.estimate);
}

}  // namespace
}  // namespace slc
