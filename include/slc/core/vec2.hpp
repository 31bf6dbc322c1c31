/// @file
/// Vec2: a point or vector of the plane, and the few kernels on it that every module uses.
#pragma once

#include <cmath>

namespace slc {

/// A point or a vector in the plane, by value.
struct Vec2 {
    double x = 0.0;  ///< first coordinate
    double y = 0.0;  ///< second coordinate

    /// Adds o componentwise.
    constexpr Vec2& operator+=(Vec2 o) {
        x += o.x;
        y += o.y;
        return *this;
    }
    /// Subtracts o componentwise.
    constexpr Vec2& operator-=(Vec2 o) {
        x -= o.x;
        y -= o.y;
        return *this;
    }
    /// Scales both components by s.
    constexpr Vec2& operator*=(double s) {
        x *= s;
        y *= s;
        return *this;
    }
    /// Component i (0, 1 for x, y), for code written once over the dimension (Space<dim>).
    constexpr double operator[](int i) const { return i == 0 ? x : y; }
    /// Component i (0, 1), writable.
    constexpr double& operator[](int i) { return i == 0 ? x : y; }
    /// Exact equality of both components (no tolerance).
    friend constexpr bool operator==(Vec2, Vec2) = default;
};

/// The componentwise sum.
constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
/// The componentwise difference.
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
/// The opposite vector.
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
/// a scaled by s.
constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
/// a scaled by s.
constexpr Vec2 operator*(Vec2 a, double s) { return {s * a.x, s * a.y}; }
/// a divided by s (no check for s = 0).
constexpr Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }

/// The scalar product a · b.
constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// The z-component of a × b: positive when b lies counterclockwise of a.
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
/// The signed angle from direction a to direction b, in (−π, π]: positive counterclockwise.
inline double turn_angle(Vec2 a, Vec2 b) { return std::atan2(cross(a, b), dot(a, b)); }
/// a rotated a quarter turn counterclockwise, (x, y)^⊥ = (−y, x) as in the paper's §3.1.
constexpr Vec2 perp(Vec2 a) { return {-a.y, a.x}; }
/// The squared length |a|², without a square root.
constexpr double norm2(Vec2 a) { return dot(a, a); }
/// The length |a|, by std::hypot (no overflow or underflow in the squares).
inline double norm(Vec2 a) { return std::hypot(a.x, a.y); }
/// The Euclidean distance |a − b|.
inline double distance(Vec2 a, Vec2 b) { return norm(a - b); }
/// True when neither coordinate is NaN or infinite.
inline bool is_finite(Vec2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }

}  // namespace slc
