/// @file
/// Orthtree<dim>: the 2^dim tree of square (dim = 2) or cubic (dim = 3) cells under the distance
/// tree (paper §1.3, Figure 2a) and the contouring tree (§2.1), written once for both dimensions
/// (DESIGN §8) as CGAL's Orthtree is, with Quadtree and Octree its two instances. The tree holds
/// only structure; owners keep per-cell data in arrays indexed by cell number. 2:1 balance on
/// request (tree_balance). Explicitly instantiated for 2 and 3 in src/tree/orthtree.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "slc/core/space.hpp"
#include "slc/tree/balance.hpp"

namespace slc {

/// A tree over a square or cubic root box. Cells are numbered in creation order: the root is 0
/// and the 2^dim children of a cell are consecutive, child k high along axis i when bit i of k is
/// set (in 2D: (low x, low y), (high x, low y), (low x, high y), (high x, high y)). A cell at
/// level l has integer coordinates in [0, 2^l)^dim. Faces (edges in 2D) are numbered d = 0 ..
/// 2·dim − 1: −x, +x, −y, +y, −z, +z.
template <int dim>
class Orthtree {
    static_assert(dim == 2 || dim == 3, "an orthtree is a quadtree or an octree");

public:
    using Point = PointOf<dim>;    ///< Vec2 or Vec3
    using Region = RegionOf<dim>;  ///< Box or Box3: the root and the cells

    /// The index that names no cell: a leaf's first_child, the root's parent, a failed search.
    static constexpr std::uint32_t no_cell = 0xffffffffu;
    /// Deepest level supported (Space<dim>::max_tree_depth: 30 in 2D, 21 in 3D).
    static constexpr int max_supported_depth = Space<dim>::max_tree_depth;
    /// Children of a split cell: 4 or 8.
    static constexpr std::uint32_t children = 1u << dim;
    /// Faces of a cell (edges in 2D): 4 or 6.
    static constexpr int faces = 2 * dim;

    /// One cell: its place in the tree and its integer coordinates at its level.
    struct Cell {
        std::uint32_t parent = no_cell;       ///< no_cell for the root
        std::uint32_t first_child = no_cell;  ///< no_cell for a leaf
        /// Coordinates at its level along x, y (, z), each in [0, 2^level).
        std::array<std::uint32_t, dim> coords{};
        int level = 0;  ///< 0 for the root; edge = root edge / 2^level
    };

    /// Integer coordinates of a cell at the deepest existing level of the tree.
    using LatticePoint = std::array<std::uint64_t, dim>;

    /// A single root cell covering root, which must be a square (cube) of positive size, and
    /// cells never deeper than max_depth (0..max_resolvable_depth(root)). Throws InvalidInput
    /// otherwise, naming the box or the depth.
    Orthtree(Region root, int max_depth);

    /// The deepest level whose cells doubles still resolve in root (tolerance::min_relative_cell),
    /// at most max_supported_depth; −1 when root is not a square (cube) of width in
    /// [tolerance::min_domain_width, 2·tolerance::max_coordinate] with corners within
    /// ±tolerance::max_coordinate.
    static int max_resolvable_depth(const Region& root);

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
    /// The square (cube) the root covers.
    const Region& root_box() const { return root_; }
    /// Edge length of a cell at the given level.
    double edge(int level) const { return edges_[static_cast<std::size_t>(level)]; }
    /// The square (cube) of cell c, computed from its integer coordinates (corners exact on the
    /// lattice). Inline, as lattice_point: every closest-point query calls both. O(1).
    Region box(std::size_t c) const {
        const Cell& cell = cells_[c];
        const double h = edge(cell.level);
        Point lo = root_.lo, hi;
        for (int i = 0; i < dim; ++i) {
            lo[i] += cell.coords[i] * h;
            hi[i] = lo[i] + h;
        }
        return {lo, hi};
    }
    /// The cell's concentric triple: the block of 3^dim same-size cells around it (§1.3).
    Region triple(std::size_t c) const { return box(c).inflated(edge(cells_[c].level)); }

    /// Splits leaf c into 2^dim children, appended at the end. Precondition: c is a leaf above
    /// max_depth. Returns the index of the first child. Amortized O(1).
    std::uint32_t split(std::size_t c);

    /// Integer coordinates, at the deepest existing level, of the cell holding p (moved first to
    /// the nearest point of the root box); on a shared face the high side wins (to rounding). O(1).
    LatticePoint lattice_point(Point p) const {
        const double scale = static_cast<double>(std::uint64_t{1} << depth_) / root_.width();
        const double top = static_cast<double>((std::uint64_t{1} << depth_) - 1);
        LatticePoint q;
        for (int i = 0; i < dim; ++i)
            q[i] = static_cast<std::uint64_t>(std::clamp((p[i] - root_.lo[i]) * scale, 0.0, top));
        return q;
    }

    /// The leaf holding lattice point q, descending from cell `from` (which must hold q): one bit
    /// of each coordinate per level, no box arithmetic. O(levels below `from`).
    std::uint32_t descend(std::uint32_t from, LatticePoint q) const;

    /// The leaf containing p: descend(0, lattice_point(p)). O(depth).
    std::uint32_t leaf_at(Point p) const { return descend(0, lattice_point(p)); }

    /// The cell at the given level and integer coordinates, or the deepest existing cell
    /// containing it; no_cell when the coordinates lie outside [0, 2^level)^dim. O(level).
    std::uint32_t find(int level, const std::array<std::int64_t, dim>& coords) const;

    /// The cell of the same level as c sharing its face d (0 .. 2·dim − 1: −x, +x, −y, +y, −z,
    /// +z), or the deepest existing cell containing that place; no_cell beyond the root box.
    /// O(1) on average: it climbs only as far as the nearest common ancestor.
    std::uint32_t neighbour(std::size_t c, int d) const;

    /// Splits leaves until every two leaves that share part of a face differ by at most one
    /// level. Calls on_split(c) after each split, in order. Cost O(cells) on average.
    template <class OnSplit>
    void balance(OnSplit&& on_split) {
        tree_balance::balance<faces>(
            *this, [this](std::size_t c, int d) { return coarser_neighbour(c, d); }, on_split);
    }
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
    /// The leaf bordering cell c across face d when it is coarser than c, that is when c's
    /// same-level neighbour there is missing; otherwise, or beyond the root box, no_cell.
    std::uint32_t coarser_neighbour(std::size_t c, int d) const;

    Region root_;
    int max_depth_ = 0;
    int depth_ = 0;
    std::vector<double> edges_;
    std::vector<Cell> cells_;
};

extern template class Orthtree<2>;
extern template class Orthtree<3>;

/// The quadtree: square cells in the plane.
using Quadtree = Orthtree<2>;
/// The octree: cubic cells in space.
using Octree = Orthtree<3>;

}  // namespace slc
