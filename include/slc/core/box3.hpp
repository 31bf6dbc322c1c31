/// @file
/// Box3: an axis-aligned box of space, used for the 3D domain (a cube), octree cells and the
/// bounding boxes of triangles. The 3D counterpart of Box.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string_view>

#include "slc/core/exact_cube.hpp"
#include "slc/core/vec3.hpp"

namespace slc {

/// The closed box [lo.x, hi.x] × [lo.y, hi.y] × [lo.z, hi.z].
struct Box3 {
    Vec3 lo;  ///< lowest corner
    Vec3 hi;  ///< highest corner

    /// The cube [−b, b]³.
    static constexpr Box3 centered_cube(double b) { return {{-b, -b, -b}, {b, b, b}}; }
    /// The cube of half-width b centred on c: exactly a cube (is_cube()), which c ± b need not
    /// be, as x, y and z round differently. Then its corners are snapped to a grid of about
    /// 2^−24 of its width, outward, so that it still holds [c − b, c + b]³ (as Box::square).
    static Box3 cube(Vec3 c, double b) {
        const Box3 naive{{c.x - b, c.y - b, c.z - b}, {c.x + b, c.y + b, c.z + b}};
        if (naive.is_cube() || !(b > 0.0) || !std::isfinite(b) || !std::isfinite(c.x) ||
            !std::isfinite(c.y) || !std::isfinite(c.z))
            return naive;  // a cube already, or bad input that validation names
        const auto [lo, w] = detail::exact_cube<3>({c.x, c.y, c.z}, b);
        return {{lo[0], lo[1], lo[2]}, {lo[0] + w, lo[1] + w, lo[2] + w}};
    }
    /// The empty box (lo > hi): the identity of unite().
    static constexpr Box3 empty() {
        constexpr double inf = std::numeric_limits<double>::infinity();
        return {{inf, inf, inf}, {-inf, -inf, -inf}};
    }

    /// True when the box holds no point.
    constexpr bool is_empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    /// The extent along axis i (0, 1, 2).
    constexpr double extent(int i) const { return hi[i] - lo[i]; }
    /// hi.x − lo.x.
    constexpr double width() const { return hi.x - lo.x; }
    /// True when all three extents are equal.
    constexpr bool is_cube() const { return extent(1) == width() && extent(2) == width(); }
    /// The largest magnitude of a corner coordinate: the scale of rounding in the box.
    double largest_magnitude() const {
        return std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x),
                         std::abs(hi.y), std::abs(hi.z)});
    }
    /// The midpoint of the box.
    constexpr Vec3 center() const { return 0.5 * (lo + hi); }
    /// True when p lies in the closed box.
    constexpr bool contains(Vec3 p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z &&
               p.z <= hi.z;
    }
    /// True when the whole of b lies in this closed box.
    constexpr bool contains(const Box3& b) const {
        return b.lo.x >= lo.x && b.hi.x <= hi.x && b.lo.y >= lo.y && b.hi.y <= hi.y &&
               b.lo.z >= lo.z && b.hi.z <= hi.z;
    }
    /// True when the two closed boxes share at least one point (touching counts).
    constexpr bool overlaps(const Box3& b) const {
        return b.lo.x <= hi.x && b.hi.x >= lo.x && b.lo.y <= hi.y && b.hi.y >= lo.y &&
               b.lo.z <= hi.z && b.hi.z >= lo.z;
    }
    /// The box grown by m on every side.
    constexpr Box3 inflated(double m) const {
        return {{lo.x - m, lo.y - m, lo.z - m}, {hi.x + m, hi.y + m, hi.z + m}};
    }
    /// The point of the box nearest p.
    constexpr Vec3 clamp(Vec3 p) const {
        return {std::clamp(p.x, lo.x, hi.x), std::clamp(p.y, lo.y, hi.y),
                std::clamp(p.z, lo.z, hi.z)};
    }
    /// Exact equality of both corners.
    friend constexpr bool operator==(const Box3&, const Box3&) = default;
};

/// The smallest box holding a and b.
constexpr Box3 unite(const Box3& a, const Box3& b) {
    return {{std::min(a.lo.x, b.lo.x), std::min(a.lo.y, b.lo.y), std::min(a.lo.z, b.lo.z)},
            {std::max(a.hi.x, b.hi.x), std::max(a.hi.y, b.hi.y), std::max(a.hi.z, b.hi.z)}};
}

/// The smallest box holding every finite point; Box3::empty() when there is none.
inline Box3 bounding_box(std::span<const Vec3> points) {
    Box3 b = Box3::empty();
    for (const Vec3 p : points) {
        if (is_finite(p)) b = unite(b, {p, p});
    }
    return b;
}

/// Squared Euclidean distance from p to the box (zero inside).
constexpr double distance2(const Box3& b, Vec3 p) { return norm2(b.clamp(p) - p); }

/// Squared Euclidean distance between two boxes (zero when they overlap).
inline double distance2(const Box3& a, const Box3& b) {
    double d2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double gap = std::max({0.0, a.lo[i] - b.hi[i], b.lo[i] - a.hi[i]});
        d2 += gap * gap;
    }
    return d2;
}

/// The cube around the box with corners (x0, y0, z0) and (x1, y1, z1) given as six numbers: the
/// same centre, half-width the box's largest half-side (a domain, DESIGN §8). Throws InvalidInput
/// naming `name` ("--box", "box") unless there are six finite numbers with x0 < x1, y0 < y1 and
/// z0 < z1 within ±tolerance::max_coordinate.
Box3 cube_around_corners(std::span<const double> six, std::string_view name);

}  // namespace slc
