// Moving surfaces: one step on one thread and on all, against the number of triangles and for
// each kind of law, and Enright's test beside OpenVDB (from docs/tables/enright.md, which
// bench/enright.py writes). Writes the section "Moving surfaces" of docs/performance.md between
// its markers; performance_bench keeps that section when it writes the rest of the file.
//
// A step's time is the least wall time of --repeats calls of advance() on the same surface, the
// calls alternating between one thread and all (each call does all of a step's work, from the
// distance tree of the surface given to the contour of the next), in each of --rounds rounds
// over every row, minutes apart. The surfaces from one thread and from all are compared to the
// last bit.
//
// Usage: surface_performance_bench [--out FILE] [--enright FILE] [--repeats n] [--rounds n]
//                                  [--largest-depth K] [--triangles n]
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_support.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/evolve/surface_step.hpp"
#include "slc/slc.hpp"

namespace {

using namespace slc;

using bench::surfaces_begin;
using bench::surfaces_end;
using bench::wall_now;

bool same_surface(const Surface& a, const Surface& b) {
    if (a.vertices.size() != b.vertices.size() || a.triangles != b.triangles) return false;
    for (std::size_t i = 0; i < a.vertices.size(); ++i) {
        const Vec3 p = a.vertices[i], q = b.vertices[i];
        if (p.x != q.x || p.y != q.y || p.z != q.z) return false;
    }
    return true;
}

/// One step of a problem's law from its initial surface contoured at K and ε, timed on one
/// thread and on all.
struct StepTiming {
    std::string problem;
    int depth = 0;
    double eps = 0.0;
    std::size_t triangles_in = 0;
    std::size_t triangles_out = 0;
    double g_per_vertex = 0.0;  ///< G and G̃ evaluations over the output's vertices
    double one = 0.0;           ///< wall seconds on one thread
    double all = 0.0;           ///< wall seconds on all threads
    bool identical = false;     ///< the same surface from both
};

/// ε for about `target` triangles at depth K: from a first contour at 1e−4, the triangles
/// growing as 1/ε.
double eps_for(const std::string& name, int depth, double target) {
    const double first = 1e-4;
    const Surface trial = initial_surface(
        make_surface_problem(name),
        {.depth = depth, .refine_passes = SurfaceContourOptions::until_converged, .eps = first});
    return first * static_cast<double>(trial.size()) / target;
}

StepTiming time_step(const std::string& name, int depth, double eps, int repeats, int threads) {
    const SurfaceProblem p = make_surface_problem(name);
    SurfaceStepOptions o;
    o.contour = {
        .depth = depth, .refine_passes = SurfaceContourOptions::until_converged, .eps = eps};
    set_thread_count(threads);
    const Surface start = initial_surface(p, o.contour);
    const double k = p.t_end / p.steps;
    StepTiming r{name, depth, eps, start.size()};
    Surface results[2];
    // Calls alternate between one thread and all, so that a slow spell of the machine falls on
    // both: at least one pair, at most `repeats`, and none begun after two minutes.
    double least[2] = {std::numeric_limits<double>::infinity(),
                       std::numeric_limits<double>::infinity()};
    const double began = wall_now();
    for (int i = 0; i < repeats && (i == 0 || wall_now() - began < 120.0); ++i) {
        for (int which = 0; which < 2; ++which) {
            set_thread_count(which == 0 ? 1 : threads);
            const double w0 = wall_now();
            SurfaceStepResult step = advance(start, 0.0, k, *p.law, p.domain, o);
            least[which] = std::min(least[which], wall_now() - w0);
            if (i == 0) {
                r.triangles_out = step.surface.size();
                r.g_per_vertex = static_cast<double>(step.stats.g_evals()) /
                                 static_cast<double>(step.surface.vertices.size());
                results[which] = std::move(step.surface);
            }
        }
    }
    r.one = least[0];
    r.all = least[1];
    set_thread_count(threads);
    r.identical = same_surface(results[0], results[1]);
    return r;
}

std::string sci(double v) { return std::isfinite(v) ? fmt::format("{:.3g}", v) : "–"; }

/// n with commas between groups of three digits.
std::string grouped(std::size_t n) {
    const std::string digits = std::to_string(n);
    std::string s;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) s += ',';
        s += digits[i];
    }
    return s;
}

/// The table of docs/tables/enright.md (its lines starting with '|') and what follows it.
std::string enright_table(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) return "";
    std::string line, table, after;
    bool seen = false;
    while (std::getline(in, line)) {
        if (line.starts_with("|")) {
            table += line + "\n";
            seen = true;
        } else if (seen && !line.empty()) {
            after += line + "\n";
        } else if (seen && !after.empty() && !after.ends_with("\n\n")) {
            after += "\n";  // the blank line between blocks
        }
    }
    while (after.ends_with("\n\n")) after.pop_back();
    return table.empty() ? "" : table + "\n" + after;
}

/// Replaces the section between the markers in the file's text, or puts it before "## Where
/// the time goes" (or at the end) when the file has none.
std::string with_section(const std::string& text, const std::string& section) {
    const std::string block = std::string(surfaces_begin) + "\n" + section + surfaces_end + "\n";
    const auto b = text.find(surfaces_begin);
    const auto e = text.find(surfaces_end);
    if (b != std::string::npos && e != std::string::npos && e > b)
        return text.substr(0, b) + block + text.substr(e + std::string(surfaces_end).size() + 1);
    const auto where = text.find("## Where the time goes");
    if (where == std::string::npos) return text + "\n" + block;
    return text.substr(0, where) + block + "\n" + text.substr(where);
}

}  // namespace

int main(int argc, char** argv) {
    slc::keep_freed_memory();  // as the slc tool does: the timings are the tool's
    using slc::bench::take_flag;
    const std::string out = take_flag(argc, argv, "--out", "docs/performance.md");
    const std::string enright = take_flag(argc, argv, "--enright", "docs/tables/enright.md");
    const int repeats = std::stoi(take_flag(argc, argv, "--repeats", "3"));
    const int rounds = std::stoi(take_flag(argc, argv, "--rounds", "2"));
    const int largest = std::stoi(take_flag(argc, argv, "--largest-depth", "7"));
    const double target = std::stod(take_flag(argc, argv, "--triangles", "1.4e5"));
    constexpr int law_depth = 6;
    if (repeats < 1 || rounds < 1 || largest < 4) {
        fmt::print(stderr,
                   "surface_performance_bench: --repeats >= 1, --rounds >= 1 and "
                   "--largest-depth >= 4\n");
        return 2;
    }
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

    // Rows of about 5,000, 20,000, 80,000 and 320,000 triangles (K = 4..7), then each kind of
    // law on a surface of about `target` triangles. A slow spell of this machine (up to 1.45×
    // for minutes) slows two threads more than one when it takes part of a core: every row is
    // timed again in each round, minutes after the last, and keeps its least times.
    struct Row {
        std::string name;
        int depth;
        double eps;
    };
    const char* sized[] = {"sphere-rotation", "sphere-curvature"};
    std::vector<Row> rows;
    for (const char* name : sized) {
        for (int depth = 4; depth <= largest; ++depth)
            rows.push_back({name, depth, eps_for(name, depth, 5000.0 * std::pow(4.0, depth - 4))});
    }
    const std::size_t sized_rows = rows.size();
    for (const char* name :
         {"sphere-curvature", "sphere-rotation", "merging-spheres", "peanut-volume"})
        rows.push_back({name, law_depth, eps_for(name, law_depth, target)});
    std::vector<StepTiming> timed;
    for (int round = 0; round < rounds; ++round) {
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const StepTiming r =
                time_step(rows[i].name, rows[i].depth, rows[i].eps, repeats, threads);
            if (round == 0) {
                timed.push_back(r);
            } else {
                timed[i].one = std::min(timed[i].one, r.one);
                timed[i].all = std::min(timed[i].all, r.all);
                timed[i].identical = timed[i].identical && r.identical;
            }
            fmt::print(stderr, "round {}: {} K = {}: {} triangles, {:.3f} s / {:.3f} s\n",
                       round + 1, r.problem, r.depth, r.triangles_in, r.one, r.all);
        }
    }
    std::vector<StepTiming> sizes[2];
    for (std::size_t i = 0; i < sized_rows; ++i)
        sizes[rows[i].name == sized[0] ? 0 : 1].push_back(timed[i]);
    std::vector<StepTiming> laws(timed.begin() + static_cast<std::ptrdiff_t>(sized_rows),
                                 timed.end());

    std::string md = "## Moving surfaces\n\n";
    md += fmt::format(
        "Written by `scripts/bench` (bench/surface_performance_bench.cpp). One step of a problem's "
        "law from its initial surface contoured at K and ε (refinement until converged), the "
        "step's own k = t_end / N; the least wall time of up to {} calls on one thread and on {} "
        "threads, alternating (no pair begun after two minutes), so that a slow spell of the "
        "machine falls on both, in each of {} rounds over all the rows, minutes apart (a spell "
        "that takes part of a core slows two threads more than one). Each call does all of a "
        "step's work, from the "
        "distance tree of the surface "
        "given to the refined contour of the next. *identical*: the two surfaces agree to the "
        "last bit. G per vertex: evaluations of G̃ and G over the new surface's vertices.\n\n",
        repeats, threads, rounds);
    const SurfaceProblem curvature = make_surface_problem("sphere-curvature");
    md += fmt::format(
        "### Against the number of triangles\n\nsphere-rotation (a flow field: one contour, of "
        "G(x) = F(x*) with x* the characteristic's foot) and sphere-curvature (mean curvature "
        "flow: predictor and corrector, the curvature a Gaussian mean over σ = √k = {}, which "
        "covers more vertices as the triangles shrink). The time on one thread over N log₂ N "
        "is constant for a step that costs O(N log N).\n\n",
        sci(std::sqrt(curvature.t_end / curvature.steps)));
    md += fmt::format(
        "| problem | K | ε | triangles | s, 1 thread | µs per triangle | ns / (N log₂ N) | s, {} "
        "threads | speed-up | G per vertex | identical |\n|---|---:|---:|---:|---:|---:|---:|---:|"
        "---:|---:|---|\n",
        threads);
    for (int which = 0; which < 2; ++which) {
        for (const StepTiming& r : sizes[which]) {
            const double n = static_cast<double>(r.triangles_in);
            md += fmt::format(
                "| {} | {} | {} | {} | {} | {:.1f} | {:.0f} | {} | {:.2f}× | {:.2f} | {} |\n",
                r.problem, r.depth, sci(r.eps), grouped(r.triangles_in), sci(r.one),
                1e6 * r.one / n, 1e9 * r.one / (n * std::log2(n)), sci(r.all), r.one / r.all,
                r.g_per_vertex, r.identical ? "yes" : "**no**");
        }
    }
    md += fmt::format("\n### Each kind of law (K = {}, ε for about {} triangles)\n\n", law_depth,
                      grouped(static_cast<std::size_t>(target)));
    md += fmt::format(
        "| problem | law | ε | triangles in | triangles out | s, 1 thread | s, {} threads | "
        "speed-up | G per vertex | identical |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n",
        threads);
    auto law_of = [](const std::string& name) -> std::string {
        if (name == "sphere-curvature") return "mean curvature (nearest-point extension)";
        if (name == "sphere-rotation") return "rotation (a flow field: no predictor)";
        if (name == "merging-spheres") return "unit normal speed (direct extension)";
        return "volume-preserving mean curvature";
    };
    for (const StepTiming& r : laws) {
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {:.2f}× | {:.2f} | {} |\n",
                          r.problem, law_of(r.problem), sci(r.eps), grouped(r.triangles_in),
                          grouped(r.triangles_out), sci(r.one), sci(r.all), r.one / r.all,
                          r.g_per_vertex, r.identical ? "yes" : "**no**");
    }
    // Over every step above of more than 10^5 triangles.
    std::vector<double> speedups;
    bool identical = true;
    for (const auto* list : {&sizes[0], &sizes[1], &laws}) {
        for (const StepTiming& r : *list) {
            identical &= r.identical;
            if (r.triangles_in > 100000) speedups.push_back(r.one / r.all);
        }
    }
    if (!speedups.empty()) {
        const auto [least, most] = std::minmax_element(speedups.begin(), speedups.end());
        md += fmt::format(
            "\nThe {} steps above over 10⁵ triangles: {} threads are {:.2f}× to {:.2f}× faster "
            "than one (goal ≥ 1.8× for every such step: {}). The surfaces are {} for one thread "
            "and for {}.\n",
            speedups.size(), threads, *least, *most, *least >= 1.8 ? "met" : "not met",
            identical ? "the same to the last bit" : "**not** the same", threads);
    } else {
        md += "\nNo step above reached 10⁵ triangles.\n";
    }
    md +=
        "\nThe convergence studies of moving surfaces, with CPU seconds per step on two threads, "
        "are docs/tables/table5_3d.md (sphere rotation), table6_3d.md (merging spheres) and "
        "table7_3d.md (shrinking sphere); the named problems at their own settings are "
        "docs/tables/surface_problems.md.\n\n";
    md += "### Enright's test beside OpenVDB\n\n";
    const std::string table = enright_table(enright);
    if (table.empty()) {
        md += fmt::format("{} is missing: run bench/enright.py (scripts/bench runs it).\n\n",
                          enright);
    } else {
        md +=
            "From docs/tables/enright.md (bench/enright.py, in the same run as OpenVDB's "
            "`tools::LevelSetAdvection`; wall time on this machine). Goal: under 0.001% of "
            "the volume lost and within 1e−3 of the sphere at t = 3, in minutes, and faster "
            "than OpenVDB at every accuracy OpenVDB reaches.\n\n" +
            table + "\n";
    }

    const std::string text = std::filesystem::exists(out) ? read_text_file(out) : std::string();
    write_file_atomic(out, with_section(text, md));
    fmt::print(stderr, "wrote {}\n", out);
}
