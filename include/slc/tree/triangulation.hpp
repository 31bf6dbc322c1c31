/// @file
/// Conforming triangulation of a 2:1-balanced quadtree (paper §1.3, Figure 2b–c): the corners and
/// centres of the leaves are the vertices; each leaf is a fan of triangles from its centre to its
/// boundary vertices, which are its four corners plus the midpoint of every edge shared with finer
/// neighbours. Up to symmetry these are the paper's six cell configurations.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "slc/core/vec2.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc {

/// Vertices, counterclockwise triangles, and for each cell the range of its triangles.
struct Triangulation {
    std::vector<Vec2> vertices;  ///< corners, edge midpoints and centres of the leaves
    std::vector<std::array<std::uint32_t, 3>> triangles;  ///< vertex indices, counterclockwise
    /// Triangles of cell c are [cell_offsets[c], cell_offsets[c + 1]); empty for inner cells.
    /// Within a leaf the first vertex of every triangle is the leaf's centre.
    std::vector<std::uint32_t> cell_offsets;
};

/// Triangulates a balanced quadtree: 4 to 8 triangles per leaf, every vertex shared, never a
/// vertex inside another triangle's edge. Cost O(cells · depth). Throws InvalidInput if the tree
/// is not 2:1 balanced.
Triangulation triangulate(const Quadtree& tree);

/// No vertex: what edge_vertex of fan_leaves() returns where the neighbour is not finer.
inline constexpr std::uint32_t no_vertex = 0xffffffffu;

/// The fans of triangulate(), leaf by leaf in cell order, with the vertices numbered by the
/// caller, who may know them already: vertex(c, j, gx, gy) is the number of the vertex at grid
/// point (gx, gy) (in units of half the finest cell edge, from the root box's low corner), which
/// is corner j of leaf c (0 low-left, 1 low-right, 2 high-left, 3 high-right) or its centre (j =
/// 4), and edge_vertex(c, k, gx, gy) that of the midpoint (gx, gy) of edge k of leaf c (0 bottom, 1
/// right, 2 top, 3 left), or no_vertex unless the neighbour across that edge is finer. Each leaf
/// asks for its centre, then its boundary counterclockwise from the low-left corner. Appends to
/// mesh.triangles and mesh.cell_offsets; mesh.vertices is the caller's to fill. The tree must be
/// 2:1 balanced.
template <class Vertex, class EdgeVertex>
void fan_leaves(const Quadtree& tree, Vertex vertex, EdgeVertex edge_vertex, Triangulation& mesh) {
    const int shift = tree.max_depth() + 1;
    mesh.cell_offsets.reserve(mesh.cell_offsets.size() + tree.size() + 1);
    // 4 to 8 per leaf, about 3 leaves in 4 cells
    mesh.triangles.reserve(mesh.triangles.size() + 4 * tree.size());
    mesh.cell_offsets.push_back(static_cast<std::uint32_t>(mesh.triangles.size()));
    for (std::size_t c = 0; c < tree.size(); ++c) {
        if (tree.is_leaf(c)) {
            const auto& cell = tree.cell(c);
            const std::uint64_t u = std::uint64_t{1} << (shift - cell.level);
            const std::uint64_t x0 = cell.coords[0] * u, y0 = cell.coords[1] * u, h = u / 2;
            const std::uint32_t centre = vertex(c, 4, x0 + h, y0 + h);
            std::array<std::uint32_t, 8> ring{};
            std::size_t n = 0;
            auto midpoint = [&](int k, std::uint64_t gx, std::uint64_t gy) {
                if (const std::uint32_t v = edge_vertex(c, k, gx, gy); v != no_vertex)
                    ring[n++] = v;
            };
            ring[n++] = vertex(c, 0, x0, y0);
            midpoint(0, x0 + h, y0);
            ring[n++] = vertex(c, 1, x0 + u, y0);
            midpoint(1, x0 + u, y0 + h);
            ring[n++] = vertex(c, 3, x0 + u, y0 + u);
            midpoint(2, x0 + h, y0 + u);
            ring[n++] = vertex(c, 2, x0, y0 + u);
            midpoint(3, x0, y0 + h);
            for (std::size_t k = 0; k < n; ++k)
                mesh.triangles.push_back({centre, ring[k], ring[(k + 1) % n]});
        }
        mesh.cell_offsets.push_back(static_cast<std::uint32_t>(mesh.triangles.size()));
    }
}

/// A point located in a triangulation: its triangle and barycentric weights (summing to 1).
struct TrianglePoint {
    std::uint32_t triangle = 0;       ///< index into Triangulation::triangles
    std::array<double, 3> weights{};  ///< of the triangle's three vertices, in their order
};

/// Locates p (first moved to the nearest point of the root box) in the triangle of its leaf that
/// contains it. O(depth).
TrianglePoint locate(const Quadtree& tree, const Triangulation& mesh, Vec2 p);

}  // namespace slc
