/// @file
/// Box: an axis-aligned rectangle, used for the computational domain (a square) and for tree cells.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "slc/core/exact_cube.hpp"
#include "slc/core/vec2.hpp"

namespace slc {

/// The closed rectangle [lo.x, hi.x] × [lo.y, hi.y].
struct Box {
    Vec2 lo;  ///< lower left corner
    Vec2 hi;  ///< upper right corner

    /// The square [−b, b]², the paper's standard domain.
    static constexpr Box centered_square(double b) { return {{-b, -b}, {b, b}}; }
    /// The square of half-width b centred on c: exactly square (width() == height()), which
    /// c ± b need not be, as x and y round differently. Then its corners are snapped to a grid of
    /// about 2^−24 of its width, outward, so that it still holds [c − b, c + b]².
    static Box square(Vec2 c, double b) {
        const Box naive{{c.x - b, c.y - b}, {c.x + b, c.y + b}};
        if (naive.width() == naive.height() || !(b > 0.0) || !std::isfinite(b) ||
            !std::isfinite(c.x) || !std::isfinite(c.y))
            return naive;  // square already, or bad input that validation names
        const auto [lo, w] = detail::exact_cube<2>({c.x, c.y}, b);
        return {{lo[0], lo[1]}, {lo[0] + w, lo[1] + w}};
    }
    /// The empty box (lo > hi): the identity of unite().
    static constexpr Box empty() {
        constexpr double inf = std::numeric_limits<double>::infinity();
        return {{inf, inf}, {-inf, -inf}};
    }

    /// True when the box holds no point (lo > hi in some coordinate), as Box::empty() does.
    constexpr bool is_empty() const { return !(lo.x <= hi.x && lo.y <= hi.y); }

    /// hi.x − lo.x.
    constexpr double width() const { return hi.x - lo.x; }
    /// hi.y − lo.y.
    constexpr double height() const { return hi.y - lo.y; }
    /// The largest magnitude of a corner coordinate: the scale of rounding in the box.
    double largest_magnitude() const {
        return std::max({std::abs(lo.x), std::abs(lo.y), std::abs(hi.x), std::abs(hi.y)});
    }
    /// The midpoint of the box.
    constexpr Vec2 center() const { return {0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)}; }
    /// True when p lies in the closed box (boundary included).
    constexpr bool contains(Vec2 p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    }
    /// True when the whole of b lies in this closed box.
    constexpr bool contains(const Box& b) const {
        return b.lo.x >= lo.x && b.hi.x <= hi.x && b.lo.y >= lo.y && b.hi.y <= hi.y;
    }
    /// True when the two closed boxes share at least one point (touching counts).
    constexpr bool overlaps(const Box& b) const {
        return b.lo.x <= hi.x && b.hi.x >= lo.x && b.lo.y <= hi.y && b.hi.y >= lo.y;
    }
    /// The box grown by m on every side.
    constexpr Box inflated(double m) const { return {{lo.x - m, lo.y - m}, {hi.x + m, hi.y + m}}; }
    /// The point of the box nearest p.
    constexpr Vec2 clamp(Vec2 p) const {
        return {std::clamp(p.x, lo.x, hi.x), std::clamp(p.y, lo.y, hi.y)};
    }
    /// Exact equality of both corners.
    friend constexpr bool operator==(const Box&, const Box&) = default;
};

/// The smallest box holding a and b.
constexpr Box unite(const Box& a, const Box& b) {
    return {{std::min(a.lo.x, b.lo.x), std::min(a.lo.y, b.lo.y)},
            {std::max(a.hi.x, b.hi.x), std::max(a.hi.y, b.hi.y)}};
}

/// The smallest box holding every finite point; Box::empty() when there is none.
inline Box bounding_box(std::span<const Vec2> points) {
    Box b = Box::empty();
    for (const Vec2 p : points) {
        if (is_finite(p)) b = unite(b, {p, p});
    }
    return b;
}

/// Euclidean distance from p to the box (zero inside).
inline double distance(const Box& b, Vec2 p) { return distance(b.clamp(p), p); }

}  // namespace slc
