// SegmentHierarchy: building the boxes bottom-up and the pruned nearer-first descent.
#include "slc/distance/segment_hierarchy.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace slc {
namespace {

/// Relative growth of every box: a computed segment distance can fall below the exact distance
/// between x and the box by rounding, never by more than this fraction of the coordinates, so
/// the grown box's distance stays a lower bound of every computed distance inside it.
constexpr double box_slack = 1e-12;

/// Squared distance from x to box b (0 inside; infinite for an empty box, which Box::clamp
/// does not handle).
double distance2(const Box& b, Vec2 x) {
    const double dx = std::max({b.lo.x - x.x, x.x - b.hi.x, 0.0});
    const double dy = std::max({b.lo.y - x.y, x.y - b.hi.y, 0.0});
    return dx * dx + dy * dy;
}

}  // namespace

SegmentHierarchy::SegmentHierarchy(std::span<const Segment> segments) {
    const auto n = static_cast<std::uint32_t>(segments.size());
    const std::uint32_t runs = std::max(1u, (n + leaf_size - 1) / leaf_size);
    leaves_ = std::bit_ceil(runs);
    boxes_.assign(2 * std::size_t{leaves_}, Box::empty());
    double scale = 0.0;
    for (std::uint32_t s = 0; s < n; ++s) {
        const Segment& seg = segments[s];
        Box& leaf = boxes_[leaves_ + s / leaf_size];
        leaf = unite(leaf, bounding_box(seg));
        scale = std::max(
            {scale, std::abs(seg.a.x), std::abs(seg.a.y), std::abs(seg.b.x), std::abs(seg.b.y)});
    }
    const double slack = box_slack * scale;
    for (std::uint32_t i = leaves_; i < 2 * leaves_; ++i)
        if (!boxes_[i].is_empty()) boxes_[i] = boxes_[i].inflated(slack);
    for (std::uint32_t i = leaves_ - 1; i >= 1; --i)
        boxes_[i] = unite(boxes_[2 * i], boxes_[2 * i + 1]);
}

void SegmentHierarchy::nearest(std::span<const Segment> segments, Vec2 x, NearestSegment& best,
                               std::uint32_t hint) const {
    if (boxes_.empty()) return;
    if (hint < segments.size()) best.offer(hint, closest_point(segments[hint], x));
    // Depth-first, nearer child first; a box is opened only if it may hold a segment at most as
    // far as the best (ties matter: the lower index wins).
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 1;
    while (top > 0) {
        const std::uint32_t node = stack[--top];
        if (distance2(boxes_[node], x) > best.distance2) continue;
        if (node >= leaves_) {
            const std::uint32_t first = (node - leaves_) * leaf_size;
            const std::uint32_t last = std::min<std::uint32_t>(
                first + leaf_size, static_cast<std::uint32_t>(segments.size()));
            for (std::uint32_t s = first; s < last; ++s)
                best.offer(s, closest_point(segments[s], x));
            continue;
        }
        const std::uint32_t a = 2 * node, b = 2 * node + 1;
        const double da = distance2(boxes_[a], x), db = distance2(boxes_[b], x);
        const bool a_first = da <= db;
        const std::uint32_t near = a_first ? a : b, far = a_first ? b : a;
        const double d_near = a_first ? da : db, d_far = a_first ? db : da;
        if (d_far <= best.distance2) stack[top++] = far;
        if (d_near <= best.distance2) stack[top++] = near;
    }
}

}  // namespace slc
