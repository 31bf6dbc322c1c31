// Tests of the climbing query's public answers, each run on the curves' and the surfaces' tree:
// the nearest point is the closest point without its sign, and the batches answer as the single
// queries do, whatever the thread count. Agreement with brute force is each tree's own test.
#include "slc/distance/climbing_query.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "slc/core/parallel.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/geometry/validate_surface.hpp"

namespace slc {
namespace {

/// A tree of each dimension on a round interface (a circle of 400 segments; a sphere), with
/// query points near it, far from it and beyond the domain.
template <class Tree>
struct Case;

template <>
struct Case<DistanceTree> {
    Interface curves{std::vector<std::vector<Vec2>>{shapes::circle({0.1, -0.05}, 0.7, 400)}};
    DistanceTree tree{curves, Box::centered_square(1.5), {.depth = 8, .triangulate = false}};

    static Vec2 point(std::mt19937& rng, double r) {
        std::uniform_real_distribution<double> u(-r, r);
        return {u(rng), u(rng)};
    }
    static bool same(const ClosestPoint& a, const ClosestPoint& b) {
        return a.distance == b.distance && a.point == b.point && a.segment == b.segment &&
               a.t == b.t;
    }
};

template <>
struct Case<SurfaceDistanceTree> {
    Surface surface = prepare_surface(sphere({0.1, -0.05, 0.02}, 0.7, 3)).surface;
    SurfaceDistanceTree tree{surface, Box3::centered_cube(1.5), {.depth = 5}};

    static Vec3 point(std::mt19937& rng, double r) {
        std::uniform_real_distribution<double> u(-r, r);
        return {u(rng), u(rng), u(rng)};
    }
    static bool same(const SurfacePoint& a, const SurfacePoint& b) {
        return a.distance == b.distance && a.point == b.point && a.triangle == b.triangle &&
               a.weights == b.weights && a.feature == b.feature && a.index == b.index;
    }
};

/// Points in the domain, beyond it, and far away.
template <class Tree>
std::vector<typename Tree::Point> query_points(std::mt19937& rng) {
    std::vector<typename Tree::Point> xs;
    for (int k = 0; k < 3000; ++k) xs.push_back(Case<Tree>::point(rng, 1.5));
    for (int k = 0; k < 100; ++k) xs.push_back(Case<Tree>::point(rng, 40.0));
    return xs;
}

template <class Tree>
class ClimbingQueryTest : public ::testing::Test {};
using Trees = ::testing::Types<DistanceTree, SurfaceDistanceTree>;
TYPED_TEST_SUITE(ClimbingQueryTest, Trees);

TYPED_TEST(ClimbingQueryTest, NearestPointIsTheClosestPointWithoutItsSign) {
    const Case<TypeParam> c;
    std::mt19937 rng(5);
    for (const auto& x : query_points<TypeParam>(rng)) {
        auto signed_point = c.tree.closest_point(x);
        signed_point.distance = std::abs(signed_point.distance);
        EXPECT_TRUE(Case<TypeParam>::same(c.tree.nearest_point(x), signed_point));
    }
}

TYPED_TEST(ClimbingQueryTest, BatchesAnswerAsSingleQueriesOnAnyThreadCount) {
    const Case<TypeParam> c;
    std::mt19937 rng(6);
    const auto xs = query_points<TypeParam>(rng);
    for (int threads : {1, 2, 0}) {
        set_thread_count(threads);
        const auto points = c.tree.closest_points(xs);
        std::vector<typename TypeParam::Answer> into(xs.size());
        c.tree.closest_points(xs, into);
        const std::vector<double> distances = c.tree.signed_distances(xs);
        ASSERT_EQ(points.size(), xs.size());
        ASSERT_EQ(distances.size(), xs.size());
        for (std::size_t i = 0; i < xs.size(); ++i) {
            const auto one = c.tree.closest_point(xs[i]);
            EXPECT_TRUE(Case<TypeParam>::same(points[i], one)) << "threads " << threads;
            EXPECT_TRUE(Case<TypeParam>::same(into[i], one)) << "threads " << threads;
            EXPECT_EQ(distances[i], one.distance) << "threads " << threads;
        }
    }
    set_thread_count(0);
}

}  // namespace
}  // namespace slc
