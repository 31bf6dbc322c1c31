// Tests of the distance tree against brute force, the even-odd sign oracle and the tree's
// defining invariants.
#include "slc/distance/distance_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "random_interfaces.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/shapes.hpp"

namespace slc {
namespace {

const Box domain = Box::centered_square(1.5);

/// Query points of every kind: uniform in and beyond the domain, on and near vertices, on and
/// near segments, and far away.
std::vector<Vec2> query_points(const Interface& curves, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.5, 1.5), far(-50.0, 50.0), t01(0.0, 1.0);
    std::normal_distribution<double> tiny(0.0, 1e-6), small(0.0, 1e-2);
    std::uniform_int_distribution<std::size_t> vertex(0, curves.size() - 1);
    std::vector<Vec2> xs;
    for (int k = 0; k < 300; ++k) xs.push_back({u(rng), u(rng)});
    for (int k = 0; k < 20; ++k) xs.push_back({far(rng), far(rng)});
    for (int k = 0; k < 100; ++k) {
        const std::size_t i = vertex(rng);
        const Segment s = curves.segment(i);
        xs.push_back(s.a);                               // on a vertex
        xs.push_back(s.a + t01(rng) * (s.b - s.a));      // on a segment (to rounding)
        xs.push_back(s.a + Vec2{tiny(rng), tiny(rng)});  // near a vertex
        xs.push_back(s.a + 0.5 * (s.b - s.a) + Vec2{small(rng), small(rng)});
    }
    return xs;
}

TEST(DistanceTree, AgreesWithBruteForceOnRandomInterfaces) {
    for (unsigned seed = 1; seed <= 60; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        const Interface curves = testing::random_interface(rng);
        const DistanceTree tree(curves, domain,
                                {.depth = 3 + static_cast<int>(seed % 8), .triangulate = false});
        for (const Vec2 x : query_points(curves, rng)) {
            const ClosestPoint fast = tree.closest_point(x);
            const ClosestPoint slow = closest_point_brute_force(curves, x);
            // Both take the lowest-numbered of the nearest segments and compute its distance by
            // the same arithmetic, so the answers agree to the last bit.
            ASSERT_EQ(fast.distance, slow.distance) << "at (" << x.x << ", " << x.y << ")";
            ASSERT_EQ(fast.segment, slow.segment);
            ASSERT_EQ(fast.point, slow.point);
        }
    }
}

TEST(DistanceTree, NearestPointIsTheClosestPointWithoutItsSign) {
    for (unsigned seed = 200; seed < 230; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        const Interface curves = testing::random_interface(rng);
        const DistanceTree tree(curves, domain,
                                {.depth = 3 + static_cast<int>(seed % 8), .triangulate = false});
        for (const Vec2 x : query_points(curves, rng)) {
            const ClosestPoint slow = closest_point_brute_force(curves, x);
            const ClosestPoint p = tree.nearest_point(x);
            ASSERT_EQ(p.distance, std::abs(slow.distance)) << "at (" << x.x << ", " << x.y << ")";
            ASSERT_EQ(p.segment, slow.segment);
            ASSERT_EQ(p.point, slow.point);
            ASSERT_EQ(p.t, slow.t);
        }
    }
}

TEST(DistanceTree, SignAgreesWithTheEvenOddRule) {
    for (unsigned seed = 100; seed < 140; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        const Interface curves = testing::random_interface(rng);
        const DistanceTree tree(curves, domain, {.depth = 8, .triangulate = false});
        for (const Vec2 x : query_points(curves, rng)) {
            const double d = tree.closest_point(x).distance;
            // Within rounding of Γ the crossing-number test itself is unreliable.
            if (std::abs(d) < 1e-12) continue;
            ASSERT_EQ(d < 0, is_inside_even_odd(curves, x)) << "at (" << x.x << ", " << x.y << ")";
        }
    }
}

TEST(DistanceTree, SignIsRightAtConvexAndConcaveCorners) {
    // An L-shape: convex corners and one concave corner at (0, 0).
    const Interface l_shape({{{-1, -1}, {1, -1}, {1, 0}, {0, 0}, {0, 1}, {-1, 1}}});
    const DistanceTree tree(l_shape, domain, {.depth = 6, .triangulate = false});
    const double e = 1e-3;
    // Near the convex corner (1, −1): outside along the diagonal, inside along the diagonal.
    EXPECT_NEAR(tree.closest_point({1 + e, -1 - e}).distance, std::sqrt(2.0) * e, 1e-15);
    EXPECT_NEAR(tree.closest_point({1 - e, -1 + e}).distance, -e, 1e-15);
    // At the concave corner (0, 0): outside, the two edges are nearest; inside along the
    // diagonal the corner itself is nearest and the pseudo-normal gives the sign.
    EXPECT_NEAR(tree.closest_point({e, e}).distance, e, 1e-15);
    EXPECT_NEAR(tree.closest_point({-e, -e}).distance, -std::sqrt(2.0) * e, 1e-15);
    EXPECT_EQ(tree.closest_point({-e, -e}).point, (Vec2{0, 0}));
    // On the curve the distance is exactly zero.
    EXPECT_EQ(tree.closest_point({0, 0}).distance, 0.0);
    EXPECT_EQ(tree.closest_point({0.5, -1}).distance, 0.0);
    EXPECT_EQ(tree.closest_point({-1, 1}).distance, 0.0);  // a convex corner
}

TEST(DistanceTree, LeavesAboveTheDepthLimitAreAtLeastAnEdgeAwayFromTheCurve) {
    std::mt19937 rng(5);
    const Interface curves = testing::random_interface(rng);
    const DistanceTree tree(curves, domain, {.depth = 7, .triangulate = false});
    const Quadtree& q = tree.tree();
    for (std::uint32_t c : q.leaves()) {
        if (q.cell(c).level == q.max_depth()) continue;
        const Box b = q.box(c);
        // Distance from the cell to Γ, from below: sampled points of the cell, minus half the
        // sampling diagonal.
        double d = std::numeric_limits<double>::infinity();
        const int n = 8;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                const Vec2 p{b.lo.x + b.width() * i / n, b.lo.y + b.height() * j / n};
                d = std::min(d, std::abs(closest_point_brute_force(curves, p).distance));
            }
        EXPECT_GE(d + b.width() / n, q.edge(q.cell(c).level) * (1 - 1e-12));
    }
    EXPECT_TRUE(q.is_balanced());
}

TEST(DistanceTree, CellListsHoldEverySegmentMeetingTheTriple) {
    std::mt19937 rng(8);
    const Interface curves = testing::random_interface(rng);
    const DistanceTree tree(curves, domain, {.depth = 6, .triangulate = false});
    const Quadtree& q = tree.tree();
    for (std::size_t c = 0; c < q.size(); ++c) {
        const auto list = tree.cell_segments(c);
        const Box t = q.triple(c);
        for (std::size_t s = 0; s < curves.size(); ++s) {
            // A sampled point of the segment inside the triple proves the segment meets it.
            const Segment seg = curves.segment(s);
            bool inside = false;
            for (int k = 0; k <= 64 && !inside; ++k)
                inside = t.contains(seg.a + (k / 64.0) * (seg.b - seg.a));
            if (inside) {
                EXPECT_TRUE(std::binary_search(list.begin(), list.end(), s)) << "cell " << c;
            }
        }
    }
}

TEST(DistanceTree, CostGrowsAsNLogN) {
    // A circle of N segments in a tree of depth log2 N: cells grow like N and list entries like
    // N log N at most. Counts, not seconds.
    std::vector<double> cells_per_n, entries_per_nlogn;
    for (int k = 8; k <= 14; k += 2) {
        const int n = 1 << k;
        const Interface circle({shapes::circle({0.1, -0.05}, 1.0, n)});
        const DistanceTree tree(circle, domain, {.depth = k - 1, .triangulate = false});
        std::size_t entries = 0;
        for (std::size_t c = 0; c < tree.tree().size(); ++c)
            entries += tree.cell_segments(c).size();
        cells_per_n.push_back(static_cast<double>(tree.tree().size()) / n);
        entries_per_nlogn.push_back(static_cast<double>(entries) / (n * k));
    }
    for (std::size_t i = 1; i < cells_per_n.size(); ++i) {
        // Growth by a factor 4 in N may change the ratio only by a bounded factor near 1.
        EXPECT_LT(cells_per_n[i] / cells_per_n[i - 1], 1.25);
        EXPECT_LT(entries_per_nlogn[i] / entries_per_nlogn[i - 1], 1.25);
    }
}

TEST(DistanceTree, BatchAnswersDoNotDependOnThreadCount) {
    std::mt19937 rng(77);
    const Interface curves = testing::random_interface(rng);
    const DistanceTree tree(curves, domain, {.depth = 8, .triangulate = true});
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    std::vector<Vec2> xs(20000);
    for (Vec2& x : xs) x = {u(rng), u(rng)};
    set_thread_count(1);
    const auto one = tree.signed_distances(xs);
    set_thread_count(2);
    const auto two = tree.signed_distances(xs);
    set_thread_count(0);
    EXPECT_EQ(one, two);
}

TEST(DistanceTree, CellsAndListsDoNotDependOnThreadCount) {
    // 8192 segments: enough list entries per level for the build to use every worker thread.
    const Interface circle({shapes::polar(
        {0.05, -0.1}, [](double t) { return 0.9 + 0.2 * std::cos(5 * t); }, 8192)});
    set_thread_count(1);
    const DistanceTree one(circle, domain, {.depth = 11, .triangulate = false});
    set_thread_count(2);
    const DistanceTree two(circle, domain, {.depth = 11, .triangulate = false});
    set_thread_count(0);
    ASSERT_EQ(one.tree().size(), two.tree().size());
    for (std::size_t c = 0; c < one.tree().size(); ++c) {
        ASSERT_EQ(one.tree().cell(c).first_child, two.tree().cell(c).first_child) << "cell " << c;
        const auto a = one.cell_segments(c), b = two.cell_segments(c);
        ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "cell " << c;
    }
    // The long lists of the coarse levels, against their definition: every segment whose box
    // meets the triple, in increasing order.
    const Quadtree& q = two.tree();
    for (std::size_t c = 0; c < q.size(); ++c) {
        if (q.cell(c).level > 4) continue;
        std::vector<std::uint32_t> expected;
        for (std::uint32_t s = 0; s < circle.size(); ++s)
            if (bounding_box(circle.segment(s)).overlaps(q.triple(c))) expected.push_back(s);
        const auto list = two.cell_segments(c);
        EXPECT_TRUE(std::equal(list.begin(), list.end(), expected.begin(), expected.end()))
            << "cell " << c << " lists " << list.size() << ", expected " << expected.size();
    }
}

TEST(DistanceTree, CopiesAndMovesKeepEveryList) {
    std::mt19937 rng(5);
    const Interface curves = testing::random_interface(rng);
    const Interface other({shapes::circle({}, 0.5, 64)});
    const DistanceTree tree(curves, domain, {.depth = 7, .triangulate = false});
    DistanceTree copied = tree;
    DistanceTree assigned(other, domain, {.depth = 9, .triangulate = false});
    assigned = tree;
    DistanceTree moved = std::move(copied);
    DistanceTree move_assigned(other, domain, {.depth = 9, .triangulate = false});
    move_assigned = DistanceTree(tree);
    for (const DistanceTree* t : {&assigned, &moved, &move_assigned}) {
        ASSERT_EQ(t->tree().size(), tree.tree().size());
        for (std::size_t c = 0; c < tree.tree().size(); ++c) {
            const auto a = tree.cell_segments(c), b = t->cell_segments(c);
            ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "cell " << c;
        }
        for (const Vec2 x : query_points(curves, rng))
            ASSERT_EQ(t->closest_point(x).distance, tree.closest_point(x).distance);
    }
}

TEST(DistanceTree, RejectsAnEmptyInterfaceAndBadDomains) {
    const Interface none;
    EXPECT_THROW(DistanceTree(none, domain, {}), InvalidInput);
    const Interface square({shapes::rectangle({-0.5, -0.5}, {0.5, 0.5})});
    EXPECT_THROW(DistanceTree(square, Box{{-1, -1}, {1, 2}}, {}), InvalidInput);
    EXPECT_THROW(DistanceTree(square, domain, {.depth = 99}), InvalidInput);
}

}  // namespace
}  // namespace slc
