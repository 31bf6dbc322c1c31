/// @file
/// Conforming tetrahedral mesh of a 2:1-balanced octree (paper §2.1 in 3D, "tetrahedra replace
/// triangles"): the 3D counterpart of triangulate(). Each leaf is a set of cones from its centre
/// over the triangles of its six faces. A face is split into its four quarters when the
/// neighbour across it is finer; each face (or quarter) is a fan from its centre over its
/// boundary ring, which holds its four corners and every leaf corner lying on its edges. A face
/// shared by two leaves is seen the same way from both sides, so every triangle of the mesh has
/// exactly two tetrahedra (one on the root box's faces) and no vertex lies inside another
/// tetrahedron's edge or face.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "slc/core/vec3.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc {

/// Vertices, positively oriented tetrahedra, and for each cell the range of its tetrahedra.
struct Tetrahedralization {
    /// Corners, face centres and centres of the leaves.
    std::vector<Vec3> vertices;
    /// Integer coordinates of each vertex on the grid of half the finest cell edge (the root
    /// box's low corner at 0): equal for equal points, whichever cell names them.
    std::vector<std::array<std::uint32_t, 3>> grid;
    /// Vertex indices, (b − a) · ((c − a) × (d − a)) > 0. The first vertex of each is the
    /// centre of its leaf.
    std::vector<std::array<std::uint32_t, 4>> tetrahedra;
    /// Tetrahedra of cell c are [cell_offsets[c], cell_offsets[c + 1]); empty for inner cells.
    std::vector<std::uint32_t> cell_offsets;
    /// The vertices are numbered in order of first use by the tetrahedra: those that cell c's
    /// tetrahedra use first are [vertex_offsets[c], vertex_offsets[c + 1]).
    std::vector<std::uint32_t> vertex_offsets;

    /// The key of a grid point: its three coordinates in 21 bits each.
    static std::uint64_t key(std::uint64_t gx, std::uint64_t gy, std::uint64_t gz) {
        return (gx << 42) | (gy << 21) | gz;
    }
};

/// The deepest octree tetrahedralize() takes: grid coordinates (half the finest edge), which run
/// from 0 to 2^(depth + 1), fit the 21 bits of Tetrahedralization::key.
inline constexpr int max_tetrahedralized_depth = 19;
static_assert(max_tetrahedralized_depth + 1 < 21, "grid coordinates must fit 21 bits");

/// Where finer cells touch each leaf of a 2:1 balanced octree: bit d (0 .. 5, the faces as
/// Orthtree::neighbour numbers them) when the cell of the leaf's level across face d is split,
/// and bit edge_side(a, k) when a cell of its level sharing its edge along axis a (k below) is
/// split. Exactly where corners of finer leaves lie inside the leaf's faces or edges (a corner
/// inside an edge makes the edge's midpoint a corner too); 0 for inner cells. One pass over the
/// split cells, O(cells).
std::vector<std::uint32_t> finer_sides(const Octree& tree);

/// The bit of finer_sides() for a cell's edge along axis a whose other coordinates are the
/// cell's high ones along axis (a + 1) % 3 when bit 0 of k is set, and along (a + 2) % 3 when
/// bit 1 is.
constexpr int edge_side(int a, int k) { return 6 + 4 * a + k; }

/// Tetrahedralizes a balanced octree: 24 to 96 tetrahedra a leaf (24 when all six neighbours are
/// leaves of its size). Cost O(leaves · depth), on all worker threads: each leaf's cones over its
/// own list of vertices, then the vertices numbered by first use through keys sorted into
/// buckets, so the mesh is the same for any number of threads. wanted: one flag a cell, or
/// empty for every leaf; a leaf not flagged gets no tetrahedra (its ranges are empty) and its
/// vertices are numbered only where a flagged leaf uses them. The flagged leaves' tetrahedra
/// are those of the whole mesh. sides: finer_sides(tree), or empty to have them worked out. Throws
/// InvalidInput if the tree is not 2:1 balanced or deeper than max_tetrahedralized_depth.
Tetrahedralization tetrahedralize(const Octree& tree, std::span<const std::uint8_t> wanted = {},
                                  std::span<const std::uint32_t> sides = {});

}  // namespace slc
