/// @file
/// Quadtree: the square cells of the distance tree (paper §1.3, Figure 2a) and of the contouring
/// tree (§2.1), with 2:1 balancing. The tree holds only structure; owners keep per-cell data in
/// arrays indexed by cell number.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/tree/balance.hpp"

namespace slc {

/// A quadtree over a square root box. Cells are numbered in creation order: the root is 0 and
/// the four children of a cell are consecutive, (low x, low y), (high x, low y), (low x, high y),
/// (high x, high y). A cell at level l has integer coordinates (ix, iy) in [0, 2^l)².
class Quadtree {
public:
    /// The index that names no cell: a leaf's first_child, the root's parent, a failed search.
    static constexpr std::uint32_t no_cell = 0xffffffffu;
    /// Deepest level supported: integer vertex keys of the triangulation need 2·(level + 1) bits.
    static constexpr int max_supported_depth = 30;

    /// One square cell: its place in the tree and its integer coordinates at its level.
    struct Cell {
        std::uint32_t parent = no_cell;       ///< no_cell for the root
        std::uint32_t first_child = no_cell;  ///< no_cell for a leaf
        std::uint32_t ix = 0;                 ///< column at its level, in [0, 2^level)
        std::uint32_t iy = 0;                 ///< row at its level, in [0, 2^level)
        int level = 0;                        ///< 0 for the root; edge = root edge / 2^level
    };

    /// A single root cell covering root, which must be a square of positive size, and cells
    /// never deeper than max_depth (0..max_resolvable_depth(root)). Throws InvalidInput otherwise.
    Quadtree(Box root, int max_depth);

    /// The deepest level whose cells doubles still resolve in root (tolerance::min_relative_cell),
    /// at most max_supported_depth; −1 when root is not a square of width in
    /// [tolerance::min_domain_width, 2·tolerance::max_coordinate] with corners within
    /// ±tolerance::max_coordinate.
    static int max_resolvable_depth(const Box& root);

    /// Number of cells, all levels.
    std::size_t size() const { return cells_.size(); }
    /// Cell c, 0 <= c < size().
    const Cell& cell(std::size_t c) const { return cells_[c]; }
    /// True when cell c has no children.
    bool is_leaf(std::size_t c) const { return cells_[c].first_child == no_cell; }
    /// The deepest level split() may create, as given to the constructor.
    int max_depth() const { return max_depth_; }
    /// Deepest level of any existing cell.
    int depth() const { return depth_; }
    /// The square the root covers.
    const Box& root_box() const { return root_; }
    /// Edge length of a cell at the given level.
    double edge(int level) const { return edges_[static_cast<std::size_t>(level)]; }
    /// The square of cell c, computed from its integer coordinates (corners exact on the lattice).
    /// Inline, as lattice_point: every closest-point query calls both.
    Box box(std::size_t c) const {
        const Cell& cell = cells_[c];
        const double h = edge(cell.level);
        const Vec2 lo{root_.lo.x + cell.ix * h, root_.lo.y + cell.iy * h};
        return {lo, {lo.x + h, lo.y + h}};
    }
    /// The cell's concentric triple: the 3×3 block of same-size cells around it (§1.3).
    Box triple(std::size_t c) const { return box(c).inflated(edge(cells_[c].level)); }

    /// Splits leaf c into four children, appended at the end. Precondition: c is a leaf above
    /// max_depth. Returns the index of the first child.
    std::uint32_t split(std::size_t c);

    /// Integer coordinates of a cell at the deepest existing level of the tree.
    struct LatticePoint {
        std::uint64_t ix = 0;  ///< column at the deepest existing level
        std::uint64_t iy = 0;  ///< row at the deepest existing level
    };
    /// Integer coordinates, at the deepest existing level, of the cell holding p (moved first to
    /// the nearest point of the root box); on a shared edge the high side wins (to rounding). O(1).
    LatticePoint lattice_point(Vec2 p) const {
        const double scale = static_cast<double>(std::uint64_t{1} << depth_) / root_.width();
        const double top = static_cast<double>((std::uint64_t{1} << depth_) - 1);
        return {static_cast<std::uint64_t>(std::clamp((p.x - root_.lo.x) * scale, 0.0, top)),
                static_cast<std::uint64_t>(std::clamp((p.y - root_.lo.y) * scale, 0.0, top))};
    }

    /// The leaf holding lattice point q, descending from cell `from` (which must hold q): one bit
    /// of each coordinate per level, no box arithmetic. O(levels below `from`).
    std::uint32_t descend(std::uint32_t from, LatticePoint q) const;

    /// The leaf containing p: descend(0, lattice_point(p)). O(depth).
    std::uint32_t leaf_at(Vec2 p) const { return descend(0, lattice_point(p)); }

    /// The cell at (level, ix, iy), or the deepest existing cell containing it; no_cell when
    /// (ix, iy) lies outside [0, 2^level)². O(level).
    std::uint32_t find(int level, std::int64_t ix, std::int64_t iy) const;

    /// The cell of the same level as c sharing its edge in direction (dx, dy) ∈ {(±1, 0), (0, ±1)},
    /// or the deepest existing cell containing that place; no_cell beyond the root box.
    /// O(1) on average: it climbs only as far as the nearest common ancestor.
    std::uint32_t neighbour(std::size_t c, int dx, int dy) const;

    /// Splits leaves until every two leaves that share part of an edge differ by at most one
    /// level. Calls on_split(c) after each split, in order. Cost O(cells) on average.
    template <class OnSplit>
    void balance(OnSplit&& on_split);
    /// The same, with no callback.
    void balance() {
        balance([](std::size_t) {});
    }

    /// True when every two edge-adjacent leaves differ by at most one level. On all worker
    /// threads.
    bool is_balanced() const;

    /// All leaves, in increasing cell number.
    std::vector<std::uint32_t> leaves() const;

private:
    /// The leaf bordering cell c in direction d (0..3: −x, +x, −y, +y) when it is coarser than
    /// c, that is when c's same-level neighbour there is missing; otherwise, or beyond the root
    /// box, no_cell.
    std::uint32_t coarser_neighbour(std::size_t c, int d) const;

    Box root_;
    int max_depth_ = 0;
    int depth_ = 0;
    std::vector<double> edges_;
    std::vector<Cell> cells_;
};

template <class OnSplit>
void Quadtree::balance(OnSplit&& on_split) {
    tree_balance::balance<4>(
        *this, [this](std::size_t c, int d) { return coarser_neighbour(c, d); }, on_split);
}

}  // namespace slc
