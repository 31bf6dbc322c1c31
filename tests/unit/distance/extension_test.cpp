// Tests of the nearest-point and Whitney extensions: agreement with brute force, the maximum
// principle, and continuity of the Whitney extension across cell edges.
#include "slc/distance/extension.hpp"

#include <gtest/gtest.h>

#include <random>

#include "random_interfaces.hpp"

namespace slc {
namespace {

const Box domain = Box::centered_square(1.5);

std::vector<Vec2> random_values(std::mt19937& rng, std::size_t n) {
    std::uniform_real_distribution<double> u(-3.0, 5.0);
    std::vector<Vec2> v(n);
    for (Vec2& x : v) x = {u(rng), u(rng)};
    return v;
}

TEST(NearestPointExtension, MatchesBruteForceNearestPoint) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        const Interface curves = testing::random_interface(rng);
        const DistanceTree tree(curves, domain, {.depth = 7, .triangulate = false});
        const auto values = random_values(rng, curves.size());
        std::uniform_real_distribution<double> u(-2.0, 2.0);
        std::vector<Vec2> xs(500);
        for (Vec2& x : xs) x = {u(rng), u(rng)};
        const auto fast = nearest_point_extension<Vec2>(tree, values, xs);
        for (std::size_t i = 0; i < xs.size(); ++i) {
            const Vec2 slow = nearest_point_extension<Vec2>(
                curves, values, closest_point_brute_force(curves, xs[i]));
            EXPECT_EQ(fast[i], slow);
        }
    }
}

TEST(NearestPointExtension, ReproducesVertexValuesOnTheCurve) {
    std::mt19937 rng(3);
    const Interface curves = testing::random_interface(rng);
    const DistanceTree tree(curves, domain, {.depth = 7, .triangulate = false});
    std::vector<double> values(curves.size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<double>(i);
    const auto at_vertices = nearest_point_extension<double>(tree, values, curves.points());
    for (std::size_t i = 0; i < values.size(); ++i) EXPECT_EQ(at_vertices[i], values[i]);
}

TEST(WhitneyExtension, ObeysTheMaximumPrincipleLikeTheNearestPointExtension) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        const Interface curves = testing::random_interface(rng);
        const DistanceTree tree(curves, domain, {.depth = 7, .triangulate = true});
        const auto values = random_values(rng, curves.size());
        Vec2 lo = values[0], hi = values[0];
        for (Vec2 v : values) {
            lo = {std::min(lo.x, v.x), std::min(lo.y, v.y)};
            hi = {std::max(hi.x, v.x), std::max(hi.y, v.y)};
        }
        const WhitneyExtension<Vec2> whitney(tree, values);
        std::uniform_real_distribution<double> u(-2.0, 2.0);
        std::vector<Vec2> xs(2000);
        for (Vec2& x : xs) x = {u(rng), u(rng)};
        const auto near = nearest_point_extension<Vec2>(tree, values, xs);
        const auto smooth = whitney(xs);
        // A convex combination of values of size ≤ 5 computed in floating point may leave their
        // range by a few roundings: 8 units in the last place of 5.
        const double rounding = 8 * 5.0 * std::numeric_limits<double>::epsilon();
        for (std::size_t i = 0; i < xs.size(); ++i) {
            for (const Vec2 w : {near[i], smooth[i]}) {
                EXPECT_GE(w.x, lo.x - rounding);
                EXPECT_LE(w.x, hi.x + rounding);
                EXPECT_GE(w.y, lo.y - rounding);
                EXPECT_LE(w.y, hi.y + rounding);
            }
        }
    }
}

TEST(WhitneyExtension, EqualsTheNearestPointExtensionAtTriangulationVertices) {
    std::mt19937 rng(4);
    const Interface curves = testing::random_interface(rng);
    const DistanceTree tree(curves, domain, {.depth = 6, .triangulate = true});
    const auto values = random_values(rng, curves.size());
    const WhitneyExtension<Vec2> whitney(tree, values);
    const auto& vertices = tree.triangulation().vertices;
    const auto direct = nearest_point_extension<Vec2>(tree, values, vertices);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        const Vec2 w = whitney(vertices[v]);
        EXPECT_NEAR(w.x, direct[v].x, 1e-12);
        EXPECT_NEAR(w.y, direct[v].y, 1e-12);
    }
}

TEST(WhitneyExtension, IsContinuousAcrossCellEdges) {
    // Rough vertex values make any jump visible: across an edge with a hanging vertex the two
    // sides would differ by O(1). A continuous piecewise-linear function changes by at most
    // |gradient| · 2δ between points δ either side of an edge.
    for (unsigned seed = 1; seed <= 10; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        const Interface curves = testing::random_interface(rng);
        const DistanceTree tree(curves, domain, {.depth = 7, .triangulate = true});
        const auto values = random_values(rng, curves.size());
        const WhitneyExtension<Vec2> whitney(tree, values);
        const Quadtree& q = tree.tree();
        const double finest = q.edge(q.depth());
        // Values span at most 8; slopes are at most 8 over half the finest edge (a triangle's
        // smallest height), times a margin of 4 for the triangle shapes.
        const double slope = 4 * 8.0 / (0.5 * finest);
        const double delta = 1e-9 * finest;
        std::uniform_real_distribution<double> t01(0.0, 1.0);
        for (std::uint32_t c : q.leaves()) {
            const Box b = q.box(c);
            const Vec2 right{b.hi.x, b.lo.y + t01(rng) * b.height()};
            const Vec2 top{b.lo.x + t01(rng) * b.width(), b.hi.y};
            if (right.x < domain.hi.x) {
                const Vec2 jump = whitney(right + Vec2{delta, 0}) - whitney(right - Vec2{delta, 0});
                EXPECT_LE(norm(jump), slope * 2 * delta) << "cell " << c;
            }
            if (top.y < domain.hi.y) {
                const Vec2 jump = whitney(top + Vec2{0, delta}) - whitney(top - Vec2{0, delta});
                EXPECT_LE(norm(jump), slope * 2 * delta) << "cell " << c;
            }
        }
    }
}

TEST(WhitneyExtension, RejectsAnUntriangulatedTreeAndWrongValueCounts) {
    std::mt19937 rng(1);
    const Interface curves = testing::random_interface(rng);
    const DistanceTree bare(curves, domain, {.depth = 5, .triangulate = false});
    const std::vector<double> values(curves.size(), 1.0);
    EXPECT_THROW(WhitneyExtension<double>(bare, values), InvalidInput);
    const DistanceTree tree(curves, domain, {.depth = 5, .triangulate = true});
    const std::vector<double> too_few(curves.size() - 1, 1.0);
    EXPECT_THROW(WhitneyExtension<double>(tree, too_few), InvalidInput);
}

}  // namespace
}  // namespace slc
