/// @file
/// Validation of user-given curves (DESIGN §2, §6): the one place where raw coordinates become an
/// Interface that every other module may trust.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// Two elements of a user's input (segments of curves, triangles of a surface) that meet where
/// they should not, by index, the smaller first.
struct ElementPair {
    std::size_t first = 0;
    std::size_t second = 0;
};
/// Two segments of an interface that meet where they should not.
using Crossing = ElementPair;

/// Finds a pair of segments that intersect, other than consecutive segments of one curve meeting
/// at their shared vertex, in O(N log N) by a sweep line (Shamos–Hoey) with exact predicates.
/// Touching, overlapping and crossing all count. Returns nothing for a simple, disjoint set of
/// curves.
std::optional<Crossing> find_crossing(const Interface& curves);

/// What prepare_interface did to the input besides checking it.
struct PreparedInterface {
    Interface curves;  ///< the valid curves, oriented as DESIGN §2 says
    /// One line per change made, for instance "curve 1 was clockwise; reoriented counterclockwise".
    std::vector<std::string> notes;
};

/// Turns raw curves into a valid Interface, or throws InvalidInput with one line naming the
/// curve and vertex at fault. In order:
/// - no curves at all: error;
/// - a non-finite coordinate, or one beyond ±tolerance::max_coordinate: error;
/// - a point outside domain (when given): error;
/// - consecutive duplicate points (and a last point repeating the first) are dropped silently;
/// - fewer than 3 distinct points left: error;
/// - a curve crossing itself or another (find_crossing): error;
/// - orientation: a curve nested inside an even number of others must be counterclockwise, inside
///   an odd number (a hole) clockwise; a curve the other way round is reversed and noted.
/// Cost O(N log N) plus O(C·N) for the nesting of C curves.
PreparedInterface prepare_interface(const std::vector<std::vector<Vec2>>& raw,
                                    const std::optional<Box>& domain = std::nullopt);

}  // namespace slc
