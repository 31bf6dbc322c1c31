// TriangleHierarchy: construction on the Morton order and the pruned nearest-triangle descent.
#include "slc/geometry/triangle_hierarchy.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "slc/core/parallel.hpp"

namespace slc {
namespace {

/// A box is skipped when its squared distance exceeds the best by more than this factor: a
/// triangle whose computed distance ties the best to rounding is still examined, so that the
/// least index wins as in a scan of every triangle.
constexpr double prune_slack = 1.0 + 1e-12;
/// A bound on the relative rounding of a dot product of a unit axis with a point: 10⁻¹⁴ of its
/// largest coordinate, against about 3.3·10⁻¹⁶ at most.
constexpr double rounding = 1e-14;
/// Nodes of more triangles have no slab (the whole line): a large patch of a curved surface
/// has a thick one, and each level of slabs costs a pass over every triangle's corners.
constexpr std::uint32_t largest_slab = 4096;

}  // namespace

namespace {

/// Bits 0..20 of v spread to every third bit (bit k to bit 3k).
std::uint64_t spread_by_three(std::uint64_t v) {
    v &= 0x1fffffu;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

}  // namespace

std::vector<TriangleHierarchy::NodePair> TriangleHierarchy::pair_tasks() const {
    // Split level by level (a deterministic list, though the answer does not depend on it)
    // until there are 64 tasks a thread or nothing is left to split.
    const std::size_t enough = 64 * static_cast<std::size_t>(std::max(1, thread_count()));
    std::vector<NodePair> tasks{{0, 0}}, next;
    while (tasks.size() < enough) {
        next.clear();
        bool split = false;
        for (const NodePair& p : tasks) {
            if (is_leaf_pair(p)) {
                next.push_back(p);
            } else {
                split_pair(p, next);
                split = true;
            }
        }
        tasks.swap(next);
        if (!split) break;
    }
    return tasks;
}

TriangleHierarchy::TriangleHierarchy(std::span<const Triangle3> triangles, Bounds bounds) {
    const auto n = static_cast<std::uint32_t>(triangles.size());
    if (n == 0) return;
    boxes_.resize(n);
    parallel_for(n, [&](std::size_t t) { boxes_[t] = bounding_box(triangles[t]); });
    plain_ = std::all_of(triangles.begin(), triangles.end(),
                         [](const Triangle3& t) { return in_plain_range(t); });
    // The box of the centres, from the boxes of parts of them on all threads (exact: the same
    // box for any number of parts).
    const auto parts = static_cast<std::size_t>(std::max(1, thread_count()));
    std::vector<Box3> part_centres(parts, Box3::empty());
    parallel_for(
        parts,
        [&](std::size_t p) {
            for (std::size_t t = n * p / parts; t < n * (p + 1) / parts; ++t) {
                const Vec3 c = boxes_[t].center();
                part_centres[p] = unite(part_centres[p], {c, c});
            }
        },
        1);
    Box3 centres = Box3::empty();
    for (const Box3& b : part_centres) centres = unite(centres, b);
    // The triangles in the Morton order of their boxes' centres (21 bits an axis over the box
    // of all centres; ties by index): every node is a range of this order, so a split is a cut
    // of its range, where sorting each node's triangles along an axis would cost a selection.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
    parallel_for(n, [&](std::size_t i) {
        const auto t = static_cast<std::uint32_t>(i);
        const Vec3 c = boxes_[t].center();
        std::uint64_t code = 0;
        for (int a = 0; a < 3; ++a) {
            const double extent = centres.extent(a);
            const double q = extent > 0.0 ? (c[a] - centres.lo[a]) / extent * 2097151.0 : 0.0;
            code |= spread_by_three(static_cast<std::uint64_t>(std::clamp(q, 0.0, 2097151.0))) << a;
        }
        keyed[t] = {code, t};
    });
    parallel_sort(keyed.begin(), keyed.end());  // the keys are unique: (code, index)
    order_.resize(n);
    parallel_for(n, [&](std::size_t k) { order_[k] = keyed[k].second; });
    nodes_.reserve(2 * (n / leaf_size + 1));
    auto node_of = [](std::uint32_t first, std::uint32_t count) {
        Node node;
        node.box = Box3::empty();
        node.first = first;
        node.count = count;
        return node;
    };
    nodes_.push_back(node_of(0, n));
    // Nodes are split in creation order; a split node's children are appended side by side. A
    // node is cut where its highest differing Morton bit turns on, which separates space, when
    // that leaves each side at least a third; otherwise in half. Depth stays below 64 (the stack
    // of the queries): each side keeps at most two thirds.
    // Each node's range of the order, which an inner node's first and count give up.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> range;
    range.reserve(nodes_.capacity());
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        const std::uint32_t first = nodes_[i].first, count = nodes_[i].count;
        range.emplace_back(first, count);
        if (count <= leaf_size) continue;
        const std::uint64_t lo = keyed[first].first, hi = keyed[first + count - 1].first;
        std::uint32_t cut = count / 2;
        if (lo != hi) {
            const std::uint64_t bit = std::uint64_t{1} << (63 - std::countl_zero(lo ^ hi));
            const auto begin = keyed.begin() + first, end = begin + count;
            const auto at = std::partition_point(
                begin, end, [&](const auto& k) { return (k.first & bit) == 0; });
            const auto split = static_cast<std::uint32_t>(at - begin);
            if (3 * split >= count && 3 * (count - split) >= count) cut = split;
        }
        const auto child = static_cast<std::uint32_t>(nodes_.size());
        nodes_[i].first = child;
        nodes_[i].count = 0;
        nodes_.push_back(node_of(first, cut));
        nodes_.push_back(node_of(first + cut, count - cut));
    }
    // The leaves' boxes on all threads, then the others bottom up: children come after their
    // parent.
    parallel_for(nodes_.size(), [&](std::size_t i) {
        Node& node = nodes_[i];
        if (node.count == 0) return;
        Box3 box = Box3::empty();
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
            box = unite(box, boxes_[order_[k]]);
        node.box = box;
    });
    for (std::size_t i = nodes_.size(); i-- > 0;) {
        Node& node = nodes_[i];
        if (node.count == 0) node.box = unite(nodes_[node.first].box, nodes_[node.first + 1].box);
    }
    if (bounds == Bounds::boxes) return;
    slabs_ = true;
    // The slabs: each node's axis its triangles' area normals summed (the leaves' on all threads,
    // then bottom up), and the extent of their corners along it, on all threads, from the
    // triangles copied in the order so that every node reads a contiguous range.
    std::vector<Triangle3> ordered(n);
    parallel_for(n, [&](std::size_t k) { ordered[k] = triangles[order_[k]]; });
    std::vector<Vec3> normal_sum(nodes_.size());
    parallel_for(nodes_.size(), [&](std::size_t i) {
        const Node& node = nodes_[i];
        Vec3 sum{};
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
            const Triangle3& t = ordered[k];
            sum += cross(t.b - t.a, t.c - t.a);
        }
        normal_sum[i] = sum;
    });
    for (std::size_t i = nodes_.size(); i-- > 0;) {
        const Node& node = nodes_[i];
        if (node.count == 0) normal_sum[i] = normal_sum[node.first] + normal_sum[node.first + 1];
    }
    parallel_for(nodes_.size(), [&](std::size_t i) {
        Node& node = nodes_[i];
        const double length = norm(normal_sum[i]);
        // Any unit axis bounds the distance; one across the triangles bounds it best.
        node.axis = length > 0.0 && std::isfinite(length) ? (1.0 / length) * normal_sum[i]
                                                          : Vec3{1.0, 0.0, 0.0};
        const auto [first, count] = range[i];
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        if (count > largest_slab) {  // no slab: it would prune little, and cost a pass
            node.lo = -std::numeric_limits<double>::infinity();
            node.hi = std::numeric_limits<double>::infinity();
            return;
        }
        for (std::uint32_t k = first; k < first + count; ++k) {
            const Triangle3& t = ordered[k];
            for (const Vec3 v : {t.a, t.b, t.c}) {
                const double d = dot(node.axis, v);
                lo = std::min(lo, d);
                hi = std::max(hi, d);
            }
        }
        // Widened by the dot products' rounding, a few units in the last place of the corners'
        // coordinates (the query's are allowed for in nearest()).
        const double scale = node.box.largest_magnitude();
        node.lo = lo - rounding * scale;
        node.hi = hi + rounding * scale;
    });
}

double TriangleHierarchy::slab_and_box(const Node& n, Vec3 x, double along, double gap) {
    // For x beyond the slab's top face h (below its bottom: mirrored), every point y of the
    // node's triangles lies in the box with a·y ≤ h, so |x − y|² ≥ |x − y|² + 2μ (a·y − h) for
    // any μ ≥ 0; the least of the right side over the box is taken coordinate by coordinate, at
    // y = clamp(x − μa) (Lagrangian duality). With μ the gap it is gap² + s² for a flat patch,
    // s the distance from x's foot on the patch's plane to the box, where the box and the slab
    // tested apart give only the larger of gap² and the box's distance: a tilted patch's box
    // reaches towards x. The right side is at least gap² + (h − a·y)² where a·y < h (the gap
    // and that depth add in |x − y|), so its terms cancel by at most a factor of two; a·y's
    // rounding (a few units in the last place of the box's coordinates, as the slab's widening
    // covers those of the corners) is taken off, and the relative rounding stays far below the
    // slack of the comparison.
    const bool above = along > n.hi;
    const double sign = above ? 1.0 : -1.0;
    const double face = above ? n.hi : n.lo;
    double bound = 0.0, depth = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double y = std::clamp(x[i] - sign * gap * n.axis[i], n.box.lo[i], n.box.hi[i]);
        bound += (x[i] - y) * (x[i] - y);
        depth += n.axis[i] * y;
    }
    bound += 2.0 * gap * (sign * (depth - face) - rounding * n.box.largest_magnitude());
    return bound * (1.0 - 1e-13);
}

void TriangleHierarchy::nearest(std::span<const Triangle3> triangles, Vec3 x, NearestFacet& best,
                                std::uint32_t hint) const {
    if (nodes_.empty()) return;
    const double slack = rounding * std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    const bool plain = plain_ && in_plain_range(x);
    // The hint's point is the one the search computes for it, so it changes only what is pruned.
    if (hint < triangles.size())
        best.offer(hint, plain ? closest_point_in_range(triangles[hint], x)
                               : closest_point(triangles[hint], x));
    // Nodes to visit with their boxes' squared distances, computed once, when their parent is.
    std::uint32_t stack[64];
    double stack_d2[64];
    int top = 0;
    stack[top] = 0;
    stack_d2[top++] = distance2(nodes_[0].box, x);
    while (top > 0) {
        --top;
        // A box or slab farther than the best so far holds nothing nearer; one as far (to
        // rounding) may hold a tie with a smaller index, so only clearly farther ones are
        // skipped. The box first: it is cheaper, and settles most nodes near the surface.
        const double limit = best.distance2 * prune_slack;
        if (stack_d2[top] > limit) continue;
        const Node& n = nodes_[stack[top]];
        if (slabs_) {
            const double along = dot(n.axis, x);
            const double gap = std::max(n.lo - along, along - n.hi) - slack;
            if (gap > 0.0 && (gap * gap > limit || slab_and_box(n, x, along, gap) > limit))
                continue;
        }
        if (n.count > 0) {
            for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                const std::uint32_t t = order_[i];
                if (distance2(boxes_[t], x) <= best.distance2 * prune_slack)
                    best.offer(t, plain ? closest_point_in_range(triangles[t], x)
                                        : closest_point(triangles[t], x));
            }
            continue;
        }
        // Nearer child last on the stack, so it is searched first.
        const double d0 = distance2(nodes_[n.first].box, x);
        const double d1 = distance2(nodes_[n.first + 1].box, x);
        const bool first_nearer = d0 <= d1;
        stack[top] = first_nearer ? n.first + 1 : n.first;
        stack_d2[top++] = first_nearer ? d1 : d0;
        stack[top] = first_nearer ? n.first : n.first + 1;
        stack_d2[top++] = first_nearer ? d0 : d1;
    }
}

}  // namespace slc
