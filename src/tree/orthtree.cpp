// The 2^dim tree's structure, point location, neighbours and the 2:1 balance check (paper §1.3,
// §2.1; DESIGN §8), instantiated here for the quadtree (dim = 2) and the octree (dim = 3).
#include "slc/tree/orthtree.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "slc/core/error.hpp"
#include "slc/core/tolerances.hpp"

namespace slc {
namespace {

/// The deepest level l <= cap with width·2^-l >= tolerance::min_relative_cell · magnitude, or −1
/// when width is outside [tolerance::min_domain_width, 2·tolerance::max_coordinate] or magnitude
/// beyond tolerance::max_coordinate (or either is NaN). width: the root's edge; magnitude: the
/// largest magnitude of a root corner coordinate. The dimension does not enter.
int resolvable_depth(double width, double magnitude, int cap) {
    if (!(width >= tolerance::min_domain_width) || !(magnitude <= tolerance::max_coordinate))
        return -1;
    // Cells halve with each level: the deepest l with w 2^-l ≥ min_relative_cell · magnitude.
    int depth = 0;
    while (depth < cap &&
           std::ldexp(width, -(depth + 1)) >= tolerance::min_relative_cell * magnitude) {
        ++depth;
    }
    return depth;
}

/// True when every extent of b equals its width: a square or a cube (NaN extents are not).
template <class Region>
bool is_cube(const Region& b, int dim) {
    for (int i = 1; i < dim; ++i)
        if (!(b.hi[i] - b.lo[i] == b.hi[0] - b.lo[0])) return false;
    return true;
}

/// The box as "[x0, x1]x[y0, y1]" (and "x[z0, z1]" in 3D), for messages.
template <class Region>
std::string describe(const Region& b, int dim) {
    std::string out;
    for (int i = 0; i < dim; ++i)
        out += fmt::format("{}[{}, {}]", i == 0 ? "" : "x", b.lo[i], b.hi[i]);
    return out;
}

}  // namespace

template <int dim>
int Orthtree<dim>::max_resolvable_depth(const Region& root) {
    if (!is_cube(root, dim)) return -1;
    return resolvable_depth(root.width(), root.largest_magnitude(), max_supported_depth);
}

template <int dim>
Orthtree<dim>::Orthtree(Region root, int max_depth) : root_(root), max_depth_(max_depth) {
    const double w = root.width();
    const char* shape = dim == 2 ? "square" : "cube";
    if (!(w > 0.0) || !std::isfinite(w) || !is_cube(root, dim)) {
        throw InvalidInput(fmt::format("tree root must be a {} of positive size, got {}", shape,
                                       describe(root, dim)));
    }
    const int deepest = max_resolvable_depth(root);
    if (deepest < 0) {
        throw InvalidInput(fmt::format(
            "tree root {} is out of range: coordinates within ±{:g}, width at least {:g}",
            describe(root, dim), tolerance::max_coordinate, tolerance::min_domain_width));
    }
    if (max_depth < 0 || max_depth > max_supported_depth) {
        throw InvalidInput(fmt::format("tree depth must be between 0 and {}, got {}",
                                       max_supported_depth, max_depth));
    }
    if (max_depth > deepest) {
        throw InvalidInput(fmt::format(
            "tree depth {} is too deep for doubles in the domain {}: its cells ({:.3g} wide) "
            "would be below 2^-42 of the coordinates (at most depth {} there)",
            max_depth, describe(root, dim), std::ldexp(w, -max_depth), deepest));
    }
    edges_.resize(static_cast<std::size_t>(max_depth) + 1);
    for (int l = 0; l <= max_depth; ++l) edges_[static_cast<std::size_t>(l)] = std::ldexp(w, -l);
    cells_.push_back(Cell{});
}

template <int dim>
std::uint32_t Orthtree<dim>::split(std::size_t c) {
    SLC_ASSERT(is_leaf(c) && cells_[c].level < max_depth_,
               "only leaves above the depth limit split");
    const auto first = static_cast<std::uint32_t>(cells_.size());
    const Cell parent = cells_[c];
    cells_[c].first_child = first;
    for (std::uint32_t k = 0; k < children; ++k) {
        Cell child{static_cast<std::uint32_t>(c), no_cell, {}, parent.level + 1};
        for (int i = 0; i < dim; ++i) child.coords[i] = 2 * parent.coords[i] + ((k >> i) & 1u);
        cells_.push_back(child);
    }
    if (parent.level + 1 > depth_) depth_ = parent.level + 1;
    return first;
}

template <int dim>
std::uint32_t Orthtree<dim>::descend(std::uint32_t from, LatticePoint q) const {
    std::uint32_t c = from;
    while (!is_leaf(c)) {
        const int shift = depth_ - cells_[c].level - 1;
        std::uint32_t k = 0;
        for (int i = 0; i < dim; ++i) k += static_cast<std::uint32_t>((q[i] >> shift) & 1u) << i;
        c = cells_[c].first_child + k;
    }
    return c;
}

template <int dim>
std::uint32_t Orthtree<dim>::find(int level, const std::array<std::int64_t, dim>& coords) const {
    const std::int64_t n = std::int64_t{1} << level;
    for (const std::int64_t x : coords)
        if (x < 0 || x >= n) return no_cell;
    std::uint32_t c = 0;
    while (!is_leaf(c) && cells_[c].level < level) {
        const int shift = level - cells_[c].level - 1;
        std::uint32_t k = 0;
        for (int i = 0; i < dim; ++i)
            k += static_cast<std::uint32_t>((coords[i] >> shift) & 1) << i;
        c = cells_[c].first_child + k;
    }
    return c;
}

template <int dim>
std::uint32_t Orthtree<dim>::neighbour(std::size_t c, int d) const {
    if (c == 0) return no_cell;
    // Face d lies across axis d / 2, on the low side when d is even. Bit a of a child's place k
    // among its siblings is set when the child is high along axis a; crossing along axis a flips
    // that bit.
    const std::uint32_t bit = 1u << (static_cast<unsigned>(d) / 2);
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

template <int dim>
std::uint32_t Orthtree<dim>::coarser_neighbour(std::size_t c, int d) const {
    const std::uint32_t n = neighbour(c, d);
    return n != no_cell && cells_[n].level < cells_[c].level ? n : no_cell;
}

template <int dim>
bool Orthtree<dim>::is_balanced() const {
    return tree_balance::is_balanced<faces>(
        *this, [this](std::size_t c, int d) { return coarser_neighbour(c, d); });
}

template <int dim>
std::vector<std::uint32_t> Orthtree<dim>::leaves() const {
    return tree_balance::leaves(*this);
}

template class Orthtree<2>;
template class Orthtree<3>;

}  // namespace slc
