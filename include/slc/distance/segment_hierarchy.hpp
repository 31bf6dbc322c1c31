/// @file
/// SegmentHierarchy: a bounding-box hierarchy over segments in index order, for the exact nearest
/// segment to points far from Γ, where the distance tree's cells are large and their lists long.
///
/// Consecutive segments of a curve lie side by side, so runs of consecutive indices make tight
/// boxes: the hierarchy is a complete binary tree over runs of `leaf_size` segments, built in O(N)
/// without sorting. A query descends nearer child first and skips every box farther than the best
/// segment so far, which makes it O(log N) for a point far from a curve of similar segments.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/geometry/segment.hpp"

namespace slc {

/// The nearest segment found so far: the least (distance2, segment) pair, compared in that
/// order, so that the answer is the same whatever order segments are examined in.
struct NearestSegment {
    double distance2 = std::numeric_limits<double>::infinity();         ///< squared distance to x
    std::uint32_t segment = std::numeric_limits<std::uint32_t>::max();  ///< its index
    Vec2 point;      ///< the nearest point on that segment
    double t = 0.0;  ///< point = a + t (b − a)

    /// Takes segment s with its nearest point p if (p.distance2, s) is less than the best so far.
    void offer(std::uint32_t s, const SegmentPoint& p) {
        if (p.distance2 < distance2 || (p.distance2 == distance2 && s < segment)) {
            distance2 = p.distance2;
            segment = s;
            point = p.point;
            t = p.t;
        }
    }
};

/// Boxes over runs of consecutive segments, nested in a complete binary tree (see the file
/// comment); the segments themselves stay with the caller.
class SegmentHierarchy {
public:
    /// Segments per leaf box.
    static constexpr std::uint32_t leaf_size = 8;

    SegmentHierarchy() = default;
    /// Builds the boxes over segments (which the queries must be given again, unchanged). O(N).
    explicit SegmentHierarchy(std::span<const Segment> segments);

    /// Lowers best to the least (distance2, segment) over all segments: exact, and the same
    /// answer as a scan of every segment. A best already found (for example from a short list
    /// near x) only prunes more; so does hint, a segment to try first (an index out of range:
    /// none).
    void nearest(std::span<const Segment> segments, Vec2 x, NearestSegment& best,
                 std::uint32_t hint = no_hint) const;
    /// The hint of nearest() that tries nothing first.
    static constexpr std::uint32_t no_hint = std::numeric_limits<std::uint32_t>::max();

private:
    std::uint32_t leaves_ = 0;  ///< leaf boxes, a power of two; node i has children 2i, 2i + 1
    std::vector<Box> boxes_;    ///< node 1 is the root; leaves are nodes leaves_ .. 2 leaves_ − 1
};

}  // namespace slc
