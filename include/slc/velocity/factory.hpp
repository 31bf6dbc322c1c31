/// @file
/// The built-in velocity laws of curves and of surfaces by name, with their parameters by name, as
/// the command line gives them (`--velocity NAME --param key=value`, DESIGN §6) and Python lists
/// them: one catalog per dimension, from which --help, Python and the factories all read.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slc/velocity/velocity.hpp"

namespace slc {

/// Parameter values by name.
using VelocityParams = std::map<std::string, double>;

/// One parameter of a built-in law.
struct VelocityParameter {
    std::string name;                     ///< as in --param name=value
    std::optional<double> default_value;  ///< nothing when required or computed from others
    std::string default_text;             ///< the default as shown to a user: "1", "5/(m²−1)"
    std::string meaning;                  ///< one line for --help
    bool required = false;                ///< the law cannot be built without it
};

/// A built-in law: its name, what it does, and its parameters.
struct VelocityInfo {
    std::string name;                           ///< as in --velocity NAME
    std::string summary;                        ///< one line for --help
    std::vector<VelocityParameter> parameters;  ///< in the order --help lists them
};

/// Every built-in law, in a fixed order: rotation, translation, unit-normal, anisotropic,
/// curvature, volume-preserving-curvature, mullins-sekerka, hele-shaw, vortex.
const std::vector<VelocityInfo>& velocity_catalog();

/// The built-in law `name` with the given parameters (missing ones take their defaults).
///   rotation        omega [1], cx [0], cy [0]      u = ω(−(y − cy), x − cx)
///   translation     ux, uy (both required)         u = (ux, uy)
///   unit-normal     speed [1]                      u = speed·N
///   anisotropic     R [−1], m [4], eps [5/(m²−1)], tilt [0, degrees]
///                                                   u = (R + eps·cos(m(θ − tilt)))·N
///   curvature                                      u = C·N
///   volume-preserving-curvature                    u = (C − C̄)·N
///   mullins-sekerka sigma [1], din [1], dout [1]   V = flux jump of u, Δu = 0 off Γ, u = −σC
///   hele-shaw       sigma [1], q [0], sx, sy [0]   V = −∂p/∂N, Δp = 0 inside, p = −σC
///   vortex          period [8]                     LeVeque's single vortex on [0, 1]²
/// module, when given, replaces the geometry module of the laws that need normals or curvature.
/// Throws InvalidInput for an unknown law ("unknown velocity 'x'; known: rotation, ..."), an
/// unknown parameter name (the message lists the law's parameters), a missing required or a
/// non-finite value, a period <= 0, or eps left to its default with m² = 1.
std::unique_ptr<VelocityLaw> make_velocity(const std::string& name,
                                           const VelocityParams& params = {},
                                           std::optional<GeometryModule> module = std::nullopt);

/// Every built-in law of surfaces, in a fixed order: rotation, translation, enright, unit-normal,
/// anisotropic, curvature, volume-preserving-curvature.
const std::vector<VelocityInfo>& surface_velocity_catalog();

/// The built-in law of surfaces `name` with the given parameters (missing ones take defaults):
///   rotation        omega [1], ax [0], ay [0], az [1], cx, cy, cz [0]   u = ω a × (x − c)
///   translation     ux, uy, uz (required)                              u = (ux, uy, uz)
///   enright         period [3]                                          Enright's field
///   unit-normal     speed [1]                                           u = speed·N
///   anisotropic     R [1], eps [0.5]                     u = (R + eps (Σ n_i⁴ − 3/5))·N
///   curvature                                                           u = C·N
///   volume-preserving-curvature                                         u = (C − C̄)·N
/// Throws InvalidInput as make_velocity does ("unknown velocity 'x' for a surface; known: ...").
std::unique_ptr<SurfaceVelocityLaw> make_surface_velocity(const std::string& name,
                                                          const VelocityParams& params = {});

}  // namespace slc
