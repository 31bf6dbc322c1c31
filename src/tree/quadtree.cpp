// Quadtree structure, point location and the 2:1 balance check.
#include "slc/tree/quadtree.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/tree/cell_depth.hpp"

namespace slc {

int Quadtree::max_resolvable_depth(const Box& root) {
    if (root.height() != root.width()) return -1;
    return resolvable_depth(root.width(), root.largest_magnitude(), max_supported_depth);
}

Quadtree::Quadtree(Box root, int max_depth) : root_(root), max_depth_(max_depth) {
    const double w = root.width();
    if (!(w > 0.0) || !std::isfinite(w) || root.height() != w) {
        throw InvalidInput(
            fmt::format("tree root must be a square of positive size, got [{}, {}]x[{}, {}]",
                        root.lo.x, root.hi.x, root.lo.y, root.hi.y));
    }
    const int deepest = max_resolvable_depth(root);
    if (deepest < 0) {
        throw InvalidInput(fmt::format(
            "tree root [{}, {}]x[{}, {}] is out of range: coordinates within ±{:g}, width at least "
            "{:g}",
            root.lo.x, root.hi.x, root.lo.y, root.hi.y, tolerance::max_coordinate,
            tolerance::min_domain_width));
    }
    if (max_depth < 0 || max_depth > max_supported_depth) {
        throw InvalidInput(fmt::format("tree depth must be between 0 and {}, got {}",
                                       max_supported_depth, max_depth));
    }
    if (max_depth > deepest) {
        throw InvalidInput(fmt::format(
            "tree depth {} is too deep for doubles in the domain [{}, {}]x[{}, {}]: its cells "
            "({:.3g} wide) would be below 2^-42 of the coordinates (at most depth {} there)",
            max_depth, root.lo.x, root.hi.x, root.lo.y, root.hi.y, std::ldexp(w, -max_depth),
            deepest));
    }
    edges_.resize(static_cast<std::size_t>(max_depth) + 1);
    for (int l = 0; l <= max_depth; ++l) edges_[static_cast<std::size_t>(l)] = std::ldexp(w, -l);
    cells_.push_back(Cell{});
}

std::uint32_t Quadtree::split(std::size_t c) {
    SLC_ASSERT(is_leaf(c) && cells_[c].level < max_depth_,
               "only leaves above the depth limit split");
    const auto first = static_cast<std::uint32_t>(cells_.size());
    const Cell parent = cells_[c];
    cells_[c].first_child = first;
    for (std::uint32_t k = 0; k < 4; ++k) {
        cells_.push_back(Cell{static_cast<std::uint32_t>(c), no_cell, 2 * parent.ix + (k & 1u),
                              2 * parent.iy + (k >> 1), parent.level + 1});
    }
    if (parent.level + 1 > depth_) depth_ = parent.level + 1;
    return first;
}

std::uint32_t Quadtree::descend(std::uint32_t from, LatticePoint q) const {
    std::uint32_t c = from;
    while (!is_leaf(c)) {
        const int shift = depth_ - cells_[c].level - 1;
        c = cells_[c].first_child + static_cast<std::uint32_t>((q.ix >> shift) & 1u) +
            2u * static_cast<std::uint32_t>((q.iy >> shift) & 1u);
    }
    return c;
}

std::uint32_t Quadtree::find(int level, std::int64_t ix, std::int64_t iy) const {
    const std::int64_t n = std::int64_t{1} << level;
    if (ix < 0 || iy < 0 || ix >= n || iy >= n) return no_cell;
    std::uint32_t c = 0;
    while (!is_leaf(c) && cells_[c].level < level) {
        const int shift = level - cells_[c].level - 1;
        const auto bx = static_cast<std::uint32_t>((ix >> shift) & 1);
        const auto by = static_cast<std::uint32_t>((iy >> shift) & 1);
        c = cells_[c].first_child + bx + 2 * by;
    }
    return c;
}

std::uint32_t Quadtree::neighbour(std::size_t c, int dx, int dy) const {
    if (c == 0) return no_cell;
    const std::uint32_t parent = cells_[c].parent;
    const std::uint32_t k = static_cast<std::uint32_t>(c) - cells_[parent].first_child;
    const std::uint32_t bx = k & 1u, by = k >> 1;
    // Moving within the parent: the neighbour is a sibling.
    const bool inside_x = dx == 0 || (dx > 0 ? bx == 0 : bx == 1);
    const bool inside_y = dy == 0 || (dy > 0 ? by == 0 : by == 1);
    if (inside_x && inside_y)
        return cells_[parent].first_child + (bx ^ (dx != 0)) + 2 * (by ^ (dy != 0));
    // Otherwise the parent's neighbour, then its child on our side, if it has children.
    const std::uint32_t across = neighbour(parent, dx, dy);
    if (across == no_cell || is_leaf(across)) return across;
    return cells_[across].first_child + (bx ^ (dx != 0)) + 2 * (by ^ (dy != 0));
}

std::uint32_t Quadtree::coarser_neighbour(std::size_t c, int d) const {
    constexpr int dx[4] = {-1, 1, 0, 0};
    constexpr int dy[4] = {0, 0, -1, 1};
    const std::uint32_t n = neighbour(c, dx[d], dy[d]);
    return n != no_cell && cells_[n].level < cells_[c].level ? n : no_cell;
}

bool Quadtree::is_balanced() const {
    return tree_balance::is_balanced<4>(
        *this, [this](std::size_t c, int d) { return coarser_neighbour(c, d); });
}

std::vector<std::uint32_t> Quadtree::leaves() const { return tree_balance::leaves(*this); }

}  // namespace slc
