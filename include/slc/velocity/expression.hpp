/// @file
/// Velocity laws typed as text (`slc run --speed EXPR`, `--field EXPR,EXPR`): a normal speed
/// v(x, y, t, C, nx, ny) or a flow field (u, v)(x, y, t) moving curves, and v(x, y, z, t, C, nx,
/// ny, nz) or (u, v, w)(x, y, z, t) moving surfaces, parsed and evaluated by muparser.
/// A speed without C is a normal law (NormalLaw: the step may evaluate it off the curve with the
/// distance field's normal); a speed with C asks for the curvature at the vertices (GeometryNeeds)
/// and is extended from them; a field is sampled along characteristics like the built-in flows.
///
/// The expressions are muparser's: + − * / ^, comparisons, `c ? a : b`, sin cos tan asin acos
/// atan sinh cosh tanh asinh acosh atanh log2 log10 log ln exp sqrt sign rint abs min max sum avg,
/// the constants _pi and _e, and named constants of the caller's (`--param a=0.5`).
///
/// Evaluation is safe from any thread and its values do not depend on the thread count: each
/// call splits its batch among worker threads, each with a parser of its own (a muparser parser
/// holds mutable state), kept between calls.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "slc/velocity/factory.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc {

/// The variables of a normal speed expression, in this order: the point (x, y), the time t, the
/// curvature C = −∇·N (−1/R on a circle of radius R, so "C" is curvature flow and "-C" grows
/// circles), and the outward unit normal (nx, ny).
inline constexpr std::array<std::string_view, 6> speed_variables = {"x", "y", "t", "C", "nx", "ny"};
/// The variables of a flow field expression: the point (x, y) and the time t.
inline constexpr std::array<std::string_view, 3> field_variables = {"x", "y", "t"};
/// The variables of a normal speed expression on surfaces: the point (x, y, z), the time t, the
/// mean curvature C = −∇·N (−2/R on a sphere of radius R, so "C" is mean curvature flow), and
/// the outward unit normal (nx, ny, nz).
inline constexpr std::array<std::string_view, 8> surface_speed_variables = {"x", "y",  "z",  "t",
                                                                            "C", "nx", "ny", "nz"};
/// The variables of a flow field expression in space: the point (x, y, z) and the time t.
inline constexpr std::array<std::string_view, 4> surface_field_variables = {"x", "y", "z", "t"};

/// The normal speed law u = v·N, v > 0 moving the curve outward, with v given by expression in
/// the variables speed_variables and the named constants (each name a muparser identifier,
/// [A-Za-z_][A-Za-z0-9_]*, not a variable nor a function; values finite). Without C it is a
/// NormalLaw whose vertex normals come from module (the intrinsic module by default); with C,
/// normals and curvature both come from module (the arclength module by default), and the law
/// asks for them (GeometryNeeds::curvature), so that the defaults pick the curvature settings.
/// Its name() is "speed = expression". Throws InvalidInput with one line naming the expression
/// and what is wrong: empty, a syntax error, an unknown name, more than one value ("1, 2"), or
/// a bad constant. A value that is not finite during a run is a NumericalFailure (from the
/// checks of vertex_velocities and the step). Cost: about one muparser evaluation (tens of ns
/// for short expressions) per point.
std::unique_ptr<VelocityLaw> speed_expression_law(
    const std::string& expression, const VelocityParams& constants = {},
    std::optional<GeometryModule> module = std::nullopt);

/// The flow field (u, v) given by expression "U, V": two muparser expressions separated by a
/// top-level comma, in the variables field_variables and the named constants (as
/// speed_expression_law). A field law (VelocityLaw::is_field), sampled at any point. Its name()
/// is "field = (U, V)". Throws InvalidInput as speed_expression_law does, and when expression
/// gives other than two values ("x": one component).
std::unique_ptr<VelocityLaw> field_expression_law(const std::string& expression,
                                                  const VelocityParams& constants = {});

/// The normal speed law of surfaces u = v·N with v given by expression in the variables
/// surface_speed_variables and the named constants (as speed_expression_law). Without C it is a
/// SurfaceNormalLaw, which the step evaluates off the surface with the distance field's normal;
/// with C it asks for the normals and mean curvature at the vertices (GeometryNeeds) and is
/// extended from them. Its name() is "speed = expression". Throws InvalidInput as
/// speed_expression_law does.
std::unique_ptr<SurfaceVelocityLaw> surface_speed_expression_law(
    const std::string& expression, const VelocityParams& constants = {});

/// The flow field (u, v, w) in space given by expression "U, V, W" (three muparser expressions
/// separated by top-level commas) in the variables surface_field_variables and the named
/// constants. A field law sampled at any point; its name() is "field = (U, V, W)". Throws
/// InvalidInput as field_expression_law does, and when expression gives other than three values.
std::unique_ptr<SurfaceVelocityLaw> surface_field_expression_law(
    const std::string& expression, const VelocityParams& constants = {});

}  // namespace slc
