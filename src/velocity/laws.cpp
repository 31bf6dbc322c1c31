// The built-in velocity laws: rigid rotation and translation, the single vortex, constant and
// anisotropic normal speed (paper Eq. 12), curvature flow and its volume-preserving nonlocal form
// (paper Eq. 13).
#include "slc/velocity/laws.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"

namespace slc {
namespace {

/// Throws InvalidInput unless g holds what the law asked for at every vertex.
void require_geometry(const VelocityLaw& law, const Interface& curves, const VertexGeometry& g) {
    const bool curvature = law.needs().curvature;
    if (g.normals.size() != curves.size() || (curvature && g.curvature.size() != curves.size())) {
        throw InvalidInput(fmt::format(
            "velocity '{}' needs the {} at the vertices (vertex_velocities computes them)",
            law.name(), curvature ? "normals and curvature" : "normals"));
    }
}

/// u_i = v_i N_i for normal speeds v.
template <class Speed>
std::vector<Vec2> normal_velocities(const VelocityLaw& law, const Interface& curves,
                                    const VertexGeometry& g, Speed&& speed) {
    require_geometry(law, curves, g);
    std::vector<Vec2> u(g.normals.size());
    parallel_for(u.size(), [&](std::size_t i) { u[i] = speed(i) * g.normals[i]; });
    return u;
}

}  // namespace

void Rotation::sample(double, std::span<const Vec2> points, std::span<Vec2> out) const {
    parallel_for_cheap(points.size(),
                       [&](std::size_t i) { out[i] = omega_ * perp(points[i] - centre_); });
}

void Translation::sample(double, std::span<const Vec2> points, std::span<Vec2> out) const {
    std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(points.size()), u_);
}

SingleVortex::SingleVortex(double period) : period_(period) {
    if (!(period > 0.0) || !std::isfinite(period))
        throw InvalidInput(
            fmt::format("velocity 'vortex': period must be positive, got {}", period));
}

void SingleVortex::sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const {
    using std::numbers::pi;
    const double c = std::cos(pi * t / period_);
    parallel_for(points.size(), [&](std::size_t i) {
        const Vec2 x = points[i];
        const double sx = std::sin(pi * x.x), sy = std::sin(pi * x.y);
        out[i] = {sx * sx * std::sin(2 * pi * x.y) * c, -sy * sy * std::sin(2 * pi * x.x) * c};
    });
}

void NormalSpeed::normal_speeds(double, std::span<const Vec2> points, std::span<const Vec2>,
                                std::span<double> out) const {
    std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(points.size()), speed_);
}

void AnisotropicNormalSpeed::normal_speeds(double, std::span<const Vec2> points,
                                           std::span<const Vec2> normals,
                                           std::span<double> out) const {
    parallel_for(points.size(), [&](std::size_t i) {
        const double theta = std::atan2(normals[i].y, normals[i].x);
        out[i] = r_ + eps_ * std::cos(m_ * (theta - tilt_));
    });
}

std::vector<Vec2> CurvatureFlow::velocities(double, const Interface& curves,
                                            const VertexGeometry& g) const {
    return normal_velocities(*this, curves, g, [&](std::size_t i) { return g.curvature[i]; });
}

std::vector<Vec2> VolumePreservingCurvatureFlow::velocities(double, const Interface& curves,
                                                            const VertexGeometry& g) const {
    require_geometry(*this, curves, g);
    const double mean = arc_length_mean(curves, g.curvature);
    return normal_velocities(*this, curves, g,
                             [&](std::size_t i) { return g.curvature[i] - mean; });
}

}  // namespace slc
