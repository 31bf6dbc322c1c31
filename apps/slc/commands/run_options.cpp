// Method options of slc run and slc study, and the summary of a run.
#include "commands/run_options.hpp"

#include <fmt/format.h>

#include <cmath>

#include "commands/common.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/surface_problems.hpp"

namespace slc::cli {
void add_method_options(CLI::App& cmd, MethodOptions& o) {
    cmd.add_option(
           "-N,--steps", o.settings.steps,
           "N: time steps on [0, a] (a problem's own; for --initial 40 for curves and 20 "
           "for a surface, 10 for curves under a flow field evaluated directly, raised to a "
           "multiple of --frames; under the stiff mullins-sekerka and hele-shaw, as many as the "
           "start's sharpest turn needs, up to 2000)")
        ->check(integer_in(setting_range::steps));
    cmd.add_option(
           "-K,--depth", o.settings.depth,
           fmt::format("K: depth of the contouring tree (a problem's own; for --initial {}; "
                       "{} to {} for curves, {} to {} for surfaces)",
                       default_rule::depth(), setting_range::curve_depth.lo,
                       setting_range::curve_depth.hi, setting_range::surface_depth.lo,
                       setting_range::surface_depth.hi))
        ->check(
            integer_in(setting_range::curve_depth.lo,
                       std::max(setting_range::curve_depth.hi, setting_range::surface_depth.hi)));
    cmd.add_option(
           "-P,--refine", o.settings.refine,
           "P: passes of adaptive refinement, or 'converged': until every segment "
           "midpoint is within eps (a named problem's own P; for --initial converged, or 2 for "
           "curves under a law of curvature)")
        ->transform(CLI::Validator(
            [](std::string& text) {
                if (text == "converged") {
                    text = std::to_string(ContourOptions::until_converged);
                    return std::string();
                }
                std::string copy = text;
                if (integer_in(setting_range::refine)(copy).empty()) return std::string();
                return fmt::format("must be an integer from {} to {} or 'converged', got '{}'",
                                   setting_range::refine.lo, setting_range::refine.hi, text);
            },
            "in [0, 64] or converged"));
    cmd.add_option("--eps", o.settings.eps,
                   fmt::format("epsilon: midpoint tolerance of refinement (a problem's own; with "
                               "-K, or for --initial at its K, the rule of the dimension, with "
                               "half-width 1 for a problem: {})",
                               default_rule::eps()))
        ->check(positive_number());
    cmd.add_option("--eta", o.settings.eta,
                   fmt::format("eta: root-finding tolerance (the half-width is 1 for a "
                               "problem; default {})",
                               default_rule::eta()))
        ->check(positive_number());
    cmd.add_option(
           "--thin-depth", o.settings.thin_depth,
           fmt::format("Levels beyond K for cells where the zero set's two sides, or a sharp "
                       "turn, lie within one cell (a problem's own: 0, but 2 for enright and "
                       "box-normal; for --initial {}; 2 for curves under a speed that "
                       "depends on the normal)",
                       default_rule::thin_depth()))
        ->check(integer_in(setting_range::thin_depth));
    cmd.add_option("--rho", o.settings.rho, "rho: pruning ratio in [0, 1) (default 0.1)")
        ->check(fraction_below_one());
    cmd.add_option("--mesh", o.settings.mesh, "M: embedded mesh points per side (default 2^(K+1))")
        ->check(integer_in(setting_range::mesh));
    cmd.add_option("--eno-order", o.settings.eno_order,
                   "E: ENO order of the embedded module (default 3)")
        ->check(integer_in(setting_range::eno_order));
    cmd.add_option("-S,--smooth", o.settings.smoothing,
                   "S: cosine smoothing passes (problem's default)")
        ->check(integer_in(setting_range::smoothing));
    cmd.add_option(
           "-L,--tree-depth", o.settings.tree_depth,
           "L: distance tree depth (default K + P/2 rounded down; K + P with --extension whitney)")
        ->check(integer_in(setting_range::tree_depth));
    cmd.add_option("--extension", o.extension,
                   "Velocity off the curve: nearest (the vertex velocities at the nearest point), "
                   "whitney, or direct (the law itself: a flow field sampled along each "
                   "characteristic, traced back by 4th-order Runge-Kutta, one contour per step; a "
                   "normal law with the normal of the distance field, so corners move exactly). "
                   "Default: direct for flow fields and normal laws, nearest otherwise; a named "
                   "problem's own (nearest)")
        ->check(CLI::IsMember(names_of<Extension>(extension_names)));
    cmd.add_option("--geometry", o.geometry,
                   "Geometry module for normals and curvature: intrinsic, embedded, or arclength "
                   "(circumcircle curvature averaged over --arc-width; the law's default "
                   "otherwise)")
        ->check(CLI::IsMember(names_of<GeometryModule>(geometry_module_names)));
    // A flag function, called only when given: a flag bound to the optional would set it always.
    cmd.add_flag_function(
        "--arcs,!--no-arcs", [&o](std::int64_t count) { o.settings.arcs = count > 0; },
        "Read the curve as circular arcs through its vertices, not as chords, when G is "
        "evaluated (corners turning by more than 0.5 rad stay sharp): for smooth curves, "
        "whose chords lose a little area each step. Default: on for curvature laws with "
        "the arclength module (their default), for mullins-sekerka and for laws evaluated "
        "directly (normal laws, flow fields), off otherwise and for named problems");
    cmd.add_flag_function(
        "--area-correction,!--no-area-correction",
        [&o](std::int64_t count) { o.settings.area_correction = count > 0; },
        "After each step under a law that keeps the area (volume-preserving curvature), shift "
        "the curves along their normals by the area lost over the length, as summary.json's "
        "area_corrected reports; for a surface, the volume over the area (volume_corrected). "
        "Default: on for such laws, off for named problems of curves (the paper's method)");
    cmd.add_option("--arc-width", o.settings.arc_width,
                   "sigma: arc length over which the arclength geometry module averages the "
                   "curvature (default sqrt(k); curvature flow is stable from 0.76 sqrt(k))")
        ->check(nonnegative_number());
    add_threads_option(cmd, o.threads);
}

std::optional<GeometryModule> geometry_module(const MethodOptions& method) {
    if (method.geometry.empty()) return std::nullopt;
    return value_named<GeometryModule>(geometry_module_names, method.geometry, "--geometry");
}

RunOverrides overrides_of(const MethodOptions& m) {
    RunOverrides q = m.settings;
    if (m.extension)
        q.extension = value_named<Extension>(extension_names, *m.extension, "--extension");
    return q;
}

RunOptions resolve_run_options(const MethodOptions& m, const Problem& p) {
    return run_options(p, overrides_of(m), SettingNames::tool);
}

std::map<std::string, double> parse_params(const std::vector<std::string>& params) {
    std::map<std::string, double> out;
    for (const std::string& kv : params) {
        const auto eq = kv.find('=');
        double value = 0.0;
        std::size_t used = 0;
        bool ok = eq != std::string::npos && eq > 0 && eq + 1 < kv.size();
        if (ok) {
            try {
                value = std::stod(kv.substr(eq + 1), &used);
                ok = used == kv.size() - eq - 1 && std::isfinite(value);
            } catch (const std::exception&) {
                ok = false;
            }
        }
        if (!ok)
            throw InvalidInput(
                fmt::format("--param expects key=value with a finite number, got '{}'", kv));
        out[kv.substr(0, eq)] = value;
    }
    return out;
}

std::string problem_help() {
    std::string text = "A named problem:";
    for (const auto& p : problem_catalog()) text += fmt::format("\n  {}: {}", p.name, p.summary);
    text += "\nA named problem of a surface:";
    for (const std::string& name : surface_problem_names())
        text += fmt::format("\n  {}: {}", name, surface_problem_summary(name));
    return text;
}

std::string velocity_help() {
    auto listed = [](const std::vector<VelocityInfo>& catalog) {
        std::string text;
        for (const auto& v : catalog) {
            std::string params;
            for (const auto& q : v.parameters)
                params += fmt::format(" {}[{}]", q.name,
                                      q.default_text.empty() ? "required" : q.default_text);
            text += fmt::format("\n  {}:{} — {}", v.name, params, v.summary);
        }
        return text;
    };
    return "Velocity law for --initial:" + listed(velocity_catalog()) +
           "\nVelocity law for --initial with a surface (.obj, .stl, .ply, .vdb):" +
           listed(surface_velocity_catalog());
}

}  // namespace slc::cli
