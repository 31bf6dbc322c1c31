// The built-in velocity laws: rigid rotation, the single vortex, constant and anisotropic normal
// speed (paper Eq. 12), and curvature flow and its volume-preserving nonlocal form (paper Eq. 13)
// for curves and surfaces alike.
#include "slc/velocity/laws.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"

namespace slc {
namespace {

/// u_i = v_i N_i for normal speeds v.
template <class Point, class Geometry, class Speed>
std::vector<Point> normal_velocities(const Geometry& g, Speed&& speed) {
    std::vector<Point> u(g.normals.size());
    parallel_for(u.size(), [&](std::size_t i) { u[i] = speed(i) * g.normals[i]; });
    return u;
}

/// The mean of g over the interface: by arc length along curves, by area over a surface.
double interface_mean(const Interface& curves, std::span<const double> g) {
    return arc_length_mean(curves, g);
}
double interface_mean(const Surface& surface, std::span<const double> g) {
    return area_mean(surface, g);
}

}  // namespace

void Rotation::sample(double, std::span<const Vec2> points, std::span<Vec2> out) const {
    parallel_for_cheap(points.size(),
                       [&](std::size_t i) { out[i] = omega_ * perp(points[i] - centre_); });
}

template <int dim>
BasicReversingFlow<dim>::BasicReversingFlow(const char* law, double period) : period_(period) {
    if (!(period > 0.0) || !std::isfinite(period))
        throw InvalidInput(
            fmt::format("velocity '{}': period must be positive, got {}", law, period));
}

template class BasicReversingFlow<2>;
template class BasicReversingFlow<3>;

void SingleVortex::sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const {
    using std::numbers::pi;
    const double c = reversal(t);
    parallel_for(points.size(), [&](std::size_t i) {
        const Vec2 x = points[i];
        const double sx = std::sin(pi * x.x), sy = std::sin(pi * x.y);
        out[i] = {sx * sx * std::sin(2 * pi * x.y) * c, -sy * sy * std::sin(2 * pi * x.x) * c};
    });
}

void AnisotropicNormalSpeed::normal_speeds(double, std::span<const Vec2> points,
                                           std::span<const Vec2> normals,
                                           std::span<double> out) const {
    parallel_for(points.size(), [&](std::size_t i) {
        const double theta = std::atan2(normals[i].y, normals[i].x);
        out[i] = r_ + eps_ * std::cos(m_ * (theta - tilt_));
    });
}

template <int dim>
void BasicCurvatureLaw<dim>::require_geometry(const ShapeOf<dim>& interface,
                                              const GeometryOf<dim>& geometry) const {
    const std::size_t n = vertex_points(interface).size();
    if (geometry.normals.size() != n || geometry.curvature.size() != n) {
        throw InvalidInput(
            fmt::format("velocity '{}' needs the normals and curvature at the "
                        "vertices (vertex_velocities computes them)",
                        this->name()));
    }
}

template <int dim>
std::vector<PointOf<dim>> BasicCurvatureFlow<dim>::velocities(double, const ShapeOf<dim>& interface,
                                                              const GeometryOf<dim>& g) const {
    this->require_geometry(interface, g);
    return normal_velocities<PointOf<dim>>(g, [&](std::size_t i) { return g.curvature[i]; });
}

template <int dim>
std::vector<PointOf<dim>> BasicVolumePreservingFlow<dim>::velocities(
    double, const ShapeOf<dim>& interface, const GeometryOf<dim>& g) const {
    this->require_geometry(interface, g);
    const double mean = interface_mean(interface, g.curvature);
    return normal_velocities<PointOf<dim>>(g, [&](std::size_t i) { return g.curvature[i] - mean; });
}

template class BasicCurvatureLaw<2>;
template class BasicCurvatureLaw<3>;
template class BasicCurvatureFlow<2>;
template class BasicCurvatureFlow<3>;
template class BasicVolumePreservingFlow<2>;
template class BasicVolumePreservingFlow<3>;

}  // namespace slc
