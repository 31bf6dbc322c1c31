// The built-in velocity laws by name, of curves and of surfaces: the catalogs of names and
// parameters, and make_velocity / make_surface_velocity, which check the parameters (one code for
// both) and build the law.
#include "slc/velocity/factory.hpp"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/velocity/laws.hpp"
#include "slc/velocity/potential_laws.hpp"
#include "slc/velocity/surface_laws.hpp"

namespace slc {
namespace {

/// Parameter values after defaults, and which ones the user gave.
struct Resolved {
    VelocityParams values;
    double operator[](const std::string& key) const { return values.at(key); }
    bool has(const std::string& key) const { return values.count(key) != 0; }
};

/// A law of dimension dim by name: what --help and Python list, and how it is built.
template <int dim>
struct Entry {
    VelocityInfo info;
    std::function<std::unique_ptr<BasicVelocityLaw<dim>>(const Resolved&,
                                                         std::optional<GeometryModule>)>
        build;
};

VelocityParameter param(std::string name, double value, std::string meaning) {
    return {std::move(name), value, fmt::format("{}", value), std::move(meaning), false};
}

/// A parameter without a default, which the user must give.
VelocityParameter required(std::string name, std::string meaning) {
    return {std::move(name), std::nullopt, "required", std::move(meaning), true};
}

std::unique_ptr<VelocityLaw> make_anisotropic(const Resolved& p,
                                              std::optional<GeometryModule> module) {
    const double m = p["m"];
    if (!p.has("eps") && m * m == 1.0) {
        throw InvalidInput(fmt::format(
            "velocity 'anisotropic': the default eps = 5/(m²−1) is undefined for m = {}; give eps",
            m));
    }
    const double eps = p.has("eps") ? p["eps"] : 5.0 / (m * m - 1.0);
    return std::make_unique<AnisotropicNormalSpeed>(p["R"], m, eps,
                                                    p["tilt"] * std::numbers::pi / 180.0, module);
}

const std::vector<Entry<2>>& curve_entries() {
    using M = std::optional<GeometryModule>;
    static const std::vector<Entry<2>> table = {
        {{"rotation",
          "rigid counterclockwise rotation u = omega (-(y - cy), x - cx)",
          {param("omega", 1, "angular velocity"), param("cx", 0, "x of the centre"),
           param("cy", 0, "y of the centre")}},
         [](const Resolved& p, M) {
             return std::make_unique<Rotation>(p["omega"], Vec2{p["cx"], p["cy"]});
         }},
        {{"translation",
          "constant velocity u = (ux, uy)",
          {required("ux", "x velocity"), required("uy", "y velocity")}},
         [](const Resolved& p, M) {
             return std::make_unique<Translation>(Vec2{p["ux"], p["uy"]});
         }},
        {{"unit-normal",
          "constant normal speed u = speed N (positive grows)",
          {param("speed", 1, "normal speed, either sign")}},
         [](const Resolved& p, M m) { return std::make_unique<NormalSpeed>(p["speed"], m); }},
        {{"anisotropic",
          "anisotropic normal speed u = (R + eps cos(m (theta - tilt))) N",
          {param("R", -1, "isotropic part of the normal speed"),
           param("m", 4, "number of facets"),
           {"eps", std::nullopt, "5/(m²−1)", "amplitude of the anisotropy", false},
           param("tilt", 0, "turn of the anisotropy's axes, degrees")}},
         make_anisotropic},
        {{"curvature", "motion by curvature u = C N (shrinks circles)", {}},
         [](const Resolved&, M m) { return std::make_unique<CurvatureFlow>(m); }},
        {{"volume-preserving-curvature", "nonlocal u = (C - mean of C over all of Gamma) N", {}},
         [](const Resolved&, M m) { return std::make_unique<VolumePreservingCurvatureFlow>(m); }},
        {{"mullins-sekerka",
          "two-phase Mullins-Sekerka: V = jump of the flux of u, u harmonic off Gamma, u = -sigma "
          "C on it (coarsening; keeps the total area)",
          {param("sigma", 1, "surface tension"), param("din", 1, "diffusion coefficient inside"),
           param("dout", 1, "diffusion coefficient outside")}},
         [](const Resolved& p, M) {
             return std::make_unique<MullinsSekerka>(p["sigma"], p["din"], p["dout"]);
         }},
        {{"hele-shaw",
          "one-phase Hele-Shaw: V = -dp/dN, p harmonic inside each region, p = -sigma C on its "
          "curves (each region keeps its area; q > 0 injects at (sx, sy))",
          {param("sigma", 1, "surface tension"), param("q", 0, "injection rate, area per time"),
           param("sx", 0, "x of the source"), param("sy", 0, "y of the source")}},
         [](const Resolved& p, M) {
             return std::make_unique<HeleShaw>(p["sigma"], p["q"], Vec2{p["sx"], p["sy"]});
         }},
        {{"vortex",
          "LeVeque's single vortex on [0, 1]^2, reversed at t = period/2",
          {param("period", 8, "period T: the flow is multiplied by cos(pi t / T)")}},
         [](const Resolved& p, M) { return std::make_unique<SingleVortex>(p["period"]); }},
    };
    return table;
}

const std::vector<Entry<3>>& surface_entries() {
    using M = std::optional<GeometryModule>;
    static const std::vector<Entry<3>> table = {
        {{"rotation",
          "rigid rotation u = omega a x (x - c) about the axis a through c",
          {param("omega", 1, "angular velocity"), param("ax", 0, "x of the axis"),
           param("ay", 0, "y of the axis"), param("az", 1, "z of the axis"),
           param("cx", 0, "x of a point on the axis"), param("cy", 0, "y of that point"),
           param("cz", 0, "z of that point")}},
         [](const Resolved& p, M) {
             return std::make_unique<SurfaceRotation>(p["omega"], Vec3{p["ax"], p["ay"], p["az"]},
                                                      Vec3{p["cx"], p["cy"], p["cz"]});
         }},
        {{"translation",
          "constant velocity u = (ux, uy, uz)",
          {required("ux", "x velocity"), required("uy", "y velocity"),
           required("uz", "z velocity")}},
         [](const Resolved& p, M) {
             return std::make_unique<SurfaceTranslation>(Vec3{p["ux"], p["uy"], p["uz"]});
         }},
        {{"enright",
          "Enright's deformation field on the unit cube, reversed at t = period/2",
          {param("period", 3, "period T: the flow is multiplied by cos(pi t / T)")}},
         [](const Resolved& p, M) { return std::make_unique<EnrightField>(p["period"]); }},
        {{"unit-normal",
          "constant normal speed u = speed N (positive grows)",
          {param("speed", 1, "normal speed, either sign")}},
         [](const Resolved& p, M) { return std::make_unique<SurfaceNormalSpeed>(p["speed"]); }},
        {{"anisotropic",
          "anisotropic normal speed u = (R + eps (nx^4 + ny^4 + nz^4 - 3/5)) N",
          {param("R", 1, "isotropic part of the normal speed"),
           param("eps", 0.5, "amplitude of the anisotropy")}},
         [](const Resolved& p, M) {
             return std::make_unique<SurfaceAnisotropicNormalSpeed>(p["R"], p["eps"]);
         }},
        {{"curvature", "mean curvature flow u = C N (spheres: R^2 = R0^2 - 4t)", {}},
         [](const Resolved&, M) { return std::make_unique<SurfaceMeanCurvatureFlow>(); }},
        {{"volume-preserving-curvature", "nonlocal u = (C - mean of C over the surface) N", {}},
         [](const Resolved&, M) { return std::make_unique<SurfaceVolumePreservingFlow>(); }},
    };
    return table;
}

std::string joined_names(const std::vector<VelocityParameter>& params) {
    std::string s;
    for (const auto& p : params) s += (s.empty() ? "" : ", ") + p.name;
    return s.empty() ? "none" : s;
}

/// The user's values checked against the law's parameters, with defaults filled in.
Resolved resolve(const VelocityInfo& info, const VelocityParams& given) {
    Resolved r;
    for (const auto& [key, value] : given) {
        bool known = false;
        for (const auto& p : info.parameters) known = known || p.name == key;
        if (!known) {
            throw InvalidInput(
                fmt::format("velocity '{}' has no parameter '{}'; its parameters: {}", info.name,
                            key, joined_names(info.parameters)));
        }
        if (!std::isfinite(value))
            throw InvalidInput(fmt::format("velocity '{}': parameter {} must be finite, got {}",
                                           info.name, key, value));
        r.values[key] = value;
    }
    for (const auto& p : info.parameters) {
        if (r.has(p.name)) continue;
        if (p.default_value) {
            r.values[p.name] = *p.default_value;
        } else if (p.required) {
            throw InvalidInput(fmt::format("velocity '{}' needs parameter {} (its parameters: {})",
                                           info.name, p.name, joined_names(info.parameters)));
        }
    }
    return r;
}

/// The infos of a table, in its order.
template <int dim>
std::vector<VelocityInfo> catalog_of(const std::vector<Entry<dim>>& table) {
    std::vector<VelocityInfo> c;
    for (const Entry<dim>& e : table) c.push_back(e.info);
    return c;
}

/// The law `name` of table, built from params; `of` follows the name in the message of an
/// unknown law ("" or " for a surface").
template <int dim>
std::unique_ptr<BasicVelocityLaw<dim>> make_from(const std::vector<Entry<dim>>& table,
                                                 const std::string& name,
                                                 const VelocityParams& params,
                                                 std::optional<GeometryModule> module,
                                                 const char* of) {
    std::string known;
    for (const Entry<dim>& e : table) {
        if (e.info.name == name) return e.build(resolve(e.info, params), module);
        known += (known.empty() ? "" : ", ") + e.info.name;
    }
    throw InvalidInput(fmt::format("unknown velocity '{}'{}; known: {}", name, of, known));
}

}  // namespace

const std::vector<VelocityInfo>& velocity_catalog() {
    static const std::vector<VelocityInfo> catalog = catalog_of(curve_entries());
    return catalog;
}

const std::vector<VelocityInfo>& surface_velocity_catalog() {
    static const std::vector<VelocityInfo> catalog = catalog_of(surface_entries());
    return catalog;
}

std::unique_ptr<VelocityLaw> make_velocity(const std::string& name, const VelocityParams& params,
                                           std::optional<GeometryModule> module) {
    return make_from(curve_entries(), name, params, module, "");
}

std::unique_ptr<SurfaceVelocityLaw> make_surface_velocity(const std::string& name,
                                                          const VelocityParams& params) {
    return make_from(surface_entries(), name, params, std::nullopt, " for a surface");
}

}  // namespace slc
