// Velocity laws: the default sample(), the geometry a law asks for, and the checks on what a law
// returns (a non-finite velocity names the law, the time and the vertex).
#include "slc/velocity/velocity.hpp"

#include <fmt/format.h>

#include <string>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/point_text.hpp"
#include "slc/geometry_modules/intrinsic.hpp"

namespace slc {
namespace {

/// Throws NumericalFailure at the first non-finite velocity, naming `what` (vertex or point).
template <int dim>
void check_finite(const BasicVelocityLaw<dim>& law, double t, std::span<const PointOf<dim>> at,
                  std::span<const PointOf<dim>> u, const char* what) {
    // On all threads: parallel_for_cheap throws what the least failing i threw.
    parallel_for_cheap(u.size(), [&](std::size_t i) {
        if (!is_finite(u[i])) {
            throw NumericalFailure(
                fmt::format("velocity '{}' is not finite at t = {}, {} {} {}: {}", law.name(), t,
                            what, i, point_text(at[i]), point_text(u[i])));
        }
    });
}

/// The vertex velocities of law on interface with geometry, checked.
template <int dim>
std::vector<PointOf<dim>> checked_velocities(const BasicVelocityLaw<dim>& law, double t,
                                             const ShapeOf<dim>& interface,
                                             const GeometryOf<dim>& geometry) {
    auto u = law.velocities(t, interface, geometry);
    const auto x = vertex_points(interface);
    if (u.size() != x.size()) {
        throw InvalidInput(
            fmt::format("velocity '{}' returned {} velocities for {} vertices at t = {}",
                        law.name(), u.size(), x.size(), t));
    }
    check_finite<dim>(law, t, x, u, "vertex");
    return u;
}

/// A flow field at points into out, checked.
template <int dim>
void checked_field(const BasicVelocityLaw<dim>& law, double t, std::span<const PointOf<dim>> points,
                   std::span<PointOf<dim>> out) {
    SLC_ASSERT(out.size() == points.size(), "one velocity a point");
    law.sample(t, points, out);
    check_finite<dim>(law, t, points, out, "point");
}

/// A flow field at points, checked.
template <int dim>
std::vector<PointOf<dim>> checked_field(const BasicVelocityLaw<dim>& law, double t,
                                        std::span<const PointOf<dim>> points) {
    std::vector<PointOf<dim>> u(points.size());
    checked_field<dim>(law, t, points, u);
    return u;
}

}  // namespace

template <int dim>
void BasicVelocityLaw<dim>::sample(double, std::span<const Point>, std::span<Point>) const {
    throw InvalidInput(
        fmt::format("velocity '{}' is defined only on the interface, not everywhere", name()));
}

template <int dim>
void BasicVelocityLaw<dim>::normal_speeds(double, std::span<const Point>, std::span<const Point>,
                                          std::span<double>) const {
    throw InvalidInput(fmt::format("velocity '{}' is not a normal speed law", name()));
}

template class BasicVelocityLaw<2>;
template class BasicVelocityLaw<3>;

template <int dim>
std::vector<PointOf<dim>> BasicNormalLaw<dim>::velocities(double t, const ShapeOf<dim>& interface,
                                                          const GeometryOf<dim>& geometry) const {
    const std::span<const PointOf<dim>> x = vertex_points(interface);
    if (geometry.normals.size() != x.size()) {
        throw InvalidInput(fmt::format(
            "velocity '{}' needs the normals at the vertices (vertex_velocities computes them)",
            this->name()));
    }
    std::vector<double> v(x.size());
    this->normal_speeds(t, x, geometry.normals, v);
    std::vector<PointOf<dim>> u(v.size());
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = v[i] * geometry.normals[i];
    return u;
}

template class BasicNormalLaw<2>;
template class BasicNormalLaw<3>;

std::optional<std::size_t> vertex_outside_extent(const VelocityLaw& law, const Interface& curves) {
    const std::optional<Box> extent = law.extent();
    if (!extent) return std::nullopt;
    for (std::size_t i = 0; i < curves.size(); ++i)
        if (!extent->contains(curves.point(i))) return i;
    return std::nullopt;
}

namespace {

template <int dim>
void require_forward(const std::string& what, std::span<const PointOf<dim>> x,
                     std::span<const double> slope) {
    constexpr double least_slope = -1e-6;
    for (std::size_t i = 0; i < slope.size(); ++i) {
        if (!(slope[i] < least_slope)) continue;
        throw InvalidInput(fmt::format(
            "{} falls as the curvature C grows (dv/dC = {:.3g} at {}): motion backward in "
            "curvature is ill-posed, its wiggles growing without bound; C = -1/R on a circle, so "
            "curvature flow is '+C' (as in 'a + C')",
            what, slope[i], point_text(x[i], 6)));
    }
}

}  // namespace

void require_forward_in_curvature(const std::string& what, std::span<const Vec2> x,
                                  std::span<const double> slope) {
    require_forward<2>(what, x, slope);
}

void require_forward_in_curvature(const std::string& what, std::span<const Vec3> x,
                                  std::span<const double> slope) {
    require_forward<3>(what, x, slope);
}

void require_inside_extent(const VelocityLaw& law, const Interface& curves) {
    const std::optional<std::size_t> i = vertex_outside_extent(law, curves);
    if (!i) return;
    const Box b = *law.extent();
    const Vec2 p = curves.point(*i);
    throw InvalidInput(fmt::format(
        "the initial curves leave the region where velocity '{}' is known, [{}, {}] x [{}, {}]: "
        "vertex {} at ({}, {})",
        law.name(), b.lo.x, b.hi.x, b.lo.y, b.hi.y, *i, p.x, p.y));
}

namespace {

/// The normals and curvature of needs' module, or nothing when the law needs neither.
VertexGeometry module_geometry(const GeometryNeeds& needs, const Interface& curves,
                               const GeometryContext& context) {
    if (!needs.any()) return {};
    const GeometryModule module = needs.resolved_module();
    if (module == GeometryModule::intrinsic) return intrinsic_geometry(curves);
    if (module == GeometryModule::arclength) return arclength_geometry(curves, context.arc_width);
    if (context.tree == nullptr)
        throw InvalidInput("the embedded geometry module needs a distance tree of the interface");
    if (&context.tree->curves() != &curves)
        throw InvalidInput(
            "the embedded geometry module was given a distance tree of other curves");
    return embedded_geometry(*context.tree, context.embedded);
}

}  // namespace

VertexGeometry vertex_geometry(const GeometryNeeds& needs, const Interface& curves,
                               const GeometryContext& context) {
    VertexGeometry g = module_geometry(needs, curves, context);
    g.step = context.step;
    return g;
}

std::vector<Vec2> vertex_velocities(const VelocityLaw& law, double t, const Interface& curves,
                                    const GeometryContext& context) {
    return checked_velocities<2>(law, t, curves, vertex_geometry(law.needs(), curves, context));
}

SurfaceGeometry vertex_geometry(const GeometryNeeds& needs, const Surface& surface,
                                SurfaceGeometryOptions options) {
    if (!needs.any()) return {};
    if (needs.module) {
        throw InvalidInput(
            "surfaces have one geometry module: leave the law's geometry module unset");
    }
    options.curvature = needs.curvature;
    return surface_geometry(surface, options);
}

std::vector<Vec3> vertex_velocities(const SurfaceVelocityLaw& law, double t, const Surface& surface,
                                    const SurfaceGeometryOptions& options) {
    return checked_velocities<3>(law, t, surface, vertex_geometry(law.needs(), surface, options));
}

std::vector<Vec3> vertex_velocities(const SurfaceVelocityLaw& law, double t, const Surface& surface,
                                    const SurfaceGeometry& geometry) {
    return checked_velocities<3>(law, t, surface, geometry);
}

std::vector<Vec2> field_velocities(const VelocityLaw& law, double t, std::span<const Vec2> points) {
    return checked_field<2>(law, t, points);
}

std::vector<Vec3> field_velocities(const SurfaceVelocityLaw& law, double t,
                                   std::span<const Vec3> points) {
    return checked_field<3>(law, t, points);
}

void field_velocities(const VelocityLaw& law, double t, std::span<const Vec2> points,
                      std::span<Vec2> out) {
    checked_field<2>(law, t, points, out);
}

void field_velocities(const SurfaceVelocityLaw& law, double t, std::span<const Vec3> points,
                      std::span<Vec3> out) {
    checked_field<3>(law, t, points, out);
}

}  // namespace slc
