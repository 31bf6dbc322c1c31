// summary.json of a run (DESIGN §6).
#include "slc/io/summary.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sys/resource.h>

#include <algorithm>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/evolve/surface_study.hpp"

namespace slc {

double peak_rss_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

std::string run_name(const RunOptions& o) {
    return fmt::format("{}/{}/{}/{}/{:.0e}", o.steps, o.step.embedded.smoothing,
                       o.step.contour.depth, refine_name(o.step.contour.refine_passes),
                       o.step.contour.resolved_eps());
}

std::string run_name(const SurfaceRunOptions& o) {
    return fmt::format("N {}, K {}, eps {:.3g}", o.steps, o.step.contour.depth,
                       o.step.contour.resolved_eps());
}

std::string refine_name(int passes) {
    return passes == ContourOptions::until_converged ? "converged" : std::to_string(passes);
}

namespace {

/// The finest cell the run's contours used, when and where (RunTotals::finest_cell), and when
/// thin cells first reached their budget: both dimensions' summaries.
void put_resolution(nlohmann::json& s, const RunTotals& r) {
    if (r.finest_cell > 0.0)
        s["finest_cell"] = {{"width", r.finest_cell}, {"at_t", r.finest_t}, {"at", r.finest_at}};
    if (!std::isnan(r.thin_budget_at)) s["thin_budget_reached_at_t"] = r.thin_budget_at;
    if (!std::isnan(r.deeper_at))
        s["thin_deeper"] = {{"at_t", r.deeper_at},
                            {"why", r.deeper_why},
                            {"depth", r.deepest_thin_depth},
                            {"steps", r.deeper_steps}};
    if (!std::isnan(r.shallower_at))
        s["thin_shallower"] = {{"at_t", r.shallower_at},
                               {"why", r.shallower_why},
                               {"depth", r.shallowest_thin_depth},
                               {"substeps", r.shallower_substeps}};
    if (const ThinSplit& t = r.thin_split; !std::isnan(t.at)) {
        s["thin_split"] = {
            {"at_t", t.at}, {"thickness", t.thickness}, {"cell", t.cell}, {"near", t.near}};
    }
}

/// The note of a run with no thin cells that split off a part thinner than its finest cell.
std::optional<std::string> thin_split_note(const RunTotals& r) {
    const ThinSplit& t = r.thin_split;
    if (std::isnan(t.at)) return std::nullopt;
    return fmt::format(
        "the step to t = {:.6g} split off a part {:.3g} thick near {}, thinner than the finest "
        "cell, {:.3g}: with no thin cells the contours may have torn a part thinner than they "
        "resolve rather than the law splitting it (thin_split); --thin-depth or a larger depth K "
        "resolves such parts",
        t.at, t.thickness, fmt::format("({:.6g})", fmt::join(t.near, ", ")), t.cell);
}

/// The fields that both dimensions' contour statistics share.
template <int dim>
nlohmann::json basic_stats_json(const BasicContourStats<dim>& s) {
    std::vector<double> at;
    for (int i = 0; i < dim; ++i) at.push_back(s.finest_at[i]);
    return {{"cells", s.cells},
            {"leaves", s.leaves},
            {"thin_cells", s.thin_cells},
            {"thin_budget_reached", s.thin_budget_reached},
            {"specks", s.specks},
            {"finest_cell", s.finest_cell},
            {"finest_at", at},
            {"vertices", s.vertices},
            {"g_evals", s.g_evals},
            {"g_evals_tree", s.g_evals_tree},
            {"g_evals_roots", s.g_evals_roots},
            {"g_evals_refine", s.g_evals_refine},
            {"g_evals_per_vertex", s.g_evals_per_vertex},
            {"settled", s.settled},
            {"bound_evals", s.bound_evals},
            {"gamma", s.gamma},
            {"perturbed", s.perturbed},
            {"moved_across", s.moved_across},
            {"unconverged_roots", s.unconverged_roots},
            {"passes", s.passes},
            {"splits", s.splits},
            {"rejected", s.rejected}};
}

}  // namespace

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
        {"eta", std::max(c.resolved_eta(),
                         tolerance::rounding_floor(doubled_domain(p.domain, r.domain_doublings)))},
        {"rho", c.rho},
        {"thin_depth", std::max(c.thin_depth, r.thin_depth)},
        {"guards", o.guards},
        {"M", o.step.embedded.mesh},
        {"E", o.step.embedded.eno_order},
        {"eno_bias", o.step.embedded.eno_bias},
        {"S", o.step.embedded.smoothing},
        {"embedded_average", o.step.embedded.average},
        {"L", o.step.resolved_tree_depth()},
        {"domain", {p.domain.lo.x, p.domain.lo.y, p.domain.hi.x, p.domain.hi.y}},
        {"t_end", o.t_end},
        {"velocity", p.velocity.empty() ? law.name() : p.velocity},
        {"velocity_params", p.velocity_params},
        {"extension", to_string(o.step.resolved_extension(law))},
        {"arcs", o.step.resolved_arcs(law)},
        {"area_correction", o.step.resolved_area_correction(law)},
        {"arc_width", o.step.resolved_arc_width((o.t_end - o.t_start) / o.steps)}};
    if (p.velocity == "speed" || p.velocity == "field")
        params["velocity_expression"] = p.velocity_expression;
    if (p.velocity == "field-file") {
        params["velocity_file"] = p.velocity_file;
        params["field_outside"] = p.velocity_zero_outside ? "zero" : "error";
    }
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
    if (!r.message.empty()) s["message"] = r.message;
    if (const auto note = thin_split_note(r)) s["note"] = *note;
    if (r.split_steps > 0)
        s["substeps"] = {{"split_steps", r.split_steps}, {"most", r.most_substeps}};
    if (o.step.resolved_area_correction(law)) s["area_corrected"] = r.area_corrected;
    if (r.domain_doublings > 0) {
        const Box d = doubled_domain(p.domain, r.domain_doublings);
        s["domain_grown"] = {{"at_t", r.domain_grown_at},
                             {"doublings", r.domain_doublings},
                             {"domain", {d.lo.x, d.lo.y, d.hi.x, d.hi.y}},
                             {"K", c.depth + r.domain_doublings}};
    }
    put_resolution(s, r);
    return s;
}

nlohmann::json surface_run_summary(const SurfaceProblem& p, const Surface& initial,
                                   const SurfaceRunOptions& options, const SurfaceRunResult& r) {
    const SurfaceContourOptions& c = options.step.contour;
    const Surface& s = r.surface;
    const double volume0 = volume(initial), area0 = area(initial);
    // The volumes as the steps read the surfaces, curved patches included: the triangles of a
    // finer or coarser mesh fall short of that surface by other amounts (Enright's sphere at
    // K 7: its 95,568 triangles hold 0.0245% less than the sphere, their patches 2.6e−8 less).
    const double read0 = initial.empty() ? 0.0 : step_volume(initial, options.step);
    const double read = s.empty() ? 0.0 : step_volume(s, options.step);
    const std::optional<double> e = surface_error(p, r.t, s);
    nlohmann::json summary = {
        {"problem", p.name},
        {"velocity", p.law->name()},
        {"dimension", 3},
        {"domain",
         {p.domain.lo.x, p.domain.lo.y, p.domain.lo.z, p.domain.hi.x, p.domain.hi.y,
          p.domain.hi.z}},
        {"t_end", options.t_end},
        {"params",
         {{"N", options.steps},
          {"k", (options.t_end - options.t_start) / options.steps},
          {"K", c.depth},
          {"P", c.refine_passes < 0 ? nlohmann::json("until converged")
                                    : nlohmann::json(c.refine_passes)},
          {"eps", c.resolved_eps()},
          {"eta", std::max(options.step.resolved_eta(), tolerance::rounding_floor(doubled_domain(
                                                            p.domain, r.domain_doublings)))},
          {"thin_depth", std::max(c.thin_depth, r.thin_depth)},
          {"volume_drift", options.volume_drift},
          {"guards", options.guards},
          {"threads", thread_count()}}},
        {"status", to_string(r.status)},
        {"t", r.t},
        {"steps", options.steps},
        {"steps_done", r.steps_done},
        {"triangles", s.size()},
        {"vertices", s.vertices.size()},
        {"components", s.empty() ? 0 : component_count(s)},
        {"genus", s.empty() ? 0 : genus(s)},
        {"volume", volume(s)},
        {"area", area(s)},
        {"volume_initial", volume0},
        {"area_initial", area0},
        {"volume_change", volume0 != 0.0 ? (volume(s) - volume0) / volume0 : 0.0},
        {"volume_read", read},
        {"volume_read_change", read0 != 0.0 ? (read - read0) / read0 : 0.0},
        {"e_inf", e ? nlohmann::json(*e) : nlohmann::json(nullptr)},
        {"g_evals", r.g_evals},
        {"split_steps", r.split_steps},
        {"most_substeps", r.most_substeps},
        {"cpu_s", r.cpu_s},
        {"wall_s", r.wall_s}};
    if (!r.message.empty()) summary["message"] = r.message;
    std::vector<std::string> notes;
    if (c.refine_passes == SurfaceContourOptions::until_converged) {
        summary["unconverged_steps"] = r.unconverged_steps;
        if (r.unconverged_steps > 0) {
            summary["largest_residual"] = r.largest_residual;
            notes.push_back(fmt::format(
                "in {} of {} steps refinement left |G| up to {:.3g} at an edge midpoint or "
                "centroid, above eps = {:.3g} (splits its safeguards refused, as along sharp "
                "edges): the surface is that far from each step's, not eps (unconverged_steps, "
                "largest_residual); a larger depth K resolves such features finer",
                r.unconverged_steps, r.steps_done, r.largest_residual, c.resolved_eps()));
        }
    }
    if (const auto note = thin_split_note(r)) notes.push_back(*note);
    if (!notes.empty()) {
        std::string note = notes[0];
        for (std::size_t i = 1; i < notes.size(); ++i) note += "; and " + notes[i];
        summary["note"] = note;
    }
    if (options.step.resolved_volume_correction(*p.law))
        summary["volume_corrected"] = r.volume_corrected;
    if (r.domain_doublings > 0) {
        const Box3 d = doubled_domain(p.domain, r.domain_doublings);
        summary["domain_grown"] = {{"at_t", r.domain_grown_at},
                                   {"doublings", r.domain_doublings},
                                   {"domain", {d.lo.x, d.lo.y, d.lo.z, d.hi.x, d.hi.y, d.hi.z}},
                                   {"K", c.depth + r.domain_doublings}};
    }
    put_resolution(summary, r);
    return summary;
}

void require_half_resolution(int steps, int depth, const std::string& option) {
    if (steps < 2 || depth < 2) {
        throw InvalidInput(fmt::format(
            "{} compares with the run at half resolution, which needs N >= 2 and K >= 2, got N = "
            "{} and K = {}",
            option, steps, depth));
    }
}

nlohmann::json estimate_json(const std::string& coarse, RunStatus status,
                             const std::function<CoarseRun()>& run_coarse,
                             const std::string& what) {
    nlohmann::json e = {{"distance", nullptr}, {"coarse", coarse}, {"estimate", nullptr}};
    if (status != RunStatus::ok) {
        e["note"] = fmt::format("no estimate: the run ended with status {}, not at t_end",
                                to_string(status));
        return e;
    }
    const CoarseRun c = run_coarse();
    e["coarse_status"] = to_string(c.status);
    e["coarse_cpu_s"] = c.cpu_s;
    if (!std::isfinite(c.distance)) {
        e["note"] = fmt::format(
            "no estimate: the run at half resolution ended {} at t = {:.6g}{}, which cannot be "
            "compared with this run's {}",
            to_string(c.status), c.t, c.empty ? fmt::format(" with no {}", what) : "", what);
        return e;
    }
    e["distance"] = c.distance;
    e["estimate"] = c.distance;
    e["note"] = fmt::format(
        "distance between the final {} of this run and of the same run at half resolution (N/2 "
        "steps, K - 1, 4 eps): an estimate of this run's error that holds if it converges at "
        "first order or faster (at second order the error is about a third of it), not a bound",
        what == "surface" ? "surfaces" : what);
    return e;
}

// The counts each dimension adds to BasicContourStats, as summary.json names them (a
// ContourStats' max_midpoint_value, optional, apart).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ContourStats, triangles, curves, segments, mean_segment_length,
                                   pruned, joined, parted, slivers)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SurfaceContourStats, tetrahedra, triangles, collapses, flips,
                                   residual)

nlohmann::json contour_stats_json(const ContourStats& s) {
    nlohmann::json j = basic_stats_json(s);
    j.update(nlohmann::json(s));
    j["max_midpoint_value"] =
        s.max_midpoint_value ? nlohmann::json(*s.max_midpoint_value) : nlohmann::json(nullptr);
    return j;
}

nlohmann::json contour_stats_json(const SurfaceContourStats& s) {
    nlohmann::json j = basic_stats_json(s);
    j.update(nlohmann::json(s));
    return j;
}

}  // namespace slc
