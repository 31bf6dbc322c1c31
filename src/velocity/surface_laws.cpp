// The built-in velocity laws of surfaces: rotation about an axis, Enright's deformation field, and
// constant and anisotropic normal speed (translation and the curvature flows are in laws.cpp).
#include "slc/velocity/surface_laws.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"

namespace slc {

SurfaceRotation::SurfaceRotation(double omega, Vec3 axis, Vec3 centre)
    : omega_(omega), centre_(centre) {
    const double length = norm(axis);
    if (!(length > 0.0) || !std::isfinite(length))
        throw InvalidInput(fmt::format(
            "velocity 'rotation': the axis ({}, {}, {}) has no direction", axis.x, axis.y, axis.z));
    axis_ = axis / length;
}

void SurfaceRotation::sample(double, std::span<const Vec3> points, std::span<Vec3> out) const {
    parallel_for_cheap(points.size(),
                       [&](std::size_t i) { out[i] = omega_ * cross(axis_, points[i] - centre_); });
}

void EnrightField::sample(double t, std::span<const Vec3> points, std::span<Vec3> out) const {
    using std::numbers::pi;
    const double c = reversal(t);
    parallel_for(points.size(), [&](std::size_t i) {
        // sin 2a = 2 sin a cos a: three sine–cosine pairs (one sincos call each) for six sines.
        const Vec3 x = points[i];
        const double sx = std::sin(pi * x.x), sy = std::sin(pi * x.y), sz = std::sin(pi * x.z);
        const double s2x = 2.0 * sx * std::cos(pi * x.x), s2y = 2.0 * sy * std::cos(pi * x.y),
                     s2z = 2.0 * sz * std::cos(pi * x.z);
        out[i] = c * Vec3{2.0 * sx * sx * s2y * s2z, -s2x * sy * sy * s2z, -s2x * s2y * sz * sz};
    });
}

void SurfaceAnisotropicNormalSpeed::normal_speeds(double, std::span<const Vec3> points,
                                                  std::span<const Vec3> normals,
                                                  std::span<double> out) const {
    parallel_for_cheap(points.size(), [&](std::size_t i) {
        const Vec3 n = normals[i];
        const double quartic =
            n.x * n.x * n.x * n.x + n.y * n.y * n.y * n.y + n.z * n.z * n.z * n.z;
        out[i] = r_ + eps_ * (quartic - 0.6);
    });
}

}  // namespace slc
