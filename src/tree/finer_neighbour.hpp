// The neighbour test that the triangulation of a quadtree and the tetrahedralization of an octree
// (paper §2.1) share, internal to the tree module: where a leaf's face meets finer cells, its
// simplices fan out to the finer vertices.
#pragma once

#include <cstddef>

#include "slc/core/error.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc {

/// True when the neighbour of leaf c across face d is finer than c (a cell of c's level with
/// children). Throws InvalidInput(unbalanced) when it is a leaf coarser than c's parent: the tree
/// is not 2:1 balanced (checked here, where every leaf's neighbours are found anyway, instead of
/// in a pass of its own). O(1).
template <int dim>
bool has_finer_neighbour(const Orthtree<dim>& tree, std::size_t c, int d, const char* unbalanced) {
    const std::uint32_t n = tree.neighbour(c, d);
    if (n == Orthtree<dim>::no_cell) return false;
    const int level = tree.cell(c).level;
    if (tree.cell(n).level < level - 1) throw InvalidInput(unbalanced);
    return tree.cell(n).level == level && !tree.is_leaf(n);
}

}  // namespace slc
