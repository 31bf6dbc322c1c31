// Checks shared by the contour tests: residuals of G on a contour, simplicity by brute force and
// by the sweep line, and the orientation rule (G > 0 on the right of every segment).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "slc/contour/contour.hpp"
#include "slc/geometry/predicates.hpp"
#include "slc/geometry/validate.hpp"

namespace slc::testing {

/// Largest |G| over the vertices and over the segment midpoints of a contour, the midpoints
/// computed as refinement computes them (same bits, hence the same values of G).
struct Residuals {
    double vertices = 0.0;
    double midpoints = 0.0;
};

template <class F>
Residuals residuals(const Interface& curves, const F& g) {
    std::vector<Vec2> points(curves.points().begin(), curves.points().end());
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const Segment s = curves.segment(i);
        points.push_back(0.5 * (s.a + s.b));
    }
    std::vector<double> values(points.size());
    g(std::span<const Vec2>(points), std::span<double>(values));
    Residuals r;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        r.vertices = std::max(r.vertices, std::abs(values[i]));
        r.midpoints = std::max(r.midpoints, std::abs(values[curves.size() + i]));
    }
    return r;
}

/// True if two segments meet other than consecutive ones at their shared vertex: O(N²) with the
/// exact predicate, the oracle for find_crossing on small contours.
inline bool has_crossing_brute_force(const Interface& curves) {
    for (std::size_t i = 0; i < curves.size(); ++i) {
        for (std::size_t j = i + 1; j < curves.size(); ++j) {
            if (curves.next(i) == j || curves.next(j) == i) {
                // Consecutive: they must not overlap beyond the shared vertex.
                const std::size_t first = curves.next(i) == j ? i : j;
                const Segment a = curves.segment(first), b = curves.segment(curves.next(first));
                if (orientation(a.a, a.b, b.b) == 0 && dot(a.a - a.b, b.b - b.a) > 0.0) return true;
                continue;
            }
            if (segments_intersect(curves.segment(i), curves.segment(j))) return true;
        }
    }
    return false;
}

/// Every curve simple and disjoint from the others: the sweep line, and brute force when small;
/// closed polygons of at least three vertices with no zero-length segment.
inline void expect_simple(const Interface& curves) {
    for (std::size_t c = 0; c < curves.curve_count(); ++c) EXPECT_GE(curves.curve(c).size(), 3u);
    for (std::size_t i = 0; i < curves.size(); ++i)
        EXPECT_NE(curves.segment(i).a, curves.segment(i).b);
    EXPECT_FALSE(find_crossing(curves).has_value());
    if (curves.size() <= 1500) {
        EXPECT_FALSE(has_crossing_brute_force(curves));
    }
}

/// G > 0 just right of every segment midpoint and G < 0 just left of it, at the given fraction of
/// the segment's length: the orientation rule (outside on the right). The fraction must exceed
/// the midpoint error over the length and stay below the distance to other parts of the zero set.
template <class F>
void expect_outside_on_right(const Interface& curves, const F& g, double fraction) {
    std::vector<Vec2> points;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const Segment s = curves.segment(i);
        const Vec2 mid = 0.5 * (s.a + s.b), d = s.b - s.a;
        const Vec2 right{d.y, -d.x};
        points.push_back(mid + fraction * right);
        points.push_back(mid - fraction * right);
    }
    std::vector<double> values(points.size());
    g(std::span<const Vec2>(points), std::span<double>(values));
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        if (!(values[2 * i] > 0.0 && values[2 * i + 1] < 0.0)) ++wrong;
    }
    EXPECT_EQ(wrong, 0u) << "segments with G <= 0 on their right or G >= 0 on their left";
}

}  // namespace slc::testing
