// Velocity laws from Python: a built-in law by name, or a Python callable as a curve law (vertex
// velocities or normal speeds from points, normals and curvature), a normal law (speeds from
// points and normals, known off the curve) or a flow field (velocities from points).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "arrays.hpp"
#include "slc/velocity/factory.hpp"

namespace slc::python {

/// What the package passes for a law: velocity is a law's name (kind "builtin"), an expression
/// (kind "speed" or "field", as `slc run --speed` and `--field`), a file (kind "field-file"), or
/// a callable of kind "curve" f(t, points, normals, curvature), "normal" f(t, points, normals)
/// or "flow-field" f(t, points); name is what summary.json calls it.
struct LawSpec {
    py::object velocity;
    std::string kind;
    std::string name;
    VelocityParams params;
    std::optional<std::string> geometry;
    bool zero_outside = false;  ///< kind "field-file": zero outside the grid (zero_outside_extent)
};

/// The law spec describes; InvalidInput for an unknown built-in law, parameter or geometry, or
/// params given to a Python law.
std::unique_ptr<VelocityLaw> make_law(const LawSpec& spec);

/// The law of surfaces spec describes: a built-in law of surfaces by name, or a Python callable
/// with (m, 3) arrays; InvalidInput for an expression, a field file, a geometry module, an
/// unknown law or parameter, or params given to a Python law.
std::unique_ptr<SurfaceVelocityLaw> make_surface_law(const LawSpec& spec);

/// The geometry module named "intrinsic", "embedded" or "arclength"; InvalidInput otherwise.
GeometryModule geometry_module(const std::string& name);

}  // namespace slc::python
