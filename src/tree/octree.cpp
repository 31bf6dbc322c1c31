// Octree structure and point location.
#include "slc/tree/octree.hpp"

#include <fmt/format.h>

#include <cmath>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/tree/cell_depth.hpp"

namespace slc {

int Octree::max_resolvable_depth(const Box3& root) {
    if (!root.is_cube()) return -1;
    return resolvable_depth(root.width(), root.largest_magnitude(), max_supported_depth);
}

Octree::Octree(Box3 root, int max_depth) : root_(root), max_depth_(max_depth) {
    const double w = root.width();
    if (!(w > 0.0) || !std::isfinite(w) || !root.is_cube()) {
        throw InvalidInput(
            fmt::format("tree root must be a cube of positive size, got [{}, {}]x[{}, {}]x[{}, {}]",
                        root.lo.x, root.hi.x, root.lo.y, root.hi.y, root.lo.z, root.hi.z));
    }
    const int deepest = max_resolvable_depth(root);
    if (deepest < 0) {
        throw InvalidInput(fmt::format(
            "tree root of width {} at {} is out of range: coordinates within ±{:g}, width at "
            "least {:g}",
            w, root.largest_magnitude(), tolerance::max_coordinate, tolerance::min_domain_width));
    }
    if (max_depth < 0 || max_depth > deepest) {
        throw InvalidInput(
            fmt::format("tree depth must be between 0 and {} here, got {}", deepest, max_depth));
    }
    edges_.resize(static_cast<std::size_t>(max_depth) + 1);
    for (int l = 0; l <= max_depth; ++l) edges_[static_cast<std::size_t>(l)] = std::ldexp(w, -l);
    cells_.push_back(Cell{});
}

std::uint32_t Octree::split(std::size_t c) {
    SLC_ASSERT(is_leaf(c) && cells_[c].level < max_depth_,
               "only leaves above the depth limit split");
    const auto first = static_cast<std::uint32_t>(cells_.size());
    const Cell parent = cells_[c];
    cells_[c].first_child = first;
    for (std::uint32_t k = 0; k < 8; ++k) {
        cells_.push_back(Cell{static_cast<std::uint32_t>(c), no_cell, 2 * parent.ix + (k & 1u),
                              2 * parent.iy + ((k >> 1) & 1u), 2 * parent.iz + (k >> 2),
                              parent.level + 1});
    }
    if (parent.level + 1 > depth_) depth_ = parent.level + 1;
    return first;
}

std::uint32_t Octree::descend(std::uint32_t from, LatticePoint q) const {
    std::uint32_t c = from;
    while (!is_leaf(c)) {
        const int shift = depth_ - cells_[c].level - 1;
        c = cells_[c].first_child + static_cast<std::uint32_t>((q.ix >> shift) & 1u) +
            2u * static_cast<std::uint32_t>((q.iy >> shift) & 1u) +
            4u * static_cast<std::uint32_t>((q.iz >> shift) & 1u);
    }
    return c;
}

std::uint32_t Octree::neighbour(std::size_t c, int d) const {
    if (c == 0) return no_cell;
    // Direction d moves along axis d / 2, down when d is even. Child bit a of k is set when the
    // child is high along axis a; moving along axis a flips that bit.
    const unsigned axis = static_cast<unsigned>(d) / 2, bit = 1u << axis;
    const bool up = (d & 1) != 0;
    const std::uint32_t parent = cells_[c].parent;
    const std::uint32_t k = static_cast<std::uint32_t>(c) - cells_[parent].first_child;
    // Moving within the parent: the neighbour is a sibling.
    if (((k & bit) != 0) != up) return cells_[parent].first_child + (k ^ bit);
    // Otherwise the parent's neighbour, then its child on our side, if it has children.
    const std::uint32_t across = neighbour(parent, d);
    if (across == no_cell || is_leaf(across)) return across;
    return cells_[across].first_child + (k ^ bit);
}

std::uint32_t Octree::coarser_neighbour(std::size_t c, int d) const {
    const std::uint32_t n = neighbour(c, d);
    return n != no_cell && cells_[n].level < cells_[c].level ? n : no_cell;
}

bool Octree::is_balanced() const {
    return tree_balance::is_balanced<6>(
        *this, [this](std::size_t c, int d) { return coarser_neighbour(c, d); });
}

std::vector<std::uint32_t> Octree::leaves() const { return tree_balance::leaves(*this); }

}  // namespace slc
