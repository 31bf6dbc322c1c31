// Method options of slc run and slc study, and the summary of a run.
#include "commands/run_options.hpp"

#include <fmt/format.h>
#include <sys/resource.h>

#include <cmath>

#include "commands/common.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc::cli {
namespace {

/// The --extension spellings, also used in summary.json.
const std::map<std::string, Extension> extension_names = {{"nearest", Extension::nearest_point},
                                                          {"whitney", Extension::whitney},
                                                          {"direct", Extension::direct}};

/// The --geometry spellings.
const std::map<std::string, GeometryModule> geometry_names = {
    {"intrinsic", GeometryModule::intrinsic},
    {"embedded", GeometryModule::embedded},
    {"arclength", GeometryModule::arclength}};

/// The most memory the process has held so far (resident set, MiB): the check that long runs
/// stay bounded (scripts/memcheck) reads it from summary.json.
double peak_rss_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

std::string extension_name(Extension e) {
    for (const auto& [name, value] : extension_names)
        if (value == e) return name;
    return "nearest";
}

}  // namespace

void add_method_options(CLI::App& cmd, MethodOptions& o) {
    cmd.add_option("-N,--steps", o.steps, "N: time steps on [0, a] (problem's default)")
        ->check(integer_in(1, 100000000));
    cmd.add_option("-K,--depth", o.depth, "K: depth of the contouring tree (problem's default)")
        ->check(integer_in(1, 24));
    cmd.add_option("-P,--refine", o.refine,
                   "P: passes of adaptive refinement, or 'converged': until every segment "
                   "midpoint is within eps (a named problem's own P; converged for --initial)")
        ->transform(CLI::Validator(
            [](std::string& text) {
                if (text == "converged") {
                    text = std::to_string(ContourOptions::until_converged);
                    return std::string();
                }
                std::string copy = text;
                if (integer_in(0, 64)(copy).empty()) return std::string();
                return fmt::format("must be an integer from 0 to 64 or 'converged', got '{}'",
                                   text);
            },
            "in [0, 64] or converged"));
    cmd.add_option("--eps", o.eps,
                   "epsilon: midpoint tolerance of refinement (a problem's own; 10^-K with -K; "
                   "1e-5 times the curves' half-width for --initial)")
        ->check(positive_number());
    cmd.add_option("--eta", o.eta,
                   "eta: root-finding tolerance (default 1e-10, times the curves' half-width for "
                   "--initial)")
        ->check(positive_number());
    cmd.add_option("--rho", o.rho, "rho: pruning ratio in [0, 1) (default 0.1)")
        ->check(fraction_below_one());
    cmd.add_option("--mesh", o.mesh, "M: embedded mesh points per side (default 2^(K+1))")
        ->check(integer_in(8, 1 << 22));
    cmd.add_option("--eno-order", o.eno_order, "E: ENO order of the embedded module (default 3)")
        ->check(integer_in(1, 5));
    cmd.add_option("-S,--smooth", o.smooth, "S: cosine smoothing passes (problem's default)")
        ->check(integer_in(0, 64));
    cmd.add_option(
           "-L,--tree-depth", o.tree_depth,
           "L: distance tree depth (default K + P/2 rounded down; K + P with --extension whitney)")
        ->check(integer_in(1, 30));
    cmd.add_option("--extension", o.extension,
                   "Velocity off the curve: nearest (the vertex velocities at the nearest point), "
                   "whitney, or direct (the law itself: a flow field sampled along each "
                   "characteristic, traced back by 4th-order Runge-Kutta, one contour per step; a "
                   "normal law with the normal of the distance field, so corners move exactly). "
                   "Default: direct for flow fields and normal laws, nearest otherwise; a named "
                   "problem's own (nearest)")
        ->check(CLI::IsMember(extension_names));
    cmd.add_option("--geometry", o.geometry,
                   "Geometry module for normals and curvature: intrinsic, embedded, or arclength "
                   "(circumcircle curvature averaged over --arc-width; the law's default "
                   "otherwise)")
        ->check(CLI::IsMember(geometry_names));
    // A flag function, called only when given: a flag bound to the optional would set it always.
    cmd.add_flag_function(
        "--arcs,!--no-arcs", [&o](std::int64_t count) { o.arcs = count > 0; },
        "Read the curve as circular arcs through its vertices, not as chords, when G is "
        "evaluated (corners turning by more than 0.5 rad stay sharp): for smooth curves, "
        "whose chords lose a little area each step. Default: on for curvature laws with "
        "the arclength module (their default), off otherwise and for named problems");
    cmd.add_option("--arc-width", o.arc_width,
                   "sigma: arc length over which the arclength geometry module averages the "
                   "curvature (default sqrt(k); curvature flow is stable from 0.76 sqrt(k))")
        ->check(nonnegative_number());
    cmd.add_option("--threads", o.threads,
                   "Worker threads (0 = all cores); results do not depend on it")
        ->check(integer_in(0, 1024));
}

std::optional<GeometryModule> geometry_module(const MethodOptions& method) {
    if (method.geometry.empty()) return std::nullopt;
    return geometry_names.at(method.geometry);
}

RunOptions resolve_run_options(const MethodOptions& m, const Problem& p) {
    RunOptions r;
    r.t_start = p.t_start;
    r.t_end = p.t_end;
    r.steps = m.steps.value_or(p.steps);
    ContourOptions& c = r.step.contour;
    c.depth = m.depth.value_or(p.depth);
    c.refine_passes = m.refine.value_or(p.refine);
    c.eps = m.eps ? *m.eps : (m.depth ? std::pow(10.0, -c.depth) * p.length_scale : p.eps);
    c.eta = m.eta.value_or(p.eta);
    c.rho = m.rho;
    c.triangle_safeguard = p.triangle_safeguard;
    if (*c.eps < c.eta)
        throw InvalidInput(fmt::format("--eps ({}) must not be below --eta ({})", *c.eps, c.eta));
    r.max_domain_doublings = p.max_domain_doublings;
    r.step.tree_depth = m.tree_depth.value_or(0);
    r.step.extension = m.extension ? std::optional(extension_names.at(*m.extension)) : p.extension;
    r.step.embedded.mesh = m.mesh.value_or(default_mesh_size(c.depth));
    r.step.embedded.eno_order = m.eno_order;
    r.step.embedded.smoothing = m.smooth.value_or(p.smoothing);
    r.step.arcs = m.arcs ? m.arcs : p.arcs;
    r.step.area_correction = p.area_correction;
    r.step.arc_width = m.arc_width;
    return r;
}

std::string run_name(const RunOptions& o) {
    return fmt::format("{}/{}/{}/{}/{:.0e}", o.steps, o.step.embedded.smoothing,
                       o.step.contour.depth, refine_name(o.step.contour.refine_passes),
                       o.step.contour.resolved_eps());
}

std::string refine_name(int passes) {
    return passes == ContourOptions::until_converged ? "converged" : std::to_string(passes);
}

nlohmann::json run_summary(const Problem& p, const RunOptions& o, const RunResult& r,
                           const VelocityLaw& law) {
    const auto e_inf = max_error(p, r.curves, r.t);
    const ContourOptions& c = o.step.contour;
    nlohmann::json params = {
        {"N", o.steps},
        {"K", c.depth},
        {"P", c.refine_passes == ContourOptions::until_converged ? nlohmann::json("converged")
                                                                 : nlohmann::json(c.refine_passes)},
        {"eps", c.resolved_eps()},
        {"eta", c.eta},
        {"rho", c.rho},
        {"M", o.step.embedded.mesh},
        {"E", o.step.embedded.eno_order},
        {"S", o.step.embedded.smoothing},
        {"L", o.step.resolved_tree_depth()},
        {"domain", {p.domain.lo.x, p.domain.lo.y, p.domain.hi.x, p.domain.hi.y}},
        {"t_end", o.t_end},
        {"velocity", law.name()},
        {"velocity_params", p.velocity_params},
        {"extension", extension_name(o.step.resolved_extension(law))},
        {"arcs", o.step.resolved_arcs(law)},
        {"area_correction", o.step.area_correction.value_or(law.preserves_area())},
        {"arc_width", o.step.resolved_arc_width((o.t_end - o.t_start) / o.steps)}};
    for (const auto& q : p.parameters) params["problem_params"][q.name] = q.value;
    nlohmann::json s = {
        {"problem", p.name},
        {"run", run_name(o)},
        {"params", params},
        {"t_end", o.t_end},
        {"t", r.t},
        {"steps", o.steps},
        {"steps_done", r.steps_done},
        {"status", to_string(r.status)},
        {"e_inf", e_inf ? nlohmann::json(*e_inf) : nlohmann::json(nullptr)},
        {"area", area(r.curves)},
        {"length", length(r.curves)},
        {"components", r.curves.curve_count()},
        {"segments", r.curves.size()},
        {"wall_s", r.wall_s},
        {"cpu_s", r.cpu_s},
        {"cpu_s_per_step", r.steps_done > 0 ? r.cpu_s / r.steps_done : 0.0},
        {"threads", thread_count()},
        {"g_evals", r.g_evals},
        {"peak_rss_mib", peak_rss_mib()},
        {"g_evals_per_vertex",
         r.vertices_produced > 0 ? static_cast<double>(r.g_evals) / r.vertices_produced : 0.0}};
    if (r.status == RunStatus::error) s["message"] = r.message;
    if (o.step.area_correction.value_or(law.preserves_area()))
        s["area_corrected"] = r.area_corrected;
    if (r.domain_doublings > 0) {
        const Box d = doubled_domain(p.domain, r.domain_doublings);
        s["domain_grown"] = {{"at_t", r.domain_grown_at},
                             {"doublings", r.domain_doublings},
                             {"domain", {d.lo.x, d.lo.y, d.hi.x, d.hi.y}},
                             {"K", c.depth + r.domain_doublings}};
    }
    return s;
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
    return text;
}

std::string velocity_help() {
    std::string text = "Velocity law for --initial:";
    for (const auto& v : velocity_catalog()) {
        std::string params;
        for (const auto& q : v.parameters)
            params += fmt::format(" {}[{}]", q.name,
                                  q.default_text.empty() ? "required" : q.default_text);
        text += fmt::format("\n  {}:{} — {}", v.name, params, v.summary);
    }
    return text;
}

}  // namespace slc::cli
