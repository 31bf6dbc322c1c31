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
#include <utility>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/core/parallel.hpp"
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

    /// Calls f(t, u) once for each pair of distinct triangles t, u whose bounding boxes meet, in
    /// no fixed order, on the threads of parallel_for: f must be safe to call concurrently. One
    /// descent of the hierarchy against itself (node pairs whose boxes meet), where a query for
    /// each triangle would descend N times and find every pair twice. O(N + pairs) for
    /// well-shaped surfaces.
    template <class F>
    void for_each_overlapping_pair(F&& f) const {
        if (nodes_.empty()) return;
        const std::vector<NodePair> tasks = pair_tasks();
        parallel_for(
            tasks.size(), [&](std::size_t i) { pairs_below(tasks[i], f); }, 1);
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
    /// (docs/tables/table1_3d.md), and a node's box and slab taken together for points a few
    /// cells off a tilted or curved patch, whose box reaches towards them (about half the time
    /// of such queries). hint: a triangle to try first (an index out of range: none);
    /// one near x prunes the search from its start, and the answer does not depend on it.
    void nearest(std::span<const Triangle3> triangles, Vec3 x, NearestFacet& best,
                 std::uint32_t hint = no_hint) const;
    /// The hint of nearest() that tries nothing first.
    static constexpr std::uint32_t no_hint = std::numeric_limits<std::uint32_t>::max();
    /// True when every triangle is in_plain_range: a query point within it too may take
    /// closest_point_in_range.
    bool plain() const { return plain_; }

private:
    /// Two nodes (the same node twice: the pairs within it).
    using NodePair = std::pair<std::uint32_t, std::uint32_t>;
    /// The node pairs below the root whose boxes meet, split until there are enough to share
    /// among the threads (each a task of for_each_overlapping_pair).
    std::vector<NodePair> pair_tasks() const;
    /// Whether a pair is split no further: two leaves.
    bool is_leaf_pair(NodePair p) const {
        return nodes_[p.first].count > 0 && nodes_[p.second].count > 0;
    }
    /// Appends the pairs of p's children whose boxes meet: a node with itself gives its two
    /// children each with itself and with each other; two nodes split the one with the larger
    /// box (the inner one, when the other is a leaf).
    void split_pair(NodePair p, std::vector<NodePair>& out) const {
        const auto [a, b] = p;
        const Node& na = nodes_[a];
        const Node& nb = nodes_[b];
        auto add = [&](std::uint32_t x, std::uint32_t y) {
            if (x == y || nodes_[x].box.overlaps(nodes_[y].box)) out.emplace_back(x, y);
        };
        if (a == b) {
            add(na.first, na.first);
            add(na.first + 1, na.first + 1);
            add(na.first, na.first + 1);
            return;
        }
        const bool split_a = nb.count > 0 || (na.count == 0 && norm2(na.box.hi - na.box.lo) >=
                                                                   norm2(nb.box.hi - nb.box.lo));
        if (split_a) {
            add(na.first, b);
            add(na.first + 1, b);
        } else {
            add(a, nb.first);
            add(a, nb.first + 1);
        }
    }
    /// for_each_overlapping_pair below one node pair, on the calling thread.
    template <class F>
    void pairs_below(NodePair start, F& f) const {
        std::vector<NodePair> stack{start};
        while (!stack.empty()) {
            const NodePair p = stack.back();
            stack.pop_back();
            if (!is_leaf_pair(p)) {
                split_pair(p, stack);
                continue;
            }
            const Node& na = nodes_[p.first];
            const Node& nb = nodes_[p.second];
            for (std::uint32_t i = na.first; i < na.first + na.count; ++i) {
                const std::uint32_t t = order_[i];
                const Box3& bt = boxes_[t];
                for (std::uint32_t k = p.first == p.second ? i + 1 : nb.first;
                     k < nb.first + nb.count; ++k) {
                    if (bt.overlaps(boxes_[order_[k]])) f(t, order_[k]);
                }
            }
        }
    }

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
    /// A lower bound on the squared distance from x to the part of node n's box within its slab,
    /// for x beyond the slab by gap > 0 (along its axis at `along`).
    static double slab_and_box(const Node& n, Vec3 x, double along, double gap);

    std::vector<Node> nodes_;
    bool slabs_ = false;                ///< whether the nodes' slabs are set
    std::vector<std::uint32_t> order_;  ///< triangle indices, grouped by leaf
    std::vector<Box3> boxes_;           ///< each triangle's bounding box
    bool plain_ = true;  ///< every triangle in_plain_range: queries may skip the range checks
};

}  // namespace slc
