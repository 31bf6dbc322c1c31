// Tests of the octree's structure: children's cubes, point location, depth limits, face
// neighbours and 2:1 balance against brute force over all pairs of leaves.
#include "slc/tree/octree.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "slc/core/error.hpp"

namespace slc {
namespace {

TEST(Octree, ChildrenTileTheirParentInOrder) {
    Octree tree(Box3::cube({1, 2, 3}, 2.0), 4);
    const std::uint32_t first = tree.split(0);
    const Box3 root = tree.box(0);
    for (std::uint32_t k = 0; k < 8; ++k) {
        const Box3 b = tree.box(first + k);
        EXPECT_EQ(b.width(), 2.0);
        EXPECT_EQ(b.lo.x, (k & 1) ? 1.0 : -1.0);
        EXPECT_EQ(b.lo.y, (k & 2) ? 2.0 : 0.0);
        EXPECT_EQ(b.lo.z, (k & 4) ? 3.0 : 1.0);
        EXPECT_TRUE(root.contains(b));
        EXPECT_EQ(tree.cell(first + k).parent, 0u);
        EXPECT_EQ(tree.triple(first + k), b.inflated(2.0));
    }
}

TEST(Octree, LeafAtFindsTheLeafHoldingThePoint) {
    Octree tree(Box3::centered_cube(1.0), 6);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    // Refine around a point, irregularly.
    for (int k = 0; k < 200; ++k) {
        const std::uint32_t leaf = tree.leaf_at({u(rng) * 0.3, u(rng) * 0.3, u(rng) * 0.3});
        if (tree.cell(leaf).level < tree.max_depth()) tree.split(leaf);
    }
    for (int k = 0; k < 5000; ++k) {
        const Vec3 p{u(rng), u(rng), u(rng)};
        const std::uint32_t leaf = tree.leaf_at(p);
        ASSERT_TRUE(tree.is_leaf(leaf));
        ASSERT_TRUE(tree.box(leaf).contains(p));
    }
    // Outside: the leaf of the nearest point of the root box.
    EXPECT_TRUE(tree.box(tree.leaf_at({5, -5, 0.1})).contains(Vec3{1, -1, 0.1}));
}

TEST(Octree, RefusesBadRootsAndDepths) {
    EXPECT_THROW(Octree(Box3{{0, 0, 0}, {1, 1, 2}}, 3), InvalidInput);
    EXPECT_THROW(Octree(Box3::centered_cube(1.0), -1), InvalidInput);
    EXPECT_THROW(Octree(Box3::centered_cube(1.0), Octree::max_supported_depth + 1), InvalidInput);
    EXPECT_EQ(Octree::max_resolvable_depth(Box3::centered_cube(1e101)), -1);
    EXPECT_EQ(Octree::max_resolvable_depth(Box3::centered_cube(1.0)), Octree::max_supported_depth);
}

/// A deliberately unbalanced tree: cells holding any of `points` random points split to `depth`.
Octree graded_tree(int depth, std::mt19937& rng, int points) {
    Octree tree(Box3::centered_cube(1.0), depth);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < points; ++k) {
        const Vec3 p{u(rng), u(rng), u(rng)};
        for (std::uint32_t leaf = tree.leaf_at(p); tree.cell(leaf).level < depth;
             leaf = tree.leaf_at(p))
            tree.split(leaf);
    }
    return tree;
}

/// True when two cubes share part of a face of positive area (the trees' corners are dyadic, so
/// exact).
bool share_face(const Box3& a, const Box3& b) {
    int touching = 0, overlapping = 0;
    for (int i = 0; i < 3; ++i) {
        if (a.hi[i] == b.lo[i] || b.hi[i] == a.lo[i]) ++touching;
        if (std::min(a.hi[i], b.hi[i]) > std::max(a.lo[i], b.lo[i])) ++overlapping;
    }
    return touching == 1 && overlapping == 2;
}

/// Brute force over all pairs of leaves: true when face-adjacent leaves differ by at most one
/// level.
bool balanced_by_pairs(const Octree& tree) {
    const auto leaves = tree.leaves();
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        for (std::size_t j = i + 1; j < leaves.size(); ++j) {
            if (share_face(tree.box(leaves[i]), tree.box(leaves[j])) &&
                std::abs(tree.cell(leaves[i]).level - tree.cell(leaves[j]).level) > 1) {
                return false;
            }
        }
    }
    return true;
}

TEST(Octree, NeighbourIsTheCellAcrossEachFace) {
    std::mt19937 rng(3);
    const Octree tree = graded_tree(5, rng, 6);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const Box3 b = tree.box(c);
        const double h = b.width();
        for (int d = 0; d < 6; ++d) {
            // The centre of the same-size cube across face d.
            const double s = (d & 1) ? h : -h;
            const int a = d / 2;
            const Vec3 across =
                b.center() + Vec3{a == 0 ? s : 0.0, a == 1 ? s : 0.0, a == 2 ? s : 0.0};
            const std::uint32_t n = tree.neighbour(c, d);
            if (!tree.root_box().contains(across)) {
                EXPECT_EQ(n, Octree::no_cell) << "cell " << c << " direction " << d;
                continue;
            }
            // The same-level cell there, or the deepest existing cell holding it.
            ASSERT_NE(n, Octree::no_cell);
            EXPECT_TRUE(tree.box(n).contains(across)) << "cell " << c << " direction " << d;
            EXPECT_LE(tree.cell(n).level, tree.cell(c).level);
            if (tree.cell(n).level < tree.cell(c).level) {
                EXPECT_TRUE(tree.is_leaf(n));
            }
        }
    }
}

TEST(Octree, BalanceLeavesFaceNeighboursWithinOneLevel) {
    for (unsigned seed = 1; seed <= 8; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        Octree tree = graded_tree(6, rng, 3);
        EXPECT_FALSE(tree.is_balanced());
        EXPECT_FALSE(balanced_by_pairs(tree));
        std::size_t splits = 0;
        tree.balance([&](std::size_t c) {
            EXPECT_FALSE(tree.is_leaf(c));
            ++splits;
        });
        EXPECT_GT(splits, 0u);
        EXPECT_TRUE(tree.is_balanced());
        EXPECT_TRUE(balanced_by_pairs(tree));
    }
}

TEST(Octree, IsBalancedAgreesWithAllPairsOfLeaves) {
    // Graded trees, balanced and not, and every intermediate tree of their balancing.
    int balanced = 0, unbalanced = 0;
    for (unsigned seed = 1; seed <= 12; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        Octree tree =
            graded_tree(2 + static_cast<int>(seed % 3), rng, 1 + static_cast<int>(seed % 3));
        auto check = [&] {
            const bool expected = balanced_by_pairs(tree);
            EXPECT_EQ(tree.is_balanced(), expected);
            (expected ? balanced : unbalanced) += 1;
        };
        check();
        tree.balance([&](std::size_t) { check(); });
        check();
    }
    EXPECT_GT(balanced, 12);  // both answers were asked for
    EXPECT_GT(unbalanced, 12);
}

}  // namespace
}  // namespace slc
