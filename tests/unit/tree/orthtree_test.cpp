// Tests of the 2^dim tree, each run on the quadtree and the octree: children's boxes, depth
// limits, point location, lookup by coordinates, face neighbours, and 2:1 balance against brute
// force over all pairs of leaves.
#include "slc/tree/orthtree.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <type_traits>

#include "slc/core/error.hpp"

namespace slc {
namespace {

/// The sizes of the randomized cases in each dimension: fewer, shallower trees in 3D, where
/// brute force over pairs of leaves costs more.
template <int dim>
struct Sizes;
template <>
struct Sizes<2> {
    static constexpr unsigned balance_seeds = 20;  ///< graded trees balanced
    static constexpr int balance_depth = 7;
    static constexpr int balance_points = 4;
    static constexpr unsigned pair_seeds = 30;  ///< graded trees checked against all pairs
    static constexpr int pair_depths = 5;       ///< depths 2 .. 2 + pair_depths − 1
    static constexpr int pair_points = 4;       ///< 1 .. pair_points points
};
template <>
struct Sizes<3> {
    static constexpr unsigned balance_seeds = 8;
    static constexpr int balance_depth = 6;
    static constexpr int balance_points = 3;
    static constexpr unsigned pair_seeds = 12;
    static constexpr int pair_depths = 3;
    static constexpr int pair_points = 3;
};

/// The trees and brute-force checks of one dimension.
template <int dim>
struct Trees {
    using Tree = Orthtree<dim>;
    using Point = typename Tree::Point;
    using Region = typename Tree::Region;

    /// The square or cube of half-width b centred on c.
    static Region cube(Point c, double b) {
        if constexpr (dim == 2) {
            return Box::square(c, b);
        } else {
            return Box3::cube(c, b);
        }
    }
    /// [−b, b]^dim.
    static Region centered(double b) { return cube(Point{}, b); }
    /// A box whose last extent is twice the others: not a square or a cube.
    static Region stretched() {
        Region b = centered(1.0);
        b.hi[dim - 1] += 2.0;
        return b;
    }
    /// A point with coordinates drawn from u, in order.
    template <class Distribution>
    static Point random_point(Distribution& u, std::mt19937& rng) {
        Point p;
        for (int i = 0; i < dim; ++i) p[i] = u(rng);
        return p;
    }

    /// A deliberately unbalanced tree: cells holding any of `points` random points split to
    /// `depth`.
    static Tree graded_tree(int depth, std::mt19937& rng, int points) {
        Tree tree(centered(1.0), depth);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int k = 0; k < points; ++k) {
            const Point p = random_point(u, rng);
            for (std::uint32_t leaf = tree.leaf_at(p); tree.cell(leaf).level < depth;
                 leaf = tree.leaf_at(p))
                tree.split(leaf);
        }
        return tree;
    }

    /// True when two boxes share part of a face of positive measure (the trees' corners are
    /// dyadic, so exact).
    static bool share_face(const Region& a, const Region& b) {
        int touching = 0, overlapping = 0;
        for (int i = 0; i < dim; ++i) {
            if (a.hi[i] == b.lo[i] || b.hi[i] == a.lo[i]) ++touching;
            if (std::min(a.hi[i], b.hi[i]) > std::max(a.lo[i], b.lo[i])) ++overlapping;
        }
        return touching == 1 && overlapping == dim - 1;
    }

    /// Brute force over all pairs of leaves: true when face-adjacent leaves differ by at most
    /// one level.
    static bool balanced_by_pairs(const Tree& tree) {
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
};

template <class Dim>
class OrthtreeTest : public ::testing::Test {};
using Dimensions = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(OrthtreeTest, Dimensions);

TYPED_TEST(OrthtreeTest, ChildrenTileTheirParentInOrder) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    using Region = typename T::Region;
    constexpr int dim = TypeParam::value;
    typename T::Point centre;
    for (int i = 0; i < dim; ++i) centre[i] = i + 1.0;  // (1, 2) or (1, 2, 3)
    Tree tree(T::cube(centre, 2.0), 4);
    const std::uint32_t first = tree.split(0);
    const Region root = tree.box(0);
    for (std::uint32_t k = 0; k < Tree::children; ++k) {
        const Region b = tree.box(first + k);
        EXPECT_EQ(b.width(), 2.0);
        // Child k is high along axis i when bit i of k is set.
        for (int i = 0; i < dim; ++i) EXPECT_EQ(b.lo[i], (k >> i & 1u) ? centre[i] : centre[i] - 2);
        EXPECT_TRUE(root.contains(b));
        EXPECT_EQ(tree.cell(first + k).parent, 0u);
        EXPECT_EQ(tree.cell(first + k).level, 1);
        EXPECT_EQ(tree.triple(first + k), b.inflated(2.0));
    }
}

TYPED_TEST(OrthtreeTest, DepthIsLimitedToCellsDoublesResolve) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    using Region = typename T::Region;
    constexpr int dim = TypeParam::value;
    // Centred: only the supported depth limits. A unit square (cube) at 1e12, where doubles are
    // 1.2e-4 apart: cells must stay above 2^-42 · 1e12 ≈ 0.23, so depth 2 (0.25) is the deepest.
    EXPECT_EQ(Tree::max_resolvable_depth(T::centered(1e-50)), Tree::max_supported_depth);
    EXPECT_EQ(Tree::max_resolvable_depth(T::centered(1.0)), Tree::max_supported_depth);
    Region far;
    for (int i = 0; i < dim; ++i) {
        far.lo[i] = 1e12;
        far.hi[i] = 1e12 + 1;
    }
    EXPECT_EQ(Tree::max_resolvable_depth(far), 2);
    EXPECT_NO_THROW(Tree(far, 2));
    EXPECT_THROW(Tree(far, 3), InvalidInput);
    // Out of range: too large, too small, not a square (cube).
    EXPECT_EQ(Tree::max_resolvable_depth(T::centered(1e101)), -1);
    EXPECT_EQ(Tree::max_resolvable_depth(T::centered(1e-101)), -1);
    EXPECT_EQ(Tree::max_resolvable_depth(T::stretched()), -1);
    EXPECT_THROW(Tree(T::centered(1e101), 0), InvalidInput);
}

TYPED_TEST(OrthtreeTest, RejectsARootThatIsNotACubeAndDepthsOutOfRange) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    EXPECT_THROW(Tree(T::stretched(), 3), InvalidInput);
    EXPECT_THROW(Tree(T::centered(0.0), 3), InvalidInput);
    EXPECT_THROW(Tree(T::centered(1.0), -1), InvalidInput);
    EXPECT_THROW(Tree(T::centered(1.0), Tree::max_supported_depth + 1), InvalidInput);
}

TYPED_TEST(OrthtreeTest, LeafAtReturnsTheLeafContainingThePoint) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    using Point = typename T::Point;
    constexpr int dim = TypeParam::value;
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto expect_located = [&](const Tree& tree, std::mt19937& rng, int count) {
        for (int k = 0; k < count; ++k) {
            const Point p = T::random_point(u, rng);
            const std::uint32_t leaf = tree.leaf_at(p);
            ASSERT_TRUE(tree.is_leaf(leaf));
            ASSERT_TRUE(tree.box(leaf).contains(p));
        }
        // Outside: the leaf of the nearest point of the root box.
        Point outside, nearest;
        for (int i = 0; i < dim; ++i) {
            outside[i] = i == 0 ? 5.0 : (i == 1 ? -7.0 : 0.1);
            nearest[i] = i == 0 ? 1.0 : (i == 1 ? -1.0 : 0.1);
        }
        EXPECT_TRUE(tree.box(tree.leaf_at(outside)).contains(nearest));
    };
    // A graded tree, and one refined irregularly around a point.
    std::mt19937 rng(7);
    expect_located(T::graded_tree(8, rng, 5), rng, 2000);
    Tree tree(T::centered(1.0), 6);
    std::mt19937 irregular(5);
    for (int k = 0; k < 200; ++k) {
        const std::uint32_t leaf = tree.leaf_at(0.3 * T::random_point(u, irregular));
        if (tree.cell(leaf).level < tree.max_depth()) tree.split(leaf);
    }
    expect_located(tree, irregular, 5000);
}

TYPED_TEST(OrthtreeTest, FindReturnsCellOrDeepestAncestor) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    constexpr int dim = TypeParam::value;
    std::mt19937 rng(11);
    const Tree tree = T::graded_tree(6, rng, 3);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const auto& cell = tree.cell(c);
        std::array<std::int64_t, dim> at;
        for (int i = 0; i < dim; ++i) at[i] = cell.coords[i];
        EXPECT_EQ(tree.find(cell.level, at), c);
    }
    for (int i = 0; i < dim; ++i) {
        std::array<std::int64_t, dim> at{};
        at[i] = -1;
        EXPECT_EQ(tree.find(3, at), Tree::no_cell);
        at[i] = 8;
        EXPECT_EQ(tree.find(3, at), Tree::no_cell);
    }
}

TYPED_TEST(OrthtreeTest, NeighbourAgreesWithLookupByCoordinates) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    constexpr int dim = TypeParam::value;
    std::mt19937 rng(13);
    const Tree tree = T::graded_tree(7 - (dim - 2) * 2, rng, 6);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const auto& cell = tree.cell(c);
        for (int d = 0; d < Tree::faces; ++d) {
            std::array<std::int64_t, dim> at;
            for (int i = 0; i < dim; ++i) at[i] = cell.coords[i];
            at[d / 2] += (d & 1) ? 1 : -1;
            EXPECT_EQ(tree.neighbour(c, d), tree.find(cell.level, at));
        }
    }
}

TYPED_TEST(OrthtreeTest, NeighbourIsTheCellAcrossEachFace) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    using Region = typename T::Region;
    std::mt19937 rng(3);
    const Tree tree = T::graded_tree(5, rng, 6);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const Region b = tree.box(c);
        const double h = b.width();
        for (int d = 0; d < Tree::faces; ++d) {
            // The centre of the same-size cell across face d.
            auto across = b.center();
            across[d / 2] += (d & 1) ? h : -h;
            const std::uint32_t n = tree.neighbour(c, d);
            if (!tree.root_box().contains(across)) {
                EXPECT_EQ(n, Tree::no_cell) << "cell " << c << " direction " << d;
                continue;
            }
            // The same-level cell there, or the deepest existing cell holding it.
            ASSERT_NE(n, Tree::no_cell);
            EXPECT_TRUE(tree.box(n).contains(across)) << "cell " << c << " direction " << d;
            EXPECT_LE(tree.cell(n).level, tree.cell(c).level);
            if (tree.cell(n).level < tree.cell(c).level) {
                EXPECT_TRUE(tree.is_leaf(n));
            }
        }
    }
}

TYPED_TEST(OrthtreeTest, BalanceLeavesFaceNeighboursWithinOneLevel) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    using S = Sizes<TypeParam::value>;
    for (unsigned seed = 1; seed <= S::balance_seeds; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        Tree tree = T::graded_tree(S::balance_depth, rng, S::balance_points);
        EXPECT_FALSE(tree.is_balanced());
        EXPECT_FALSE(T::balanced_by_pairs(tree));
        std::size_t splits = 0;
        tree.balance([&](std::size_t c) {
            EXPECT_FALSE(tree.is_leaf(c));
            ++splits;
        });
        EXPECT_GT(splits, 0u);
        EXPECT_TRUE(tree.is_balanced());
        EXPECT_TRUE(T::balanced_by_pairs(tree));
    }
}

TYPED_TEST(OrthtreeTest, IsBalancedAgreesWithAllPairsOfLeaves) {
    using T = Trees<TypeParam::value>;
    using Tree = typename T::Tree;
    using S = Sizes<TypeParam::value>;
    // Graded trees, balanced and not, and every intermediate tree of their balancing.
    int balanced = 0, unbalanced = 0;
    for (unsigned seed = 1; seed <= S::pair_seeds; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        Tree tree = T::graded_tree(2 + static_cast<int>(seed % S::pair_depths), rng,
                                   1 + static_cast<int>(seed % S::pair_points));
        auto check = [&] {
            const bool expected = T::balanced_by_pairs(tree);
            EXPECT_EQ(tree.is_balanced(), expected);
            (expected ? balanced : unbalanced) += 1;
        };
        check();
        tree.balance([&](std::size_t) { check(); });
        check();
    }
    // Both answers were asked for.
    EXPECT_GT(balanced, static_cast<int>(S::pair_seeds));
    EXPECT_GT(unbalanced, static_cast<int>(S::pair_seeds));
}

}  // namespace
}  // namespace slc
