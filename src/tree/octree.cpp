// Octree structure and point location.
#include "slc/tree/octree.hpp"

#include <fmt/format.h>

#include <cmath>

#include "slc/core/error.hpp"
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

std::vector<std::uint32_t> Octree::leaves() const {
    std::vector<std::uint32_t> out;
    for (std::size_t c = 0; c < cells_.size(); ++c)
        if (is_leaf(c)) out.push_back(static_cast<std::uint32_t>(c));
    return out;
}

}  // namespace slc
