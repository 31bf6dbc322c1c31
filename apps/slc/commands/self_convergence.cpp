// slc study --initial: runs at successive resolutions compared with each other (no exact
// solution), with observed orders and a Richardson estimate of the finest run's error.
#include "commands/self_convergence.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>

#include "commands/run_options.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/render.hpp"
#include "slc/io/summary.hpp"
#include "slc/io/surface_files.hpp"

namespace slc::cli {
namespace {

std::string number(const std::optional<double>& v, const char* format = "{:.3g}") {
    return v ? fmt::format(fmt::runtime(format), *v) : "—";
}

std::optional<double> finite(double v) {
    return std::isfinite(v) ? std::optional(v) : std::nullopt;
}

nlohmann::json json_number(const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

bool ended_empty(const RunResult& r) { return r.curves.empty(); }
bool ended_empty(const SurfaceRunResult& r) { return r.surface.empty(); }

/// What the estimate is, or why there is none, in one sentence.
template <class Run>
std::string estimate_note(const BasicSelfConvergenceResult<Run>& s, const char* what) {
    const std::string finest = run_name(s.runs.back().options);
    if (!s.estimate) {
        const auto& a = s.runs[s.runs.size() - 2].result;
        const auto& b = s.runs.back().result;
        std::string why;
        if (a.status != b.status) {
            why = fmt::format("they ended differently, {} at t = {:.6g} and {} at t = {:.6g}",
                              to_string(a.status), a.t, to_string(b.status), b.t);
        } else if (ended_empty(a) || ended_empty(b)) {
            why =
                fmt::format("{} that vanished (at t = {:.6g} and {:.6g}) leave nothing to compare",
                            what, a.t, b.t);
        } else {
            why = fmt::format("they ended at different times, t = {:.6g} and {:.6g}", a.t, b.t);
        }
        return fmt::format("No estimate: the two finest runs cannot be compared: {}.", why);
    }
    const ErrorEstimate& e = *s.estimate;
    return fmt::format(
        "Estimated error of the finest run ({}): {:.3g} = d / (2^p − 1), d = {:.3g} its distance "
        "to the next coarser run and p = {:.2f} {}.",
        finest, e.error, s.distances.back(), e.order,
        e.observed ? "the last observed order, clamped to [0.5, 4]"
                   : "assumed (first order: no order was observed)");
}

/// The pairs of neighbours: their distance and the order observed from it and the next.
template <class Run>
nlohmann::json pairs_json(const BasicSelfConvergenceResult<Run>& s) {
    nlohmann::json pairs = nlohmann::json::array();
    for (std::size_t r = 0; r < s.distances.size(); ++r) {
        pairs.push_back({{"coarse", r},
                         {"fine", r + 1},
                         {"distance", json_number(finite(s.distances[r]))},
                         {"order", r < s.orders.size() ? json_number(s.orders[r]) : nullptr}});
    }
    return pairs;
}

/// The estimate of the finest run's error, or null.
template <class Run>
nlohmann::json estimate_json(const BasicSelfConvergenceResult<Run>& s) {
    if (!s.estimate) return nullptr;
    return {{"error", s.estimate->error},
            {"run", run_name(s.runs.back().options)},
            {"order", s.estimate->order},
            {"order_observed", s.estimate->observed}};
}

/// A run's P in table.json: its passes of refinement, or "converged".
nlohmann::json refine_json(int passes) {
    static_assert(ContourOptions::until_converged == SurfaceContourOptions::until_converged);
    return passes == ContourOptions::until_converged ? nlohmann::json("converged")
                                                     : nlohmann::json(passes);
}

/// The distance column of row r of a table: to the next run, or why there is none.
template <class Run>
std::string distance_cell(const BasicSelfConvergenceResult<Run>& s, std::size_t r) {
    if (r >= s.distances.size()) return "";
    return std::isfinite(s.distances[r]) ? fmt::format("{:.3g}", s.distances[r])
                                         : std::string("∞ (not comparable)");
}

/// The last three cells of row r of table.csv: distance_to_next, order, error_estimate.
template <class Run>
std::string csv_tail(const BasicSelfConvergenceResult<Run>& s, std::size_t r) {
    const std::string d = r < s.distances.size() ? fmt::format("{:.6g}", s.distances[r]) : "";
    const std::string order =
        r < s.orders.size() && s.orders[r] ? fmt::format("{:.4g}", *s.orders[r]) : "";
    const std::string estimate =
        r + 1 == s.runs.size() && s.estimate ? fmt::format("{:.6g}", s.estimate->error) : "";
    return fmt::format("{},{},{}", d, order, estimate);
}

/// One column of a study's tables: its heading in table.md, its name in table.csv and
/// table.json, and a run's value in it. Each dimension lists its columns once, so the three files
/// cannot disagree.
/// The files a column is in (Column::where), for curves and surfaces alike.
enum In : unsigned {
    in_md = 1,
    in_csv = 2,
    in_json = 4,
    in_md_json = in_md | in_json,
    in_csv_json = in_csv | in_json,
    in_all = in_md | in_csv | in_json
};

template <class Run>
struct Column {
    unsigned where;       ///< the files it is in
    const char* heading;  ///< in table.md
    const char* key;      ///< in table.csv and table.json
    nlohmann::json (*value)(const Run&);
    const char* md_format = "{}";   ///< for a number in table.md
    const char* csv_format = "{}";  ///< for a number in table.csv
};

/// A value of a column as text: a string as it is, a number in `format`.
std::string cell(const nlohmann::json& v, const char* format) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number_float()) return fmt::format(fmt::runtime(format), v.get<double>());
    if (v.is_number_unsigned()) return fmt::format(fmt::runtime(format), v.get<std::uint64_t>());
    return fmt::format(fmt::runtime(format), v.get<std::int64_t>());
}

/// table.csv: r, the columns in it, distance_to_next, order and error_estimate; a line a run.
template <class Run>
std::string csv_table(const BasicSelfConvergenceResult<Run>& s,
                      std::span<const Column<Run>> columns) {
    std::string out = "r";
    for (const Column<Run>& c : columns)
        if (c.where & in_csv) out += fmt::format(",{}", c.key);
    out += ",distance_to_next,order,error_estimate\n";
    for (std::size_t r = 0; r < s.runs.size(); ++r) {
        out += std::to_string(r);
        for (const Column<Run>& c : columns)
            if (c.where & in_csv) out += "," + cell(c.value(s.runs[r]), c.csv_format);
        out += "," + csv_tail(s, r) + "\n";
    }
    return out;
}

/// table.md's table: r, the columns in it, the distance to the next run and the order observed;
/// a line a run.
template <class Run>
std::string markdown_table(const BasicSelfConvergenceResult<Run>& s,
                           std::span<const Column<Run>> columns) {
    std::string head = "| r |";
    std::string rule = "|---|";
    for (const Column<Run>& c : columns) {
        if (!(c.where & in_md)) continue;
        head += fmt::format(" {} |", c.heading);
        rule += "---|";
    }
    std::string out = head + " d(r, r+1) | order |\n" + rule + "---|---|\n";
    for (std::size_t r = 0; r < s.runs.size(); ++r) {
        out += fmt::format("| {} |", r);
        for (const Column<Run>& c : columns)
            if (c.where & in_md) out += fmt::format(" {} |", cell(c.value(s.runs[r]), c.md_format));
        const std::string order = r < s.orders.size() ? number(s.orders[r], "{:.2f}") : "";
        out += fmt::format(" {} | {} |\n", distance_cell(s, r), order);
    }
    return out;
}

/// A run's entry of table.json's "resolutions": r, the columns in it, and the message if any.
template <class Run>
nlohmann::json run_json(const Run& run, std::span<const Column<Run>> columns) {
    nlohmann::json j = {{"r", run.level}};
    for (const Column<Run>& c : columns)
        if (c.where & in_json) j[c.key] = c.value(run);
    if (!run.result.message.empty()) j["message"] = run.result.message;
    return j;
}

/// table.json: head (the problem and its law) with "resolutions" (run_json of each run),
/// "pairs", "estimate" and "note".
template <class Run>
nlohmann::json table_json(nlohmann::json head, const BasicSelfConvergenceResult<Run>& s,
                          std::span<const Column<Run>> columns, const std::string& note) {
    nlohmann::json runs = nlohmann::json::array();
    for (const Run& r : s.runs) runs.push_back(run_json(r, columns));
    head["resolutions"] = std::move(runs);
    head["pairs"] = pairs_json(s);
    head["estimate"] = estimate_json(s);
    head["note"] = note;
    return head;
}

/// The columns of a study of curves.
using CurveColumn = Column<ResolutionRun>;
const CurveColumn curve_columns[] = {
    {in_md_json, "N/S/K/P/ε", "run",
     [](const ResolutionRun& r) -> nlohmann::json { return run_name(r.options); }},
    {in_csv_json, "", "N",
     [](const ResolutionRun& r) -> nlohmann::json { return r.options.steps; }},
    {in_csv_json, "", "S",
     [](const ResolutionRun& r) -> nlohmann::json { return r.options.step.embedded.smoothing; }},
    {in_csv_json, "", "K",
     [](const ResolutionRun& r) -> nlohmann::json { return r.options.step.contour.depth; }},
    {in_csv_json, "", "P",
     [](const ResolutionRun& r) { return refine_json(r.options.step.contour.refine_passes); }},
    {in_csv_json, "", "eps",
     [](const ResolutionRun& r) -> nlohmann::json { return r.options.step.contour.resolved_eps(); },
     "{}", "{:.6g}"},
    {in_json, "", "eta",
     [](const ResolutionRun& r) -> nlohmann::json {
         return r.options.step.contour.resolved_eta();
     }},
    {in_all, "status", "status",
     [](const ResolutionRun& r) -> nlohmann::json { return to_string(r.result.status); }},
    {in_csv_json, "", "t", [](const ResolutionRun& r) -> nlohmann::json { return r.result.t; }},
    {in_all, "segments", "segments",
     [](const ResolutionRun& r) -> nlohmann::json { return r.result.curves.size(); }},
    {in_all, "components", "components",
     [](const ResolutionRun& r) -> nlohmann::json { return r.result.curves.curve_count(); }},
    {in_all, "area", "area",
     [](const ResolutionRun& r) -> nlohmann::json { return area(r.result.curves); }, "{:.6g}"},
    {in_all, "length", "length",
     [](const ResolutionRun& r) -> nlohmann::json { return length(r.result.curves); }, "{:.6g}"},
    {in_all, "CPU s", "cpu_s",
     [](const ResolutionRun& r) -> nlohmann::json { return r.result.cpu_s; }, "{:.3g}", "{:.6g}"},
};

/// table.md: a title, what the study did (`intro`), the table and the note on the estimate.
template <class Run>
std::string markdown(const std::string& name, const std::string& intro,
                     const BasicSelfConvergenceResult<Run>& s, std::span<const Column<Run>> columns,
                     const std::string& note) {
    return fmt::format("# Self-convergence study: {}\n\n{}\n\n{}\n{}\n", name, intro,
                       markdown_table(s, columns), note);
}

/// "on N threads", of the CPU times of a study's tables.
std::string on_threads() {
    const int threads = thread_count();
    return fmt::format("on {} thread{}", threads, threads == 1 ? "" : "s");
}

std::string curves_intro(const Problem& p) {
    // The law as given: its name, or the expression or file after the option's name.
    const std::string given =
        p.velocity_expression.empty() ? p.velocity_file : p.velocity_expression;
    const std::string law_text = given.empty() ? p.velocity : p.velocity + " " + given;
    return fmt::format(
        "The curves of {} under `{}` from t = {:.6g} to {:.6g}, without an exact solution: each "
        "run is compared with the next finer one (twice the steps, one more level of K, ε/4). d "
        "is the largest distance from a vertex or segment midpoint of either final interface to "
        "the other (the symmetric Hausdorff distance, measured as Eq. 11 measures errors); the "
        "order on row r is log2(d(r, r+1) / d(r+1, r+2)) (2: second order). CPU seconds of the "
        "time loop, {}. The final curves of run r are in final_r.json (`slc render final_*.json` "
        "overlays them).",
        p.name, law_text, p.t_start, p.t_end, on_threads());
}

nlohmann::json json(const Problem& p, const SelfConvergenceResult& s) {
    nlohmann::json j =
        table_json({{"problem", p.name},
                    {"velocity", p.velocity},
                    {"velocity_params", p.velocity_params},
                    {"t_start", p.t_start},
                    {"t_end", p.t_end}},
                   s, std::span<const CurveColumn>(curve_columns), estimate_note(s, "curves"));
    if (!p.velocity_expression.empty()) j["velocity_expression"] = p.velocity_expression;
    if (!p.velocity_file.empty()) j["velocity_file"] = p.velocity_file;
    return j;
}

/// log10 d(r − 1, r) against r, and the estimated error of the finest run beside it.
template <class Run>
void plot(const std::filesystem::path& dir, const std::string& name,
          const BasicSelfConvergenceResult<Run>& s) {
    std::vector<Vec2> line;
    Box b = Box::empty();
    auto add = [&](std::vector<Vec2>& to, double r, double d) {
        if (!std::isfinite(d) || !(d > 0)) return;
        const Vec2 q{r, std::log10(d)};
        to.push_back(q);
        b = unite(b, {q, q});
    };
    for (std::size_t r = 0; r < s.distances.size(); ++r)
        add(line, static_cast<double>(r + 1), s.distances[r]);
    std::vector<Vec2> estimate;
    if (s.estimate) add(estimate, static_cast<double>(s.runs.size() - 1), s.estimate->error);
    const bool empty = b.is_empty();
    if (empty) b = Box::square({0.5 * static_cast<double>(s.runs.size() - 1), 0.0}, 1.0);
    Figure fig(Box::square(b.center(), 0.55 * std::max({b.width(), b.height(), 1.0})),
               fmt::format("{}: distance between successive resolutions{}", name,
                           empty ? " (none comparable)" : ""));
    fig.set_axis_names("resolution r (N, K, eps of run 0 refined r times)", "log10 distance");
    if (!line.empty()) {
        fig.add_polyline(line, "d(r - 1, r)", palette_color(0));
        fig.add_points(line, palette_color(0), 2.5);
    }
    if (!estimate.empty()) {
        fig.add_polyline(estimate, "estimated error of run r", palette_color(1));
        fig.add_points(estimate, palette_color(1), 3.5);
    }
    fig.save(dir / "convergence.svg");
    fig.save(dir / "convergence.png");
}

std::string law_text(const SurfaceLawText& law) {
    std::string text = law.expression.empty() ? law.name : law.name + " " + law.expression;
    for (const auto& [key, value] : law.params) text += fmt::format(" {}={:g}", key, value);
    return text;
}

/// The estimate's note, and which runs left steps beyond ε: their distances measure those
/// contours rather than convergence, and an order from them may mislead.
std::string surface_note(const SurfaceSelfConvergenceResult& s) {
    std::string note = estimate_note(s, "surfaces");
    for (const SurfaceResolutionRun& r : s.runs) {
        if (r.result.unconverged_steps == 0) continue;
        note += fmt::format(
            " Run {} left {} of {} steps beyond ε (up to {:.3g} against {:.3g}): the distances "
            "from it measure those contours rather than convergence, and an order from them may "
            "mislead.",
            r.level, r.result.unconverged_steps, r.result.steps_done, r.result.largest_residual,
            r.options.step.contour.resolved_eps());
    }
    return note;
}

/// The columns of a study of surfaces.
using SurfaceColumn = Column<SurfaceResolutionRun>;
using SR = SurfaceResolutionRun;
const SurfaceColumn surface_columns[] = {
    {in_md_json, "run", "run", [](const SR& r) -> nlohmann::json { return run_name(r.options); }},
    {in_csv_json, "", "N", [](const SR& r) -> nlohmann::json { return r.options.steps; }},
    {in_csv_json, "", "K",
     [](const SR& r) -> nlohmann::json { return r.options.step.contour.depth; }},
    {in_csv_json, "", "P",
     [](const SR& r) { return refine_json(r.options.step.contour.refine_passes); }},
    {in_csv_json, "", "eps",
     [](const SR& r) -> nlohmann::json { return r.options.step.contour.resolved_eps(); }, "{}",
     "{:.6g}"},
    {in_json, "", "eta",
     [](const SR& r) -> nlohmann::json { return r.options.step.resolved_eta(); }},
    {in_all, "status", "status",
     [](const SR& r) -> nlohmann::json { return to_string(r.result.status); }},
    {in_csv_json, "", "t", [](const SR& r) -> nlohmann::json { return r.result.t; }},
    {in_csv_json, "", "unconverged_steps",
     [](const SR& r) -> nlohmann::json { return r.result.unconverged_steps; }},
    {in_csv_json, "", "largest_residual",
     [](const SR& r) -> nlohmann::json { return r.result.largest_residual; }, "{}", "{:.6g}"},
    {in_md, "beyond ε", "",
     [](const SR& r) -> nlohmann::json {
         const SurfaceRunResult& res = r.result;
         if (res.unconverged_steps == 0) return "0";
         return fmt::format("{} of {} ({:.3g})", res.unconverged_steps, res.steps_done,
                            res.largest_residual);
     }},
    {in_all, "triangles", "triangles",
     [](const SR& r) -> nlohmann::json { return r.result.surface.size(); }},
    {in_all, "components", "components",
     [](const SR& r) -> nlohmann::json { return component_count(r.result.surface); }},
    {in_all, "genus", "genus",
     [](const SR& r) -> nlohmann::json { return genus(r.result.surface); }},
    {in_all, "volume", "volume",
     [](const SR& r) -> nlohmann::json { return volume(r.result.surface); }, "{:.6g}", "{:.17g}"},
    {in_all, "area", "area", [](const SR& r) -> nlohmann::json { return area(r.result.surface); },
     "{:.6g}", "{:.17g}"},
    {in_all, "CPU s", "cpu_s", [](const SR& r) -> nlohmann::json { return r.result.cpu_s; },
     "{:.3g}", "{:.6g}"},
};

std::string surface_intro(const SurfaceProblem& p, const SurfaceLawText& law) {
    return fmt::format(
        "The surface {} under `{}` from t = 0 to {:.6g}, without an exact solution: each run is "
        "compared with the next finer one (twice the steps, one more level of K, ε/4), each "
        "starting from the surface as `slc run --initial` reads it at its own K and ε. d is the "
        "largest distance from a vertex or triangle centroid of either final surface to the "
        "other; the order on row r is log2(d(r, r+1) / d(r+1, r+2)) (2: second order). CPU "
        "seconds of the run, {}. *beyond ε*: the steps whose contour refinement left "
        "beyond ε (splits its safeguards refused, as along sharp edges, or where the cells are "
        "too coarse for the surface), and the largest |G| left. The final surface of run r is "
        "final_r.obj.",
        p.name, law_text(law), p.t_end, on_threads());
}

nlohmann::json surface_json(const SurfaceProblem& p, const SurfaceLawText& law,
                            const SurfaceSelfConvergenceResult& s) {
    nlohmann::json j =
        table_json({{"problem", p.name},
                    {"velocity", law.name},
                    {"velocity_params", law.params},
                    {"t_start", 0.0},
                    {"t_end", p.t_end}},
                   s, std::span<const SurfaceColumn>(surface_columns), surface_note(s));
    if (!law.expression.empty()) j["velocity_expression"] = law.expression;
    return j;
}

}  // namespace

void write_self_convergence_study(const Problem& p, const VelocityLaw& law, const RunOptions& base,
                                  int resolutions, bool quiet, const std::filesystem::path& dir) {
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    const SelfConvergenceResult s =
        self_convergence(initial, law, p.domain, base, resolutions, [&](const ResolutionRun& r) {
            if (!quiet) {
                fmt::print(stderr, "{}: {} at t = {:.6g}, {} segments, {:.3g} s cpu\n",
                           run_name(r.options), to_string(r.result.status), r.result.t,
                           r.result.curves.size(), r.result.cpu_s);
            }
        });
    // Each run's final curves, to overlay with slc render as the paper compared its runs.
    for (const ResolutionRun& r : s.runs) {
        write_file_atomic(dir / fmt::format("final_{}.json", r.level),
                          interface_json(r.result.curves, r.result.t));
    }
    write_file_atomic(dir / "table.md", markdown(p.name, curves_intro(p), s,
                                                 std::span<const CurveColumn>(curve_columns),
                                                 estimate_note(s, "curves")));
    write_file_atomic(dir / "table.csv", csv_table<ResolutionRun>(s, curve_columns));
    write_file_atomic(dir / "table.json", json(p, s).dump(2) + "\n");
    plot(dir, p.name, s);
    if (!quiet) fmt::print("{}\n", estimate_note(s, "curves"));
}

void write_surface_self_convergence_study(const SurfaceProblem& p, const SurfaceLawText& law,
                                          const SurfaceRunOptions& base, int resolutions,
                                          bool quiet, const std::filesystem::path& dir) {
    const SurfaceSelfConvergenceResult s = surface_self_convergence(
        p.initial, *p.law, p.domain, base, resolutions, [&](const SurfaceResolutionRun& r) {
            if (!quiet) {
                fmt::print(stderr, "{}: {} at t = {:.6g}, {} triangles, {:.3g} s cpu\n",
                           run_name(r.options), to_string(r.result.status), r.result.t,
                           r.result.surface.size(), r.result.cpu_s);
            }
        });
    for (const SurfaceResolutionRun& r : s.runs)
        write_file_atomic(dir / fmt::format("final_{}.obj", r.level), obj_text(r.result.surface));
    write_file_atomic(dir / "table.md",
                      markdown(p.name, surface_intro(p, law), s,
                               std::span<const SurfaceColumn>(surface_columns), surface_note(s)));
    write_file_atomic(dir / "table.csv", csv_table<SurfaceResolutionRun>(s, surface_columns));
    write_file_atomic(dir / "table.json", surface_json(p, law, s).dump(2) + "\n");
    plot(dir, p.name, s);
    if (!quiet) fmt::print("{}\n", surface_note(s));
}

}  // namespace slc::cli
