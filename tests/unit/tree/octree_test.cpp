// Tests of the octree's structure: children's cubes, point location, depth limits.
#include "slc/tree/octree.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace slc
