// TriangleHierarchy: median-split construction and the pruned nearest-triangle descent.
#include "slc/geometry/triangle_hierarchy.hpp"

#include <algorithm>
#include <numeric>

namespace slc {
namespace {

/// A box is skipped when its squared distance exceeds the best by more than this factor: a
/// triangle whose computed distance ties the best to rounding is still examined, so that the
/// least index wins as in a scan of every triangle.
constexpr double prune_slack = 1.0 + 1e-12;

}  // namespace

TriangleHierarchy::TriangleHierarchy(std::span<const Triangle3> triangles) {
    const auto n = static_cast<std::uint32_t>(triangles.size());
    if (n == 0) return;
    boxes_.resize(n);
    // The triangles' centroids (of their boxes) beside their indices, moved together while the
    // nodes are split: contiguous, where an index into a centroid array would jump about.
    struct Item {
        Vec3 centre;
        std::uint32_t t;
    };
    std::vector<Item> items(n);
    for (std::uint32_t t = 0; t < n; ++t) {
        boxes_[t] = bounding_box(triangles[t]);
        items[t] = {boxes_[t].center(), t};
    }
    nodes_.reserve(2 * (n / leaf_size + 1));
    nodes_.push_back({Box3::empty(), 0, n});
    // Nodes are split in creation order; a split node's children are appended side by side.
    // Depth stays below 64 (the stack of the queries): median splits halve the count.
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        const std::uint32_t first = nodes_[i].first, count = nodes_[i].count;
        if (count <= leaf_size) continue;
        Box3 centres = Box3::empty();
        for (std::uint32_t k = first; k < first + count; ++k)
            centres = unite(centres, {items[k].centre, items[k].centre});
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (centres.extent(a) > centres.extent(axis)) axis = a;
        const std::uint32_t half = count / 2;
        // Ties broken by index, so that the hierarchy does not depend on the sort's whims.
        std::nth_element(items.begin() + first, items.begin() + first + half,
                         items.begin() + first + count, [&](const Item& p, const Item& q) {
                             const double cp = p.centre[axis], cq = q.centre[axis];
                             return cp < cq || (cp == cq && p.t < q.t);
                         });
        const auto child = static_cast<std::uint32_t>(nodes_.size());
        nodes_[i].first = child;
        nodes_[i].count = 0;
        nodes_.push_back({Box3::empty(), first, half});
        nodes_.push_back({Box3::empty(), first + half, count - half});
    }
    order_.resize(n);
    for (std::uint32_t k = 0; k < n; ++k) order_[k] = items[k].t;
    // Boxes bottom up: children come after their parent.
    for (std::size_t i = nodes_.size(); i-- > 0;) {
        Node& node = nodes_[i];
        Box3 box = Box3::empty();
        if (node.count > 0) {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                box = unite(box, boxes_[order_[k]]);
        } else {
            box = unite(nodes_[node.first].box, nodes_[node.first + 1].box);
        }
        node.box = box;
    }
}

void TriangleHierarchy::nearest(std::span<const Triangle3> triangles, Vec3 x,
                                NearestFacet& best) const {
    if (nodes_.empty()) return;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        // A box farther than the best so far holds nothing nearer; one as far (to rounding) may
        // hold a tie with a smaller index, so only clearly farther boxes are skipped.
        if (distance2(n.box, x) > best.distance2 * prune_slack) continue;
        if (n.count > 0) {
            for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                const std::uint32_t t = order_[i];
                if (distance2(boxes_[t], x) <= best.distance2 * prune_slack)
                    best.offer(t, closest_point(triangles[t], x));
            }
            continue;
        }
        // Nearer child last on the stack, so it is searched first.
        const double d0 = distance2(nodes_[n.first].box, x);
        const double d1 = distance2(nodes_[n.first + 1].box, x);
        if (d0 <= d1) {
            stack[top++] = n.first + 1;
            stack[top++] = n.first;
        } else {
            stack[top++] = n.first;
            stack[top++] = n.first + 1;
        }
    }
}

}  // namespace slc
