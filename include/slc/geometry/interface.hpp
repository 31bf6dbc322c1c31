/// @file
/// Interface: the moving curve Γ as a finite set of closed oriented polygons (DESIGN §2), stored
/// flat so that trees and batches can index its vertices and segments by one number.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "slc/core/vec2.hpp"

namespace slc {

/// Segment i of an interface: from vertex i to the next vertex of the same curve.
struct Segment {
    Vec2 a;  ///< first end: vertex i
    Vec2 b;  ///< second end: vertex next(i)
};

/// A set of closed polygons ("curves"). Vertex i and segment i share an index: segment i joins
/// vertex i to next(i). Curves are counterclockwise around their inside, holes clockwise, so the
/// outside (signed distance > 0) lies to the right of each segment.
///
/// Invariants: every curve has at least 3 vertices. Validation of the geometry (finite, no
/// crossings, orientation) is separate: see validate.hpp.
class Interface {
public:
    /// No curves: empty() is true.
    Interface() = default;
    /// Builds from a list of curves, each a list of vertices, the closing segment implicit.
    /// Throws InvalidInput if a curve has fewer than 3 vertices.
    explicit Interface(const std::vector<std::vector<Vec2>>& curves);

    /// Number of closed curves.
    std::size_t curve_count() const { return offsets_.size() - 1; }
    /// Number of vertices, which is also the number of segments.
    std::size_t size() const { return points_.size(); }
    /// True when there are no curves (a run whose curves all vanished).
    bool empty() const { return points_.empty(); }

    /// Vertex i, 0 <= i < size().
    Vec2 point(std::size_t i) const { return points_[i]; }
    /// All vertices, curve after curve, each curve in its order.
    std::span<const Vec2> points() const { return points_; }
    /// The vertices of curve c, in order.
    std::span<const Vec2> curve(std::size_t c) const {
        return std::span<const Vec2>(points_).subspan(offsets_[c], offsets_[c + 1] - offsets_[c]);
    }
    /// Index of the first vertex of curve c; offsets()[curve_count()] == size().
    std::span<const std::size_t> offsets() const { return offsets_; }

    /// The curve holding vertex i.
    std::size_t curve_of(std::size_t i) const { return curve_index_[i]; }
    /// The next and previous vertex of the same curve, cyclically.
    std::size_t next(std::size_t i) const {
        return i + 1 == offsets_[curve_index_[i] + 1] ? offsets_[curve_index_[i]] : i + 1;
    }
    /// @copybrief next
    std::size_t prev(std::size_t i) const {
        return i == offsets_[curve_index_[i]] ? offsets_[curve_index_[i] + 1] - 1 : i - 1;
    }
    /// Segment i: from vertex i to vertex next(i).
    Segment segment(std::size_t i) const { return {points_[i], points_[next(i)]}; }

    /// Reverses the order of the vertices of curve c (flips its orientation).
    void reverse_curve(std::size_t c);

    /// The curves as nested lists, the inverse of the constructor.
    std::vector<std::vector<Vec2>> curves() const;

private:
    std::vector<Vec2> points_;
    std::vector<std::size_t> offsets_{0};
    std::vector<std::size_t> curve_index_;
};

/// The vertices of every curve, then the midpoints of every segment: [0, N) and [N, 2N). The
/// points at which the paper's Eq. (11) measures the error of an interface.
std::vector<Vec2> vertices_and_midpoints(const Interface& curves);

/// Signed area enclosed by one closed polygon: positive when counterclockwise (shoelace formula).
double signed_area(std::span<const Vec2> curve);
/// Total enclosed area of the interface: the sum of signed areas (holes, clockwise, subtract).
double area(const Interface& curves);
/// Length of one closed polygon, its closing segment included.
double length(std::span<const Vec2> curve);
/// Total length of all curves.
double length(const Interface& curves);

/// Whether curve c encloses point p (either orientation), by the crossings of the ray from p
/// towards +x. Exact; p must not lie on curve c.
bool encloses(const Interface& curves, std::size_t c, Vec2 p);

/// The region of each curve of disjoint curves: a counterclockwise curve (positive area) bounds a
/// region of its own, a clockwise one (a hole) belongs to the smallest counterclockwise curve
/// around it. Regions are numbered 0, 1, … in the order of their outer curves. Throws
/// InvalidInput for a hole inside no curve. O(curves² · vertices).
std::vector<std::size_t> curve_regions(const Interface& curves);

/// The region (curve_regions) whose inside holds x, or nothing when x is inside no region.
std::optional<std::size_t> region_containing(const Interface& curves,
                                             std::span<const std::size_t> region, Vec2 x);

}  // namespace slc
