// Velocity laws: the default sample(), the geometry a law asks for, and the checks on what a law
// returns (a non-finite velocity names the law, the time and the vertex).
#include "slc/velocity/velocity.hpp"

#include <fmt/format.h>

#include "slc/core/error.hpp"
#include "slc/geometry_modules/intrinsic.hpp"

namespace slc {
namespace {

/// Throws NumericalFailure at the first non-finite velocity, naming `what` (vertex or point).
void check_finite(const VelocityLaw& law, double t, std::span<const Vec2> at,
                  std::span<const Vec2> u, const char* what) {
    for (std::size_t i = 0; i < u.size(); ++i) {
        if (!is_finite(u[i])) {
            throw NumericalFailure(
                fmt::format("velocity '{}' is not finite at t = {}, {} {} ({}, {}): ({}, {})",
                            law.name(), t, what, i, at[i].x, at[i].y, u[i].x, u[i].y));
        }
    }
}

}  // namespace

void VelocityLaw::sample(double, std::span<const Vec2>, std::span<Vec2>) const {
    throw InvalidInput(
        fmt::format("velocity '{}' is defined only on the interface, not everywhere", name()));
}

void VelocityLaw::normal_speeds(double, std::span<const Vec2>, std::span<const Vec2>,
                                std::span<double>) const {
    throw InvalidInput(fmt::format("velocity '{}' is not a normal speed law", name()));
}

std::optional<std::size_t> vertex_outside_extent(const VelocityLaw& law, const Interface& curves) {
    const std::optional<Box> extent = law.extent();
    if (!extent) return std::nullopt;
    for (std::size_t i = 0; i < curves.size(); ++i)
        if (!extent->contains(curves.point(i))) return i;
    return std::nullopt;
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

std::vector<Vec2> FlowFieldLaw::velocities(double t, const Interface& curves,
                                           const VertexGeometry&) const {
    std::vector<Vec2> u(curves.size());
    sample(t, curves.points(), u);
    return u;
}

std::vector<Vec2> NormalLaw::velocities(double t, const Interface& curves,
                                        const VertexGeometry& geometry) const {
    if (geometry.normals.size() != curves.size()) {
        throw InvalidInput(fmt::format(
            "velocity '{}' needs the normals at the vertices (vertex_velocities computes them)",
            name()));
    }
    std::vector<double> v(curves.size());
    normal_speeds(t, curves.points(), geometry.normals, v);
    std::vector<Vec2> u(v.size());
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = v[i] * geometry.normals[i];
    return u;
}

VertexGeometry vertex_geometry(const GeometryNeeds& needs, const Interface& curves,
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

std::vector<Vec2> vertex_velocities(const VelocityLaw& law, double t, const Interface& curves,
                                    const GeometryContext& context) {
    const VertexGeometry geometry = vertex_geometry(law.needs(), curves, context);
    std::vector<Vec2> u = law.velocities(t, curves, geometry);
    if (u.size() != curves.size()) {
        throw InvalidInput(
            fmt::format("velocity '{}' returned {} velocities for {} vertices at t = {}",
                        law.name(), u.size(), curves.size(), t));
    }
    check_finite(law, t, curves.points(), u, "vertex");
    return u;
}

std::vector<Vec2> field_velocities(const VelocityLaw& law, double t, std::span<const Vec2> points) {
    std::vector<Vec2> u(points.size());
    law.sample(t, points, u);
    check_finite(law, t, points, u, "point");
    return u;
}

}  // namespace slc
