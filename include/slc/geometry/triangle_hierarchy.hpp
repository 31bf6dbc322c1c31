/// @file
/// TriangleHierarchy: a bounding-volume hierarchy over triangles of space, for the pairs of
/// triangles whose boxes meet (the self-intersection check of surface validation, O(N log N) for
/// a surface of similar triangles) and for the exact nearest triangle to points far from the
/// surface, where the distance tree's cells are large and their lists long. The 3D counterpart of
/// SegmentHierarchy; triangles in space have no natural order, so it is built on the Morton
/// order of their boxes' centres.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/geometry/triangle3.hpp"

namespace slc {

/// Boxes over triangles nested in a binary tree: the triangles sorted in the Morton order of
/// their boxes' centres, each node a range of that order, cut where its highest differing
/// Morton bit turns on (or in half when that cut would leave one side under a third). The
/// triangles themselves stay with the caller.
class TriangleHierarchy {
public:
    /// Triangles per leaf box, at most.
    static constexpr std::uint32_t leaf_size = 4;

    /// What bounds the nodes: boxes, for the pairs of triangles that meet; boxes and slabs, for
    /// nearest(), which then prunes deep inside closed surfaces too (the build passes over the
    /// triangles of every node of up to 4096 of them once more).
    enum class Bounds { boxes, boxes_and_slabs };

    TriangleHierarchy() = default;
    /// Builds the boxes (and slabs) over triangles (which the queries must be given again,
    /// unchanged). O(N log N).
    explicit TriangleHierarchy(std::span<const Triangle3> triangles, Bounds bounds = Bounds::boxes);

    /// The bounding box of each triangle, by index.
    std::span<const Box3> boxes() const { return boxes_; }
    /// The bounding box of triangle t.
    const Box3& box(std::uint32_t t) const { return boxes_[t]; }

    /// Calls f(t) for every triangle t whose bounding box meets the closed box b, in no fixed
    /// order. O(log N + answers) for well-shaped surfaces.
    template <class F>
    void for_each_overlapping(const Box3& b, F&& f) const {
        if (nodes_.empty()) return;
        std::uint32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& n = nodes_[stack[--top]];
            if (!n.box.overlaps(b)) continue;
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
                    if (boxes_[order_[i]].overlaps(b)) f(order_[i]);
            } else {
                stack[top++] = n.first;
                stack[top++] = n.first + 1;
            }
        }
    }

    /// Calls f(t) for triangles t whose bounding box passes enter(box), in a fixed order (depth
    /// first), until f returns true; returns whether it did. enter must pass a box whenever it
    /// passes a box inside it, so that nodes it fails are skipped whole. O(log N + triangles
    /// visited).
    template <class Enter, class F>
    bool any_of(Enter&& enter, F&& f) const {
        if (nodes_.empty()) return false;
        std::uint32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& n = nodes_[stack[--top]];
            if (!enter(n.box)) continue;
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
                    if (enter(boxes_[order_[i]]) && f(order_[i])) return true;
            } else {
                stack[top++] = n.first;
                stack[top++] = n.first + 1;
            }
        }
        return false;
    }
    /// any_of for the triangles whose bounding box meets the closed box b.
    template <class F>
    bool any_overlapping(const Box3& b, F&& f) const {
        return any_of([&](const Box3& box) { return box.overlaps(b); }, f);
    }

    /// Lowers best to the least (distance2, triangle) over all triangles: exact, the same answer
    /// as a scan of every triangle. A best already found only prunes more; so do slabs
    /// (Bounds::boxes_and_slabs), by a factor of 10 to 15 for points deep inside a sphere
    /// (docs/tables/table1_3d.md). hint: a triangle to try first (an index out of range: none);
    /// one near x prunes the search from its start, and the answer does not depend on it.
    void nearest(std::span<const Triangle3> triangles, Vec3 x, NearestFacet& best,
                 std::uint32_t hint = no_hint) const;
    /// The hint of nearest() that tries nothing first.
    static constexpr std::uint32_t no_hint = std::numeric_limits<std::uint32_t>::max();
    /// True when every triangle is in_plain_range: a query point within it too may take
    /// closest_point_in_range.
    bool plain() const { return plain_; }

private:
    /// A leaf (count > 0) holds order_[first, first + count); an inner node has children
    /// nodes_[first] and nodes_[first + 1]. Its triangles lie in the box and in the slab
    /// lo ≤ axis · p ≤ hi across their mean normal (a unit axis; lo and hi widened by rounding):
    /// for a point deep inside a closed surface, the box of a patch reaches towards it, where
    /// the slab of a patch curved little does not.
    struct Node {
        Box3 box;
        Vec3 axis{};
        double lo = 0.0, hi = 0.0;
        std::uint32_t first = 0;
        std::uint32_t count = 0;
    };
    std::vector<Node> nodes_;
    bool slabs_ = false;                ///< whether the nodes' slabs are set
    std::vector<std::uint32_t> order_;  ///< triangle indices, grouped by leaf
    std::vector<Box3> boxes_;           ///< each triangle's bounding box
    bool plain_ = true;  ///< every triangle in_plain_range: queries may skip the range checks
};

}  // namespace slc
