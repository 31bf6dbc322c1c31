#include "slc/tree/tetrahedralization.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

double signed_volume(const Tetrahedralization& mesh, const std::array<std::uint32_t, 4>& t) {
    const Vec3 a = mesh.vertices[t[0]];
    return dot(mesh.vertices[t[1]] - a, cross(mesh.vertices[t[2]] - a, mesh.vertices[t[3]] - a)) /
           6.0;
}

/// Every triangle of the tetrahedra's faces, counted; conforming means each inner triangle twice
/// and each triangle on the root box's boundary once.
void expect_conforming(const Octree& tree, const Tetrahedralization& mesh) {
    std::map<std::array<std::uint32_t, 3>, int> faces;
    for (const auto& t : mesh.tetrahedra) {
        for (int skip = 0; skip < 4; ++skip) {
            std::array<std::uint32_t, 3> f{};
            for (int k = 0, j = 0; k < 4; ++k)
                if (k != skip) f[j++] = t[k];
            std::sort(f.begin(), f.end());
            ++faces[f];
        }
    }
    const Box3& root = tree.root_box();
    auto on_boundary = [&](std::uint32_t v) {
        const Vec3 p = mesh.vertices[v];
        for (int a = 0; a < 3; ++a)
            if (p[a] == root.lo[a] || p[a] == root.hi[a]) return true;
        return false;
    };
    for (const auto& [f, n] : faces) {
        if (n == 2) continue;
        ASSERT_EQ(n, 1) << "a triangle in more than two tetrahedra";
        // A boundary triangle has its three vertices on one face of the root box.
        bool same_face = false;
        for (int a = 0; a < 3; ++a) {
            for (double side : {root.lo[a], root.hi[a]}) {
                same_face |= mesh.vertices[f[0]][a] == side && mesh.vertices[f[1]][a] == side &&
                             mesh.vertices[f[2]][a] == side;
            }
        }
        ASSERT_TRUE(on_boundary(f[0]) && same_face) << "a triangle with one tetrahedron inside";
    }
}

/// A balanced octree of [−1, 1]³ to the given depth, split at random: nearly every cell of the
/// coarse half of the levels, a third of the others.
Octree random_balanced_tree(unsigned seed, int depth) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Octree tree(Box3::centered_cube(1.0), depth);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const int level = tree.cell(c).level;
        if (level < depth && u(rng) < (level < depth / 2 ? 0.95 : 0.3)) tree.split(c);
    }
    tree.balance();
    return tree;
}

TEST(Tetrahedralization, UniformTreeIs24TetrahedraPerLeafFillingTheBox) {
    Octree tree(Box3::centered_cube(1.0), 2);
    tree.split(0);
    for (std::uint32_t c = 1; c <= 8; ++c) tree.split(c);
    const Tetrahedralization mesh = tetrahedralize(tree);
    EXPECT_EQ(mesh.tetrahedra.size(), 64u * 24u);
    double volume = 0.0;
    for (const auto& t : mesh.tetrahedra) {
        const double v = signed_volume(mesh, t);
        EXPECT_GT(v, 0.0);
        volume += v;
    }
    EXPECT_NEAR(volume, 8.0, 1e-12);
    // Corners (5³), face centres (3 · 4 · 4 · 5) and leaf centres (4³), each once.
    EXPECT_EQ(mesh.vertices.size(), 125u + 240u + 64u);
    expect_conforming(tree, mesh);
}

TEST(Tetrahedralization, RandomBalancedTreesConform) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 6; ++trial) {
        Octree tree(Box3{{-1.0, -0.5, 0.0}, {1.0, 1.5, 2.0}}, 5);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (std::size_t c = 0; c < tree.size(); ++c) {
            const int level = tree.cell(c).level;
            if (level < 5 && u(rng) < (level < 2 ? 0.9 : 0.25)) tree.split(c);
        }
        tree.balance();
        const Tetrahedralization mesh = tetrahedralize(tree);
        double volume = 0.0;
        for (std::size_t c = 0; c < tree.size(); ++c) {
            const auto first = mesh.cell_offsets[c], last = mesh.cell_offsets[c + 1];
            EXPECT_EQ(last > first, tree.is_leaf(c));
            for (auto t = first; t < last; ++t) {
                const double v = signed_volume(mesh, mesh.tetrahedra[t]);
                ASSERT_GT(v, 0.0);
                volume += v;
                // The first vertex is the leaf's centre, and every vertex lies in the leaf.
                EXPECT_EQ(mesh.vertices[mesh.tetrahedra[t][0]], tree.box(c).center());
                for (std::uint32_t v4 : mesh.tetrahedra[t])
                    EXPECT_TRUE(tree.box(c).contains(mesh.vertices[v4]));
            }
        }
        // The sum of some 10^4 volumes, each rounded.
        EXPECT_NEAR(volume, 8.0, 1e-10);
        expect_conforming(tree, mesh);
    }
}

TEST(Tetrahedralization, GridCoordinatesNameTheVertices) {
    Octree tree(Box3::centered_cube(1.0), 3);
    tree.split(0);
    tree.split(1);
    tree.balance();
    const Tetrahedralization mesh = tetrahedralize(tree);
    const double step = 2.0 / 16.0;  // half the finest edge, 2 / 2^3 / 2
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        for (int a = 0; a < 3; ++a) EXPECT_EQ(mesh.vertices[v][a], -1.0 + mesh.grid[v][a] * step);
    }
}

TEST(Tetrahedralization, VerticesAreNumberedByFirstUseTheSameOnAnyThreadCount) {
    const Octree tree = random_balanced_tree(11, 6);
    set_thread_count(1);
    const Tetrahedralization one = tetrahedralize(tree);
    set_thread_count(2);
    const Tetrahedralization two = tetrahedralize(tree);
    set_thread_count(0);
    EXPECT_EQ(one.tetrahedra, two.tetrahedra);
    EXPECT_EQ(one.grid, two.grid);
    EXPECT_EQ(one.vertex_offsets, two.vertex_offsets);
    ASSERT_GT(one.tetrahedra.size(), 10000u);
    // Reading the cells' tetrahedra in order, each vertex is first met in the cell whose range
    // of vertex_offsets holds it, and the first new vertex of a leaf is its centre.
    std::vector<std::uint8_t> met(one.vertices.size(), 0);
    for (std::size_t c = 0; c < tree.size(); ++c) {
        std::vector<std::uint32_t> fresh;
        for (auto t = one.cell_offsets[c]; t < one.cell_offsets[c + 1]; ++t) {
            for (const std::uint32_t v : one.tetrahedra[t]) {
                if (met[v]) continue;
                met[v] = 1;
                fresh.push_back(v);
            }
        }
        std::sort(fresh.begin(), fresh.end());
        ASSERT_EQ(fresh.size(), one.vertex_offsets[c + 1] - one.vertex_offsets[c]);
        for (std::size_t i = 0; i < fresh.size(); ++i) {
            ASSERT_EQ(fresh[i], one.vertex_offsets[c] + i);
        }
        if (tree.is_leaf(c)) {
            EXPECT_EQ(one.vertices[one.vertex_offsets[c]], tree.box(c).center());
        }
    }
    EXPECT_EQ(std::count(met.begin(), met.end(), 0), 0);
}

TEST(Tetrahedralization, WantedLeavesGetTheWholeMeshsTetrahedraAndNoOthers) {
    const Octree tree = random_balanced_tree(13, 5);
    const Tetrahedralization whole = tetrahedralize(tree);
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::uint8_t> wanted(tree.size(), 0);
    for (auto& w : wanted) w = u(rng) < 0.3 ? 1 : 0;
    const Tetrahedralization some = tetrahedralize(tree, wanted);
    // Each tetrahedron as its four corners' grid points, in order.
    using Corners = std::array<std::array<std::uint32_t, 3>, 4>;
    auto corners = [](const Tetrahedralization& m, std::uint32_t t) {
        Corners out;
        for (int k = 0; k < 4; ++k) out[k] = m.grid[m.tetrahedra[t][k]];
        return out;
    };
    std::size_t made = 0;
    for (std::size_t c = 0; c < tree.size(); ++c) {
        const std::uint32_t first = some.cell_offsets[c], last = some.cell_offsets[c + 1];
        if (!tree.is_leaf(c) || !wanted[c]) {
            EXPECT_EQ(first, last);
            EXPECT_EQ(some.vertex_offsets[c], some.vertex_offsets[c + 1]);
            continue;
        }
        ASSERT_EQ(last - first, whole.cell_offsets[c + 1] - whole.cell_offsets[c]);
        for (std::uint32_t k = 0; k < last - first; ++k)
            ASSERT_EQ(corners(some, first + k), corners(whole, whole.cell_offsets[c] + k));
        made += last - first;
    }
    EXPECT_EQ(some.tetrahedra.size(), made);
    EXPECT_GT(made, 0u);
    EXPECT_LT(made, whole.tetrahedra.size());
    // Only the vertices the wanted leaves use, each once, where the whole mesh has them.
    std::vector<std::uint8_t> used(some.vertices.size(), 0);
    for (const auto& t : some.tetrahedra)
        for (const std::uint32_t v : t) used[v] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
    std::map<std::array<std::uint32_t, 3>, Vec3> where;
    for (std::size_t v = 0; v < whole.vertices.size(); ++v)
        where[whole.grid[v]] = whole.vertices[v];
    std::map<std::array<std::uint32_t, 3>, int> seen;
    for (std::size_t v = 0; v < some.vertices.size(); ++v) {
        EXPECT_EQ(++seen[some.grid[v]], 1);
        EXPECT_EQ(some.vertices[v], where.at(some.grid[v]));
    }
}

TEST(Tetrahedralization, FinerSidesAreWhereCornersOfFinerLeavesLie) {
    // Brute force: every leaf corner on the grid of half the finest edge, then every grid point
    // strictly inside each leaf's faces and edges looked up.
    std::size_t diagonal_only = 0, marked = 0;
    for (unsigned seed : {3u, 17u, 29u}) {
        const Octree tree = random_balanced_tree(seed, 5);
        const std::vector<std::uint32_t> sides = finer_sides(tree);
        ASSERT_EQ(sides.size(), tree.size());
        const std::uint64_t top = std::uint64_t{1} << (tree.max_depth() + 1);
        std::vector<std::uint8_t> corner((top + 1) * (top + 1) * (top + 1), 0);
        auto index = [&](std::uint64_t x, std::uint64_t y, std::uint64_t z) {
            return (x * (top + 1) + y) * (top + 1) + z;
        };
        std::vector<std::uint32_t> leaves;
        for (std::size_t c = 0; c < tree.size(); ++c) {
            if (!tree.is_leaf(c)) {
                EXPECT_EQ(sides[c], 0u);
                continue;
            }
            leaves.push_back(static_cast<std::uint32_t>(c));
            const auto& cell = tree.cell(c);
            const std::uint64_t u = top >> cell.level;
            for (int k = 0; k < 8; ++k) {
                corner[index(cell.coords[0] * u + (k & 1) * u,
                             cell.coords[1] * u + (k >> 1 & 1) * u,
                             cell.coords[2] * u + (k >> 2) * u)] = 1;
            }
        }
        for (const std::uint32_t c : leaves) {
            const auto& cell = tree.cell(c);
            const std::uint64_t u = top >> cell.level;
            std::uint32_t expected = 0;
            // Face d across axis a, strictly inside.
            for (int d = 0; d < 6; ++d) {
                const int a = d / 2, b = (a + 1) % 3, e = (a + 2) % 3;
                for (std::uint64_t i = 1; i < u; ++i) {
                    for (std::uint64_t j = 1; j < u; ++j) {
                        std::array<std::uint64_t, 3> p{cell.coords[0] * u, cell.coords[1] * u,
                                                       cell.coords[2] * u};
                        p[a] += (d & 1) * u;
                        p[b] += i;
                        p[e] += j;
                        if (corner[index(p[0], p[1], p[2])]) expected |= 1u << d;
                    }
                }
            }
            // Edge k along axis a, strictly inside.
            for (int a = 0; a < 3; ++a) {
                for (int k = 0; k < 4; ++k) {
                    for (std::uint64_t i = 1; i < u; ++i) {
                        std::array<std::uint64_t, 3> p{cell.coords[0] * u, cell.coords[1] * u,
                                                       cell.coords[2] * u};
                        p[a] += i;
                        p[(a + 1) % 3] += (k & 1) * u;
                        p[(a + 2) % 3] += (k >> 1) * u;
                        if (corner[index(p[0], p[1], p[2])]) expected |= 1u << edge_side(a, k);
                    }
                }
            }
            ASSERT_EQ(sides[c], expected) << "leaf " << c << ", seed " << seed;
            marked += expected != 0;
            // An edge touched by a cell diagonally across it alone: neither face beside it is.
            for (int a = 0; a < 3; ++a) {
                for (int k = 0; k < 4; ++k) {
                    const int faces =
                        1 << (2 * ((a + 1) % 3) + (k & 1)) | 1 << (2 * ((a + 2) % 3) + (k >> 1));
                    if ((expected >> edge_side(a, k) & 1u) && (expected & faces) == 0)
                        ++diagonal_only;
                }
            }
        }
    }
    EXPECT_GT(marked, 100u);
    EXPECT_GT(diagonal_only, 10u);
}

TEST(Tetrahedralization, TheTemplateLeafGivesWhatTheSearchOfEveryLeafGives) {
    // Sides claiming that finer cells touch every leaf send every leaf through the search of
    // its faces and edges; with the true sides, most take the template leaf. The same mesh.
    const Octree tree = random_balanced_tree(23, 5);
    const std::vector<std::uint32_t> sides = finer_sides(tree);
    std::size_t untouched = 0;
    for (std::size_t c = 0; c < tree.size(); ++c) untouched += tree.is_leaf(c) && sides[c] == 0;
    ASSERT_GT(untouched, 100u);
    const std::vector<std::uint32_t> all_touched(tree.size(), ~0u);
    const Tetrahedralization fast = tetrahedralize(tree, {}, sides);
    const Tetrahedralization searched = tetrahedralize(tree, {}, all_touched);
    EXPECT_EQ(fast.grid, searched.grid);
    EXPECT_EQ(fast.vertices, searched.vertices);
    EXPECT_EQ(fast.tetrahedra, searched.tetrahedra);
    EXPECT_EQ(fast.cell_offsets, searched.cell_offsets);
    EXPECT_EQ(fast.vertex_offsets, searched.vertex_offsets);
}

TEST(Tetrahedralization, RefusesAnUnbalancedTree) {
    Octree tree(Box3::centered_cube(1.0), 4);
    const std::uint32_t low = tree.split(0);      // cells 1..8 at level 1
    const std::uint32_t inner = tree.split(low);  // cell 1's children, level 2
    // Cell 1's child on the +x side, split: level 3 cells beside cell 2, a level 1 leaf.
    tree.split(inner + 1);
    ASSERT_FALSE(tree.is_balanced());
    EXPECT_THROW(tetrahedralize(tree), InvalidInput);
}

TEST(Tetrahedralization, KeysTellApartEveryGridPointOfTheDeepestTree) {
    // Grid coordinates run from 0 to 2^(K + 1): at the deepest K they still fit 21 bits, so the
    // far corner's key is no neighbour's (at K = 20, (0, 0, 2^21) took the key of (0, 1, 0)).
    const std::uint64_t top = std::uint64_t{1} << (max_tetrahedralized_depth + 1);
    EXPECT_NE(Tetrahedralization::key(0, 0, top), Tetrahedralization::key(0, 1, 0));
    EXPECT_NE(Tetrahedralization::key(0, top, 0), Tetrahedralization::key(1, 0, 0));
    EXPECT_THROW(tetrahedralize(Octree(Box3::centered_cube(1.0), max_tetrahedralized_depth + 1)),
                 InvalidInput);
}

}  // namespace
}  // namespace slc
