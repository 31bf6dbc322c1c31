// Moving surfaces: one step on one thread and on all, against the number of triangles and for
// each kind of law, and Enright's test beside OpenVDB (from docs/tables/enright.md, which
// bench/enright.py writes). Writes its tables and summaries into their regions of the section
// "Moving surfaces" of docs/performance.md, a page written by hand (doc_regions.hpp); with
// --check-page it only checks that the page holds those regions, and with --enright-only it only
// writes the Enright table into its region.
//
// A step's time is the least wall time of --repeats calls of advance() on the same surface, the
// calls alternating between one thread and all (each call does all of a step's work, from the
// distance tree of the surface given to the contour of the next), in each of --rounds rounds
// over every row, minutes apart. The surfaces from one thread and from all are compared to the
// last bit.
//
// Usage: surface_performance_bench [--out FILE] [--enright FILE] [--repeats n] [--rounds n]
//                                  [--largest-depth K] [--triangles n] [--check-page]
//                                  [--enright-only]
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_support.hpp"
#include "doc_regions.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/evolve/surface_step.hpp"
#include "slc/slc.hpp"

namespace {

using namespace slc;

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

/// The table of docs/tables/enright.md (its lines starting with '|') and the lists after it (the
/// comparisons with OpenVDB, where slc's runs stopped), each with the line that leads to it; the
/// paragraph defining the columns stays there, and docs/performance.md explains them in its own
/// words. Empty when the file is missing.
std::string enright_table(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) return "";
    std::string line, table;
    std::vector<std::string> blocks(1);  // after the table, separated by blank lines
    while (std::getline(in, line)) {
        if (line.starts_with("|") && blocks.size() == 1 && blocks[0].empty()) {
            table += line + "\n";
        } else if (!table.empty() && line.empty()) {
            if (!blocks.back().empty()) blocks.emplace_back();
        } else if (!table.empty()) {
            blocks.back() += line + "\n";
        }
    }
    std::string md = table;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
        const std::string& b = blocks[i];
        const bool list = b.starts_with("- ");
        const bool leads =
            b.ends_with(":\n") && i + 1 < blocks.size() && blocks[i + 1].starts_with("- ");
        if (list || leads) md += "\n" + b;
    }
    return table.empty() ? "" : md;
}

int run_bench(int argc, char** argv) {
    using slc::bench::take_flag;
    const std::string out = take_flag(argc, argv, "--out", "docs/performance.md");
    const std::vector<std::string> regions = {"surfaces-settings", "surface-sizes", "surface-laws",
                                              "surface-speedups", "enright"};
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
    if (bench::take_switch(argc, argv, "--check-page")) {
        bench::check_regions(out, regions);
        fmt::print(stderr, "{} holds every region this program writes\n", out);
        return 0;
    }
    // Before the measurements, not after.
    bench::require_regions(out, regions);
    const auto enright_region = [&] {
        const std::string table = enright_table(enright);
        return bench::Region{"enright", table.empty()
                                            ? fmt::format("{} is missing: run bench/enright.py "
                                                          "(scripts/bench runs it).\n",
                                                          enright)
                                            : table};
    };
    if (bench::take_switch(argc, argv, "--enright-only")) {  // the table only, nothing measured
        bench::write_regions(out, {enright_region()});
        fmt::print(stderr, "wrote the Enright region of {}\n", out);
        return 0;
    }

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

    const SurfaceProblem curvature = make_surface_problem("sphere-curvature");
    std::vector<bench::Region> page;
    page.emplace_back(
        "surfaces-settings",
        fmt::format("Machine: {} hardware threads. Each step timed up to {} times on one thread "
                    "and on {} threads, alternating, in each of {} rounds over all the rows; "
                    "sphere-curvature's mean over σ = √k = {}; the laws' rows at K = {}, ε for "
                    "about {} triangles.",
                    threads, repeats, threads, rounds,
                    sci(std::sqrt(curvature.t_end / curvature.steps)), law_depth,
                    grouped(static_cast<std::size_t>(target))));
    std::string md = fmt::format(
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
    page.emplace_back("surface-sizes", md);
    md = fmt::format(
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
    page.emplace_back("surface-laws", md);
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
        md = fmt::format(
            "The {} steps above over 10⁵ triangles: {} threads are {:.2f}× to {:.2f}× faster "
            "than one (goal ≥ 1.8× for every such step: {}). The surfaces are {} for one thread "
            "and for {}.\n",
            speedups.size(), threads, *least, *most, *least >= 1.8 ? "met" : "not met",
            identical ? "the same to the last bit" : "**not** the same", threads);
    } else {
        md = "No step above reached 10⁵ triangles.\n";
    }
    page.emplace_back("surface-speedups", md);
    page.push_back(enright_region());
    bench::write_regions(out, page);
    fmt::print(stderr, "wrote {}\n", out);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    slc::keep_freed_memory();  // as the slc tool does: the timings are the tool's
    try {
        return run_bench(argc, argv);
    } catch (const std::exception& e) {
        fmt::print(stderr, "surface_performance_bench: {}\n", e.what());
        return 1;
    }
}
