/// @file
/// Validation of user-given surfaces (DESIGN §8): the one place where raw vertices and triangles
/// become a Surface that every other module may trust. The 3D counterpart of validate.hpp.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "slc/geometry/surface.hpp"
#include "slc/geometry/validate.hpp"

namespace slc {

/// Two triangles of a surface that meet where they should not.
using TriangleContact = ElementPair;

/// Finds the pair of triangles (least first, then least second) that meet other than in the
/// corners and edge they share, with a bounding-volume hierarchy for the candidate pairs (O(N log
/// N) for a surface of similar triangles) and exact predicates. Touching, overlapping and
/// crossing all count. Precondition: no triangle is degenerate.
std::optional<TriangleContact> find_self_intersection(const Surface& s);
/// The same among the pairs with at least one triangle flagged in `changed` (one flag a
/// triangle): when the others are known not to meet, the answer of the whole check, for the cost
/// of the flagged triangles' pairs.
std::optional<TriangleContact> find_self_intersection(const Surface& s,
                                                      std::span<const std::uint8_t> changed);
/// Contacts among the pairs with a triangle flagged: for each triangle i, in increasing order,
/// the least j > i it meets, when there is one. The first is find_self_intersection's answer.
/// Cost: the flagged triangles' pairs.
std::vector<TriangleContact> find_self_intersections(const Surface& s,
                                                     std::span<const std::uint8_t> changed);

/// What prepare_surface did to the input besides checking it.
struct PreparedSurface {
    Surface surface;  ///< the valid surface, oriented outward
    /// One line per change made, for instance "component 1 (from triangle 80) was oriented
    /// inward; reversed".
    std::vector<std::string> notes;
};

/// Turns raw vertices and triangles into a valid Surface, or throws InvalidInput with one line
/// naming the triangle(s), edge or vertex at fault (numbered from 0 in the order given). In order:
/// - no triangles: error;
/// - a non-finite coordinate, or one beyond ±tolerance::max_coordinate: error;
/// - an index beyond the vertices: error;
/// - a degenerate triangle (a repeated corner, or zero area decided exactly): error;
/// - an open edge (one triangle), a non-manifold edge (three or more), two triangles oriented
///   inconsistently across an edge: error;
/// - a non-manifold vertex (its triangles form two or more fans): error;
/// - two triangles meeting elsewhere than in a shared corner or edge (find_self_intersection):
///   error;
/// - orientation: a component nested inside an even number of others must enclose positive
///   volume (outward normals), inside an odd number (a cavity) negative; a component the other
///   way round is reversed and noted.
/// Vertices used by no triangle are kept and ignored. Cost O(N log N) plus O(C·N) for the
/// nesting of C components.
PreparedSurface prepare_surface(Surface raw);

}  // namespace slc
