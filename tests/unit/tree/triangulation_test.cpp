// Tests of the conforming triangulation of balanced quadtrees and of point location in it.
#include "slc/tree/triangulation.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "slc/core/error.hpp"

namespace slc {
namespace {

Quadtree balanced_tree(unsigned seed, int depth, int points) {
    std::mt19937 rng(seed);
    Quadtree tree(Box::centered_square(2.0), depth);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int k = 0; k < points; ++k) {
        const Vec2 p{u(rng), u(rng)};
        for (std::uint32_t c = tree.leaf_at(p); tree.cell(c).level < depth; c = tree.leaf_at(p))
            tree.split(c);
    }
    tree.balance();
    return tree;
}

TEST(Triangulation, IsConformingWithEveryInteriorEdgeInTwoTriangles) {
    for (unsigned seed = 1; seed <= 10; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        const Quadtree tree = balanced_tree(seed, 8, 6);
        const Triangulation mesh = triangulate(tree);
        // Count each undirected edge; an edge with a hanging vertex in its middle would appear
        // once in the interior.
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (const auto& t : mesh.triangles) {
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = t[k], b = t[(k + 1) % 3];
                ++uses[{std::min(a, b), std::max(a, b)}];
            }
        }
        const Box root = tree.root_box();
        for (const auto& [edge, count] : uses) {
            const Vec2 a = mesh.vertices[edge.first], b = mesh.vertices[edge.second];
            const bool on_boundary =
                (a.x == root.lo.x && b.x == root.lo.x) || (a.x == root.hi.x && b.x == root.hi.x) ||
                (a.y == root.lo.y && b.y == root.lo.y) || (a.y == root.hi.y && b.y == root.hi.y);
            EXPECT_EQ(count, on_boundary ? 1 : 2);
        }
    }
}

TEST(Triangulation, TrianglesAreCounterclockwiseAndTileTheRoot) {
    const Quadtree tree = balanced_tree(3, 9, 4);
    const Triangulation mesh = triangulate(tree);
    double total = 0.0;
    for (const auto& t : mesh.triangles) {
        const Vec2 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
        const double area = 0.5 * cross(b - a, c - a);
        EXPECT_GT(area, 0.0);
        total += area;
    }
    EXPECT_DOUBLE_EQ(total, 16.0);
    // 4 to 8 triangles per leaf: the paper's six configurations.
    for (std::uint32_t c : tree.leaves()) {
        const auto n = mesh.cell_offsets[c + 1] - mesh.cell_offsets[c];
        EXPECT_GE(n, 4u);
        EXPECT_LE(n, 8u);
    }
}

TEST(Triangulation, VerticesAreCornersAndCentresSharedOnce) {
    const Quadtree tree = balanced_tree(5, 7, 5);
    const Triangulation mesh = triangulate(tree);
    std::map<std::pair<double, double>, int> seen;
    for (Vec2 v : mesh.vertices) ++seen[{v.x, v.y}];
    for (const auto& [p, n] : seen) EXPECT_EQ(n, 1);
    // Every leaf corner is a vertex.
    for (std::uint32_t c : tree.leaves()) {
        const Box b = tree.box(c);
        EXPECT_TRUE(seen.count({b.lo.x, b.lo.y}));
        EXPECT_TRUE(seen.count({b.hi.x, b.hi.y}));
        EXPECT_TRUE(seen.count({b.center().x, b.center().y}));
    }
}

TEST(Triangulation, RejectsAnUnbalancedTree) {
    Quadtree tree(Box::centered_square(1.0), 6);
    for (std::uint32_t c = tree.leaf_at({0.1, 0.1}); tree.cell(c).level < 6;
         c = tree.leaf_at({0.1, 0.1}))
        tree.split(c);
    EXPECT_THROW(triangulate(tree), InvalidInput);
}

TEST(Triangulation, LocateFindsATriangleContainingThePoint) {
    const Quadtree tree = balanced_tree(9, 8, 5);
    const Triangulation mesh = triangulate(tree);
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int k = 0; k < 5000; ++k) {
        const Vec2 p{u(rng), u(rng)};
        const TrianglePoint tp = locate(tree, mesh, p);
        const auto& t = mesh.triangles[tp.triangle];
        Vec2 q{};
        for (int i = 0; i < 3; ++i) {
            EXPECT_GE(tp.weights[i], 0.0);
            q += tp.weights[i] * mesh.vertices[t[i]];
        }
        // Reconstruction to rounding: weights are O(1), coordinates O(2).
        EXPECT_NEAR(q.x, p.x, 1e-14);
        EXPECT_NEAR(q.y, p.y, 1e-14);
    }
}

}  // namespace
}  // namespace slc
