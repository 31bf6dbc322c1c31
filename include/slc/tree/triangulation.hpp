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
#include "slc/tree/quadtree.hpp"

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

/// A point located in a triangulation: its triangle and barycentric weights (summing to 1).
struct TrianglePoint {
    std::uint32_t triangle = 0;       ///< index into Triangulation::triangles
    std::array<double, 3> weights{};  ///< of the triangle's three vertices, in their order
};

/// Locates p (first moved to the nearest point of the root box) in the triangle of its leaf that
/// contains it. O(depth).
TrianglePoint locate(const Quadtree& tree, const Triangulation& mesh, Vec2 p);

}  // namespace slc
