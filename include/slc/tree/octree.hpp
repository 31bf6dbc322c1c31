/// @file
/// Octree: the cubic cells of the 3D distance tree (paper §1.3 with d = 3, DESIGN §8). The same
/// structure as Quadtree, one more coordinate: cells numbered in creation order, the eight
/// children of a cell consecutive, integer coordinates per level, point location by the bits of
/// a lattice point. The tree holds only structure; owners keep per-cell data in arrays indexed by
/// cell number. 2:1 balance (face-adjacent leaves at most one level apart) on request: the
/// distance tree does not need it, tetrahedral contouring will.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/tree/balance.hpp"

namespace slc {

/// An octree over a cubic root box. Child k of a cell sits at (+x if k & 1, +y if k & 2, +z if
/// k & 4). A cell at level l has integer coordinates (ix, iy, iz) in [0, 2^l)³.
class Octree {
public:
    /// The index that names no cell: a leaf's first_child, the root's parent.
    static constexpr std::uint32_t no_cell = 0xffffffffu;
    /// Deepest level supported: three 21-bit coordinates fit a 64-bit key.
    static constexpr int max_supported_depth = 21;

    /// One cubic cell: its place in the tree and its integer coordinates at its level.
    struct Cell {
        std::uint32_t parent = no_cell;       ///< no_cell for the root
        std::uint32_t first_child = no_cell;  ///< no_cell for a leaf
        std::uint32_t ix = 0;                 ///< x index at its level, in [0, 2^level)
        std::uint32_t iy = 0;                 ///< y index at its level
        std::uint32_t iz = 0;                 ///< z index at its level
        int level = 0;                        ///< 0 for the root; edge = root edge / 2^level
    };

    /// A single root cell covering root, a cube of positive size, and cells never deeper than
    /// max_depth (0..max_resolvable_depth(root)). Throws InvalidInput otherwise.
    Octree(Box3 root, int max_depth);

    /// The deepest level whose cells doubles still resolve in root (as
    /// Quadtree::max_resolvable_depth), at most max_supported_depth; −1 when root is not a cube
    /// of acceptable size and position.
    static int max_resolvable_depth(const Box3& root);

    /// Number of cells, all levels.
    std::size_t size() const { return cells_.size(); }
    /// Cell c, 0 <= c < size().
    const Cell& cell(std::size_t c) const { return cells_[c]; }
    /// True when cell c has no children.
    bool is_leaf(std::size_t c) const { return cells_[c].first_child == no_cell; }
    /// The deepest level split() may create.
    int max_depth() const { return max_depth_; }
    /// Deepest level of any existing cell.
    int depth() const { return depth_; }
    /// The cube the root covers.
    const Box3& root_box() const { return root_; }
    /// Edge length of a cell at the given level.
    double edge(int level) const { return edges_[static_cast<std::size_t>(level)]; }
    /// The cube of cell c, from its integer coordinates.
    Box3 box(std::size_t c) const {
        const Cell& cell = cells_[c];
        const double h = edge(cell.level);
        const Vec3 lo{root_.lo.x + cell.ix * h, root_.lo.y + cell.iy * h, root_.lo.z + cell.iz * h};
        return {lo, {lo.x + h, lo.y + h, lo.z + h}};
    }
    /// The cell's concentric triple: the 3×3×3 block of same-size cells around it (§1.3).
    Box3 triple(std::size_t c) const { return box(c).inflated(edge(cells_[c].level)); }

    /// Splits leaf c into eight children, appended at the end. Precondition: c is a leaf above
    /// max_depth. Returns the index of the first child.
    std::uint32_t split(std::size_t c);

    /// Integer coordinates of a cell at the deepest existing level.
    struct LatticePoint {
        std::uint64_t ix = 0;  ///< along x
        std::uint64_t iy = 0;  ///< along y
        std::uint64_t iz = 0;  ///< along z
    };
    /// The lattice point, at the deepest existing level, of the cell holding p (moved first to
    /// the nearest point of the root box). O(1).
    LatticePoint lattice_point(Vec3 p) const {
        const double scale = static_cast<double>(std::uint64_t{1} << depth_) / root_.width();
        const double top = static_cast<double>((std::uint64_t{1} << depth_) - 1);
        auto index = [&](double x, double lo) {
            return static_cast<std::uint64_t>(std::clamp((x - lo) * scale, 0.0, top));
        };
        return {index(p.x, root_.lo.x), index(p.y, root_.lo.y), index(p.z, root_.lo.z)};
    }
    /// The leaf holding lattice point q, descending from cell `from` (which must hold q).
    std::uint32_t descend(std::uint32_t from, LatticePoint q) const;
    /// The leaf containing p. O(depth).
    std::uint32_t leaf_at(Vec3 p) const { return descend(0, lattice_point(p)); }

    /// The cell of the same level as c sharing its face in direction d (0..5: −x, +x, −y, +y,
    /// −z, +z), or the deepest existing cell containing that place; no_cell beyond the root
    /// box. O(1) on average: it climbs only as far as the nearest common ancestor.
    std::uint32_t neighbour(std::size_t c, int d) const;

    /// Splits leaves until every two leaves that share part of a face differ by at most one
    /// level. Calls on_split(c) after each split, in order. Cost O(cells) on average.
    template <class OnSplit>
    void balance(OnSplit&& on_split);
    /// The same, with no callback.
    void balance() {
        balance([](std::size_t) {});
    }

    /// True when every two face-adjacent leaves differ by at most one level. On all worker
    /// threads.
    bool is_balanced() const;

    /// All leaves, in increasing cell number.
    std::vector<std::uint32_t> leaves() const;

private:
    /// The leaf bordering cell c in direction d when it is coarser than c, that is when c's
    /// same-level neighbour there is missing; otherwise, or beyond the root box, no_cell.
    std::uint32_t coarser_neighbour(std::size_t c, int d) const;

    Box3 root_;
    int max_depth_ = 0;
    int depth_ = 0;
    std::vector<double> edges_;
    std::vector<Cell> cells_;
};

template <class OnSplit>
void Octree::balance(OnSplit&& on_split) {
    tree_balance::balance<6>(
        *this, [this](std::size_t c, int d) { return coarser_neighbour(c, d); }, on_split);
}

}  // namespace slc
