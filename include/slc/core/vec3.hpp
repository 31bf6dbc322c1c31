/// @file
/// Vec3: a point or vector of space, and the few kernels on it that the surface modules use
/// (DESIGN §8). The 3D counterpart of Vec2.
#pragma once

#include <cmath>

namespace slc {

/// A point or a vector in space, by value.
struct Vec3 {
    double x = 0.0;  ///< first coordinate
    double y = 0.0;  ///< second coordinate
    double z = 0.0;  ///< third coordinate

    /// Adds o componentwise.
    constexpr Vec3& operator+=(Vec3 o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    /// Subtracts o componentwise.
    constexpr Vec3& operator-=(Vec3 o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    /// Scales every component by s.
    constexpr Vec3& operator*=(double s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    /// Component i (0, 1, 2 for x, y, z).
    constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    /// Component i (0, 1, 2), writable.
    constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    /// Exact equality of all components (no tolerance).
    friend constexpr bool operator==(Vec3, Vec3) = default;
};

/// The componentwise sum.
constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
/// The componentwise difference.
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
/// The opposite vector.
constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
/// a scaled by s.
constexpr Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
/// a scaled by s.
constexpr Vec3 operator*(Vec3 a, double s) { return s * a; }
/// a divided by s (no check for s = 0).
constexpr Vec3 operator/(Vec3 a, double s) { return {a.x / s, a.y / s, a.z / s}; }

/// The scalar product a · b.
constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
/// The vector product a × b.
constexpr Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// The squared length |a|², without a square root.
constexpr double norm2(Vec3 a) { return dot(a, a); }
/// The length |a|, by std::hypot (no overflow or underflow in the squares).
inline double norm(Vec3 a) { return std::hypot(a.x, a.y, a.z); }
/// The Euclidean distance |a − b|.
inline double distance(Vec3 a, Vec3 b) { return norm(a - b); }
/// True when no coordinate is NaN or infinite.
inline bool is_finite(Vec3 a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

}  // namespace slc
