// Tests of the quadtree: point location, lookup by coordinates, and 2:1 balancing.
#include "slc/tree/quadtree.hpp"

#include <gtest/gtest.h>

#include <random>

#include "slc/core/error.hpp"

namespace slc {
namespace {

/// A deliberately unbalanced tree: cells holding any of a few points split to full depth.
Quadtree graded_tree(int depth, std::mt19937& rng, int points) {
    Quadtree tree(Box::centered_square(1.0), depth);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < points; ++k) {
        const Vec2 p{u(rng), u(rng)};
        std::uint32_t c = tree.leaf_at(p);
        while (tree.cell(c).level < depth) {
            tree.split(c);
            c = tree.leaf_at(p);
        }
    }
    return tree;
}

/// Brute force: do two leaves share part of an edge?
bool share_edge(const Box& a, const Box& b) {
    const double tol = 1e-15;
    const bool x_touch = std::abs(a.hi.x - b.lo.x) < tol || std::abs(b.hi.x - a.lo.x) < tol;
    const bool y_touch = std::abs(a.hi.y - b.lo.y) < tol || std::abs(b.hi.y - a.lo.y) < tol;
    const bool x_overlap = std::min(a.hi.x, b.hi.x) - std::max(a.lo.x, b.lo.x) > tol;
    const bool y_overlap = std::min(a.hi.y, b.hi.y) - std::max(a.lo.y, b.lo.y) > tol;
    return (x_touch && y_overlap) || (y_touch && x_overlap);
}

TEST(Quadtree, DepthIsLimitedToCellsDoublesResolve) {
    // Centred: only the supported depth limits. A unit square at 1e12, where doubles are 1.2e-4
    // apart: cells must stay above 2^-42 · 1e12 ≈ 0.23, so depth 2 (0.25) is the deepest.
    EXPECT_EQ(Quadtree::max_resolvable_depth(Box::centered_square(1e-50)),
              Quadtree::max_supported_depth);
    const Box far{{1e12, 1e12}, {1e12 + 1, 1e12 + 1}};
    EXPECT_EQ(Quadtree::max_resolvable_depth(far), 2);
    EXPECT_NO_THROW(Quadtree(far, 2));
    EXPECT_THROW(Quadtree(far, 3), InvalidInput);
    // Out of range: too large, too small, not square.
    EXPECT_EQ(Quadtree::max_resolvable_depth(Box::centered_square(1e101)), -1);
    EXPECT_EQ(Quadtree::max_resolvable_depth(Box::centered_square(1e-101)), -1);
    EXPECT_EQ(Quadtree::max_resolvable_depth(Box{{0, 0}, {1, 2}}), -1);
    EXPECT_THROW(Quadtree(Box::centered_square(1e101), 0), InvalidInput);
}

TEST(Quadtree, LeafAtReturnsTheLeafContainingThePoint) {
    std::mt19937 rng(7);
    const Quadtree tree = graded_tree(8, rng, 5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < 2000; ++k) {
        const Vec2 p{u(rng), u(rng)};
        const std::uint32_t c = tree.leaf_at(p);
        EXPECT_TRUE(tree.is_leaf(c));
        EXPECT_TRUE(tree.box(c).contains(p));
    }
    EXPECT_TRUE(tree.box(tree.leaf_at({5.0, -7.0})).contains(Vec2{1.0, -1.0}));
}

TEST(Quadtree, FindReturnsCellOrDeepestAncestor) {
    std::mt19937 rng(11);
    const Quadtree tree = graded_tree(6, rng, 3);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const auto& cell = tree.cell(c);
        EXPECT_EQ(tree.find(cell.level, cell.ix, cell.iy), c);
    }
    EXPECT_EQ(tree.find(3, -1, 0), Quadtree::no_cell);
    EXPECT_EQ(tree.find(3, 0, 8), Quadtree::no_cell);
}

TEST(Quadtree, NeighbourAgreesWithLookupByCoordinates) {
    std::mt19937 rng(13);
    const Quadtree tree = graded_tree(7, rng, 6);
    const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const auto& cell = tree.cell(c);
        for (int d = 0; d < 4; ++d) {
            EXPECT_EQ(tree.neighbour(c, dx[d], dy[d]),
                      tree.find(cell.level, std::int64_t{cell.ix} + dx[d],
                                std::int64_t{cell.iy} + dy[d]));
        }
    }
}

TEST(Quadtree, BalanceLeavesEdgeNeighboursWithinOneLevel) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        Quadtree tree = graded_tree(7, rng, 4);
        EXPECT_FALSE(tree.is_balanced());
        std::size_t splits = 0;
        tree.balance([&](std::size_t c) {
            EXPECT_FALSE(tree.is_leaf(c));
            ++splits;
        });
        EXPECT_GT(splits, 0u);
        EXPECT_TRUE(tree.is_balanced());
        // Brute force over all pairs of leaves.
        const auto leaves = tree.leaves();
        for (std::size_t i = 0; i < leaves.size(); ++i) {
            for (std::size_t j = i + 1; j < leaves.size(); ++j) {
                if (!share_edge(tree.box(leaves[i]), tree.box(leaves[j]))) continue;
                EXPECT_LE(std::abs(tree.cell(leaves[i]).level - tree.cell(leaves[j]).level), 1);
            }
        }
    }
}

/// Brute force over all pairs of leaves: true when edge-adjacent leaves differ by at most one
/// level.
bool balanced_by_pairs(const Quadtree& tree) {
    const auto leaves = tree.leaves();
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        for (std::size_t j = i + 1; j < leaves.size(); ++j) {
            if (share_edge(tree.box(leaves[i]), tree.box(leaves[j])) &&
                std::abs(tree.cell(leaves[i]).level - tree.cell(leaves[j]).level) > 1) {
                return false;
            }
        }
    }
    return true;
}

TEST(Quadtree, IsBalancedAgreesWithAllPairsOfLeaves) {
    // Graded trees, balanced and not, and every intermediate tree of their balancing.
    int balanced = 0, unbalanced = 0;
    for (unsigned seed = 1; seed <= 30; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        Quadtree tree = graded_tree(2 + static_cast<int>(seed % 5), rng, 1 + seed % 4);
        auto check = [&] {
            const bool expected = balanced_by_pairs(tree);
            EXPECT_EQ(tree.is_balanced(), expected);
            (expected ? balanced : unbalanced) += 1;
        };
        check();
        tree.balance([&](std::size_t) { check(); });
        check();
    }
    EXPECT_GT(balanced, 30);  // both answers were asked for
    EXPECT_GT(unbalanced, 30);
}

TEST(Quadtree, RejectsARootThatIsNotASquareAndDepthsOutOfRange) {
    EXPECT_THROW(Quadtree(Box{{0, 0}, {1, 2}}, 3), InvalidInput);
    EXPECT_THROW(Quadtree(Box{{0, 0}, {0, 0}}, 3), InvalidInput);
    EXPECT_THROW(Quadtree(Box::centered_square(1.0), -1), InvalidInput);
    EXPECT_THROW(Quadtree(Box::centered_square(1.0), Quadtree::max_supported_depth + 1),
                 InvalidInput);
}

}  // namespace
}  // namespace slc
