// The named problems of moving surfaces and the built-in laws of surfaces by name.
#include "slc/evolve/surface_problems.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "slc/contour/surface_contour.hpp"
#include "slc/core/error.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/geometry/balls.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/velocity/surface_laws.hpp"
#include "user_defaults.hpp"

namespace slc {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// The parameters a law or problem takes, with their defaults (NaN: required).
using Defaults = std::vector<std::pair<std::string, double>>;

/// params completed with defaults; InvalidInput for an unknown key, a missing required one or a
/// non-finite value, naming `what`.
VelocityParams resolve(const std::string& what, const Defaults& defaults,
                       const VelocityParams& params) {
    VelocityParams out;
    for (const auto& [key, value] : params) {
        const bool known = std::any_of(defaults.begin(), defaults.end(),
                                       [&key = key](const auto& d) { return d.first == key; });
        if (!known) {
            std::string names;
            for (const auto& d : defaults) names += (names.empty() ? "" : ", ") + d.first;
            throw InvalidInput(fmt::format(
                "{} has no parameter '{}'{}", what, key,
                names.empty() ? std::string("; it takes none") : "; it takes " + names));
        }
        if (!std::isfinite(value))
            throw InvalidInput(fmt::format("{}: parameter {} must be finite", what, key));
    }
    for (const auto& [key, value] : defaults) {
        const auto given = params.find(key);
        if (given != params.end()) {
            out[key] = given->second;
        } else if (std::isnan(value)) {
            throw InvalidInput(fmt::format("{} needs --param {}=VALUE", what, key));
        } else {
            out[key] = value;
        }
    }
    return out;
}

/// The exact signed distance to the box [lo, hi].
double box_distance(Vec3 x, Vec3 lo, Vec3 hi) {
    const Vec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    const Vec3 q{std::abs(x.x - c.x) - h.x, std::abs(x.y - c.y) - h.y, std::abs(x.z - c.z) - h.z};
    const Vec3 outside{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
    return norm(outside) + std::min(std::max({q.x, q.y, q.z}), 0.0);
}

/// x turned by angle about the axis a (unit) through c (Rodrigues).
Vec3 rotated(Vec3 x, Vec3 a, Vec3 c, double angle) {
    const Vec3 v = x - c;
    return c + std::cos(angle) * v + std::sin(angle) * cross(a, v) +
           (1.0 - std::cos(angle)) * dot(a, v) * a;
}

const Box3 centred_cube{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}};
const Box3 unit_cube{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};

}  // namespace

/// The problems and their one-line summaries, in the order --help lists them.
const std::vector<std::pair<std::string, std::string>>& surface_catalog() {
    static const std::vector<std::pair<std::string, std::string>> table = {
        {"sphere-rotation", "a sphere of radius 0.25 turned once about the z axis"},
        {"enright",
         "Enright's test: a sphere of radius 0.15 stretched by LeVeque's field, back at t = 3"},
        {"zalesak-sphere", "Enright's slotted sphere turned once about the axis x = y = 0.5"},
        {"sphere-curvature", "a sphere of radius 0.5 under mean curvature flow, R^2 = 0.25 - 4t"},
        {"merging-spheres",
         "two spheres of radius 0.25, 0.1 apart, growing at unit speed until they merge"},
        {"box-normal",
         "a box at constant normal speed (--param speed, default 1): growing edges round off, "
         "shrinking ones stay sharp"},
        {"peanut-volume", "two overlapping spheres under volume-preserving mean curvature flow"}};
    return table;
}

const std::vector<std::string>& surface_problem_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const auto& entry : surface_catalog()) out.push_back(entry.first);
        return out;
    }();
    return names;
}

std::string surface_problem_summary(const std::string& name) {
    for (const auto& [n, summary] : surface_catalog())
        if (n == name) return summary;
    return {};
}

bool is_surface_problem(const std::string& name) {
    const auto& names = surface_problem_names();
    return std::find(names.begin(), names.end(), name) != names.end();
}

SurfaceProblem make_surface_problem(const std::string& name, const VelocityParams& params) {
    using std::numbers::pi;
    SurfaceProblem p;
    p.name = name;
    p.description = surface_problem_summary(name);
    const std::string what = fmt::format("problem '{}'", name);
    if (name == "sphere-rotation") {
        resolve(what, {}, params);
        const Vec3 c0{0.4, 0.0, 0.1};
        const double r = 0.25;
        p.domain = centred_cube;
        p.t_end = 2.0 * pi;
        p.steps = 32;
        p.study = SurfaceStudyPlan{.steps = 16, .depth = 5, .eps = 4e-4};
        p.law = std::make_unique<SurfaceRotation>();
        p.exact = [c0, r](double t, Vec3 x) {
            return distance(x, rotated(c0, {0.0, 0.0, 1.0}, {}, t)) - r;
        };
    } else if (name == "enright") {
        resolve(what, {}, params);
        const Vec3 c{0.35, 0.35, 0.35};
        p.domain = unit_cube;
        p.t_end = 3.0;
        // The sheet thins below a cell of K = 7 by t = 1.5; thin cells two levels deep keep it
        // whole (at K = 6 too, farther from the sphere at the end). The feet are traced to ε/10
        // at any step, so a step's error is its contour's: eight steps at ε = 2.5e−5 come back
        // with the volume within 0.001% and the shape within 0.02% of the sphere's in under two
        // minutes on two cores, where thirty at 1e−4 are off by 0.0022% and 0.028% in 157 s
        // (docs/tables/enright.md).
        p.steps = 8;
        p.depth = 7;
        p.eps = 2.5e-5;
        p.thin_depth = 2;
        p.law = std::make_unique<EnrightField>(3.0);
        p.exact = [c](double t, Vec3 x) {
            return std::abs(std::remainder(t, 3.0)) < 1e-12 ? distance(x, c) - 0.15 : nan;
        };
    } else if (name == "zalesak-sphere") {
        resolve(what, {}, params);
        p.domain = unit_cube;
        p.t_end = 1.0;
        p.steps = 20;
        p.depth = 6;
        p.law =
            std::make_unique<SurfaceRotation>(2.0 * pi, Vec3{0.0, 0.0, 1.0}, Vec3{0.5, 0.5, 0.5});
        p.azimuth = -90.0;  // from the axis's side, into the slot
        // A sphere of radius 0.15 about (0.5, 0.75, 0.5) less a slot 0.05 wide cut 0.125 deep
        // from its bottom (towards the axis), through all of it in z.
        const auto slotted = [](Vec3 x) {
            const double sphere = distance(x, {0.5, 0.75, 0.5}) - 0.15;
            const double slot = box_distance(x, {0.475, 0.5, 0.2}, {0.525, 0.725, 0.8});
            return std::max(sphere, -slot);
        };
        p.exact = [slotted](double t, Vec3 x) {
            return std::abs(std::remainder(t, 1.0)) < 1e-12 ? slotted(x) : nan;
        };
    } else if (name == "sphere-curvature") {
        resolve(what, {}, params);
        p.domain = centred_cube;
        p.t_end = 0.05;
        p.steps = 20;
        p.study = SurfaceStudyPlan{.steps = 5, .depth = 5, .eps = 4e-4};
        p.law = std::make_unique<SurfaceMeanCurvatureFlow>();
        p.exact = [](double t, Vec3 x) { return norm(x) - std::sqrt(0.25 - 4.0 * t); };
    } else if (name == "merging-spheres") {
        resolve(what, {}, params);
        const Vec3 a{-0.3, 0.0, 0.0}, b{0.3, 0.0, 0.0};
        p.domain = centred_cube;
        p.t_end = 0.15;
        p.steps = 10;
        p.study = SurfaceStudyPlan{.steps = 5, .depth = 5, .eps = 4e-4};
        p.law = std::make_unique<SurfaceNormalSpeed>(1.0);
        // The union of the grown balls, exact also in the neck where they merge (Eq. 11).
        p.exact = [a, b](double t, Vec3 x) {
            const Ball<3> balls[] = {{a, 0.25 + t}, {b, 0.25 + t}};
            return union_of_balls_distance<3>(balls, x);
        };
    } else if (name == "box-normal") {
        const VelocityParams v = resolve(what, {{"speed", 1.0}}, params);
        const double s = v.at("speed");
        const Vec3 lo{-0.35, -0.3, -0.25}, hi{0.35, 0.3, 0.25};
        p.domain = centred_cube;
        p.t_end = 0.1;
        p.steps = 10;
        p.law = std::make_unique<SurfaceNormalSpeed>(s);
        p.initial = box_surface(lo, hi, 8);
        // Its sharp edges bend G as a thin part does, and lie on the tree's planes at t = 0.1:
        // with no thin cells the shrinking box ends 6.5e−3 from the exact one (refinement refused
        // along its edges in every step), with thin cells two levels deeper 3.1e−3; growing,
        // 3.5e−4 and 3.2e−4.
        p.thin_depth = 2;
        p.exact = [lo, hi, s](double t, Vec3 x) {
            if (s >= 0.0) return box_distance(x, lo, hi) - s * t;  // the offset: rounded
            const Vec3 in{-s * t, -s * t, -s * t};
            return box_distance(x, lo + in, hi - in);  // the inner offset: a smaller box
        };
    } else if (name == "peanut-volume") {
        resolve(what, {}, params);
        p.domain = centred_cube;
        p.t_end = 0.02;
        p.steps = 20;
        p.law = std::make_unique<SurfaceVolumePreservingFlow>();
    } else {
        std::string names;
        for (const std::string& n : surface_problem_names())
            names += (names.empty() ? "" : ", ") + n;
        throw InvalidInput(
            fmt::format("unknown problem '{}'; known surface problems: {}", name, names));
    }
    if (p.initial.empty()) {
        std::function<double(Vec3)> f;
        if (name == "peanut-volume") {
            f = [](Vec3 x) {
                return std::min(distance(x, {-0.22, 0.0, 0.0}), distance(x, {0.22, 0.0, 0.0})) -
                       0.3;
            };
        } else {
            const auto exact = p.exact;
            f = [exact](Vec3 x) { return exact(0.0, x); };
        }
        p.initial_function = std::move(f);
        p.initial = initial_surface(p, {.depth = p.depth,
                                        .refine_passes = SurfaceContourOptions::until_converged,
                                        .eps = p.eps});
    }
    return p;
}

Surface initial_surface(const SurfaceProblem& p, const SurfaceContourOptions& options) {
    if (!p.initial_function) return p.initial;
    const auto g = pointwise<Vec3>(p.initial_function);
    // Every problem's function is 1-Lipschitz (distances, and their minima and maxima), so
    // points far from its zero set need no value.
    SurfaceContourOptions o = options;
    if (!o.distance_slack) o.distance_slack = 0.0;
    // Its vertices are the first step's, which differentiates them (advance_contours).
    if (!o.eta) o.eta = SurfaceContourOptions::default_eta;
    return contour_surface(g, p.domain, o).surface;
}

Box3 default_domain(const Box3& b) {
    const double half = 0.75 * std::max({b.extent(0), b.extent(1), b.extent(2)});
    if (!(2.0 * half >= tolerance::min_domain_width)) {
        throw InvalidInput(fmt::format(
            "the surface spans only {:.3g}: give --domain or --box at least {:g} wide, or scale it",
            2.0 * half / 1.5, tolerance::min_domain_width));
    }
    return Box3::cube(b.center(), half);
}

double length_scale(const Surface& surface) {
    const Box3 b = bounding_box(surface);
    return 0.5 * std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z});
}

SurfaceRunOptions default_surface_run_options(const Surface& surface, const SurfaceVelocityLaw& law,
                                              double t_start, double t_end) {
    if (surface.empty()) throw InvalidInput("the initial surface has no triangles");
    SurfaceRunOptions o = detail::user_run_options<3, SurfaceRunOptions>(
        law, t_start, t_end, length_scale(surface), detail::user_steps(3));
    o.step.contour.refine_passes = SurfaceContourOptions::until_converged;
    return o;
}

}  // namespace slc
