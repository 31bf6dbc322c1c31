/// @file
/// DistanceTree: exact signed distance F and a nearest point of Γ anywhere, fast (paper §1.3).
///
/// A quadtree over the domain in which a cell is split (to depth L) while its edge exceeds its
/// distance to Γ, then 2:1 balanced. Every cell lists the segments that meet its concentric triple
/// (the 3×3 block of same-size cells around it). The query is ClimbingQuery's (climbing_query.hpp,
/// written once for curves and surfaces): it starts in the leaf holding x, found from a grid of
/// start cells, and climbs ancestors until the box of half-width m (the best distance so far)
/// around x lies inside the cell's triple. Far from Γ, where cells are large and their lists
/// long (more than 48 segments), a SegmentHierarchy over all segments finishes the search
/// instead. This file holds the curves' part: the segment kernel, the tree and its lists.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <utility>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/distance/climbing_query.hpp"
#include "slc/distance/segment_hierarchy.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/segment.hpp"
#include "slc/tree/orthtree.hpp"
#include "slc/tree/triangulation.hpp"

namespace slc {

/// The segments of curves as the elements of the climbing query (ClimbingQuery).
struct SegmentKernel {
    static constexpr int dim = 2;
    using Point = Vec2;
    using Element = Segment;
    using Nearest = NearestSegment;  ///< the least (distance², segment) pair so far
    using Hierarchy = SegmentHierarchy;
    using Answer = ClosestPoint;

    /// The exact closest point of segment s to x (at any coordinates: plain is for triangles).
    static SegmentPoint closest_point(const Segment& s, Vec2 x, bool /*plain*/) {
        return slc::closest_point(s, x);
    }
    /// The segment of a nearest pair (or SegmentHierarchy::no_hint when none was found).
    static std::uint32_t element_of(const NearestSegment& n) { return n.segment; }
    /// The square x ± m (as rounded) that a cell's triple must hold to end the climb.
    static Box reach(Vec2 x, double m) { return {{x.x - m, x.y - m}, {x.x + m, x.y + m}}; }
    /// The nearest point without its sign: distance |F(x)|.
    static ClosestPoint unsigned_point(const NearestSegment& best) {
        return {std::sqrt(best.distance2), best.point, best.segment, best.t};
    }
};

/// Exact signed distance F and a nearest point of an interface Γ at any point, in O(log N) per
/// query near Γ (paper §1.3; the construction is described at the top of this file). The queries
/// (closest_point, nearest_point, closest_points, signed_distances) are ClimbingQuery's; the
/// sign is right at corners (pseudo-normal at vertices). The tree refers to the curves it was
/// built on and never copies them.
class DistanceTree : public ClimbingQuery<DistanceTree, SegmentKernel> {
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
    /// True when cell c's list is short enough to scan (at most 48 segments): a query reaching
    /// a cell with a longer one finishes in the segment hierarchy.
    bool is_listed(std::size_t c) const;

private:
    friend class ClimbingQuery<DistanceTree, SegmentKernel>;
    void build_lists();
    void build_start_grid();
    /// The leaf holding x (clamped to the domain): Quadtree::leaf_at, but starting from the
    /// start grid instead of the root, which saves most of the descent.
    std::uint32_t leaf_at(Vec2 x) const;
    /// The query's view of the tree (ClimbingQuery): lists, segments, hierarchy and sign rule.
    std::span<const std::uint32_t> cell_list(std::size_t c) const { return cell_segments(c); }
    std::span<const Segment> elements() const { return segment_ends_; }
    const SegmentHierarchy& hierarchy() const { return hierarchy_; }
    /// Segments need no range checks.
    bool in_plain_range(Vec2) const { return true; }
    ClosestPoint signed_point(const NearestSegment& best, Vec2 x) const;

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

extern template class ClimbingQuery<DistanceTree, SegmentKernel>;

}  // namespace slc
