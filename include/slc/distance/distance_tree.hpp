/// @file
/// DistanceTree: exact signed distance F and a nearest point of Γ anywhere, fast (paper §1.3).
///
/// A quadtree over the domain in which a cell is split (to depth L) while its edge exceeds its
/// distance to Γ, then 2:1 balanced. Every cell lists the segments that meet its concentric triple
/// (the 3×3 block of same-size cells around it). A query starts in the leaf holding x and climbs
/// ancestors, keeping the nearest segment of their lists, until the box of half-width m (the best
/// distance so far) around x lies inside the cell's triple: every segment nearer than m meets that
/// box and so is on the list, which makes the answer exact. Far from Γ, where cells are large
/// and their lists long, a SegmentHierarchy over all segments finishes the search instead.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <utility>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/distance/segment_hierarchy.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/segment.hpp"
#include "slc/tree/orthtree.hpp"
#include "slc/tree/triangulation.hpp"

namespace slc {

/// Exact signed distance F and a nearest point of an interface Γ at any point, in O(log N) per
/// query near Γ (paper §1.3; the construction is described at the top of this file). The tree
/// refers to the curves it was built on and never copies them.
class DistanceTree {
public:
    /// The tree's parameters (paper Table 4: L).
    struct Options {
        int depth = 8;            ///< L: deepest level of the tree
        bool triangulate = true;  ///< build the triangulation and its vertices' nearest points
    };

    /// Builds the tree for curves inside domain (a square). The tree refers to curves, which must
    /// outlive it and stay unchanged. Throws InvalidInput for an empty interface, a domain that is
    /// not a square, or a depth outside 0..Quadtree::max_supported_depth.
    /// Cost O(N log N) time and memory for N segments of similar size.
    DistanceTree(const Interface& curves, Box domain, Options options);

    /// A depth for curves in domain when none is given: the level whose cells are about as
    /// large as the mean segment, between 2 and 16 (and within what doubles resolve there).
    /// Only the cost of a query depends on it. Precondition: curves is not empty.
    static int default_depth(const Interface& curves, const Box& domain);

    /// Signed closest point of Γ to x (any x, also outside the domain): distance exact to
    /// rounding; sign right at corners (pseudo-normal at vertices); 0 on Γ. O(log N) near Γ.
    ClosestPoint closest_point(Vec2 x) const;
    /// closest_point(x) without the sign: the same nearest point, segment and t, with distance
    /// |F(x)|. For callers that need only where the nearest point lies (the nearest-point
    /// extension): it skips the side test, which at a vertex takes two normals. O(log N) near Γ.
    ClosestPoint nearest_point(Vec2 x) const;

    /// closest_point for a batch, on all worker threads; out.size() == xs.size(). The answer for
    /// each point does not depend on the thread count.
    void closest_points(std::span<const Vec2> xs, std::span<ClosestPoint> out) const;
    /// The same, returning a new vector.
    std::vector<ClosestPoint> closest_points(std::span<const Vec2> xs) const;
    /// Signed distances F for a batch, on all worker threads.
    std::vector<double> signed_distances(std::span<const Vec2> xs) const;

    /// The curves the tree was built on.
    const Interface& curves() const { return *curves_; }
    /// The balanced quadtree: cells split to depth L near Γ.
    const Quadtree& tree() const { return tree_; }
    /// The triangulation of the balanced tree (empty unless Options::triangulate).
    const Triangulation& triangulation() const { return mesh_; }
    /// Signed closest point of every triangulation vertex: the vertices' pointers to their
    /// nearest segments, which make the nearest-point extension O(1) there.
    std::span<const ClosestPoint> vertex_closest_points() const { return vertex_nearest_; }
    /// Segments listed by cell c: those meeting its concentric triple, in increasing order.
    std::span<const std::uint32_t> cell_segments(std::size_t c) const {
        return {segments_.data() + offsets_[c], segments_.data() + offsets_[c + 1]};
    }

private:
    void build_lists();
    void build_start_grid();
    /// The leaf holding x (clamped to the domain): Quadtree::leaf_at, but starting from the
    /// start grid instead of the root, which saves most of the descent.
    std::uint32_t leaf_at(Vec2 x) const;
    /// The least (distance², segment) pair over Γ at x: the query both closest_point and
    /// nearest_point answer.
    NearestSegment nearest_segment(Vec2 x) const;

    const Interface* curves_;
    std::vector<Segment> segment_ends_;  ///< the segments' endpoints, contiguous for the queries
    /// Answers the queries whose cell lists are long: points far from Γ, in large cells.
    SegmentHierarchy hierarchy_;
    Quadtree tree_;
    std::vector<std::uint32_t>
        offsets_;  ///< CSR: segments of cell c are [offsets_[c], offsets_[c+1])
    /// The cells' lists, one after another. Grown level by level, at least twofold as
    /// std::vector grows, but by realloc and without initializing the new entries: a block large
    /// enough to be mapped on its own has its pages moved, not copied, and the threads that pack
    /// the lists touch their pages first.
    class Lists {
    public:
        Lists() = default;
        Lists(const Lists& o) : Lists() { *this = o; }
        Lists(Lists&& o) noexcept
            : data_(std::exchange(o.data_, nullptr)),
              size_(std::exchange(o.size_, 0)),
              capacity_(std::exchange(o.capacity_, 0)) {}
        Lists& operator=(const Lists& o) {
            if (this != &o) {
                resize(o.size_);
                std::copy_n(o.data_, o.size_, data_);
            }
            return *this;
        }
        Lists& operator=(Lists&& o) noexcept {
            std::swap(data_, o.data_);
            std::swap(size_, o.size_);
            std::swap(capacity_, o.capacity_);
            return *this;
        }
        ~Lists() { std::free(data_); }
        /// New entries are uninitialized; throws std::bad_alloc when memory runs out.
        void resize(std::size_t n);
        std::size_t size() const { return size_; }
        std::uint32_t* data() { return data_; }
        const std::uint32_t* data() const { return data_; }

    private:
        std::uint32_t* data_ = nullptr;
        std::size_t size_ = 0, capacity_ = 0;
    };
    Lists segments_;
    /// The deepest cell at or above level start_level_ holding each block of a uniform grid of
    /// 2^start_level_ blocks per side (row-major from the low corner).
    int start_level_ = 0;
    std::vector<std::uint32_t> start_grid_;
    /// Each cell's first child (Quadtree::no_cell for a leaf), compact for the descent.
    std::vector<std::uint32_t> first_child_;
    Triangulation mesh_;
    std::vector<ClosestPoint> vertex_nearest_;
};

}  // namespace slc
