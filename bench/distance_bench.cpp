// Benchmarks of the distance tree (paper §1.3, Table 1): building, triangulating and extending
// for the propeller interface at K = 6..12, and signed-distance queries near the interface at
// N = 10^3..10^6 segments beside a brute-force baseline. Writes docs/tables/table1.md itself.
//
// Usage: distance_bench [--table PATH] [google-benchmark flags]
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <map>
#include <random>

#include "bench_support.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/extension.hpp"
#include "slc/geometry/shapes.hpp"

namespace {

using namespace slc;
using namespace slc::bench;

const Box domain = Box::centered_square(1.0);
/// The Table 1 interface: the propeller r = 0.5 (1 + 0.5 cos 3θ) with 4096 segments.
const Interface& table1_interface() {
    static const Interface curves({shapes::propeller(4096)});
    return curves;
}

void BM_BuildTree(benchmark::State& state) {
    const int k = static_cast<int>(state.range(0));
    std::size_t cells = 0;
    for (auto _ : state) {
        const DistanceTree tree(table1_interface(), domain, {.depth = k, .triangulate = false});
        cells = tree.tree().size();
        benchmark::DoNotOptimize(cells);
    }
    state.counters["cells"] = static_cast<double>(cells);
}

void BM_Triangulate(benchmark::State& state) {
    const int k = static_cast<int>(state.range(0));
    const DistanceTree tree(table1_interface(), domain, {.depth = k, .triangulate = false});
    for (auto _ : state) {
        const Triangulation mesh = triangulate(tree.tree());
        // The vertices' pointers to their nearest segments belong to this step (paper §1.3).
        const auto nearest = tree.closest_points(mesh.vertices);
        benchmark::DoNotOptimize(nearest.data());
    }
}

void BM_Extend(benchmark::State& state) {
    const int k = static_cast<int>(state.range(0));
    const DistanceTree tree(table1_interface(), domain, {.depth = k, .triangulate = true});
    std::vector<Vec2> u(tree.curves().size());
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = perp(tree.curves().point(i));
    for (auto _ : state) {
        const WhitneyExtension<Vec2> w(tree, u);
        benchmark::DoNotOptimize(w.vertex_values().data());
    }
}

/// Points within a few finest-cell widths of a circle of n segments, and its tree at the depth
/// whose cells are about a segment long.
struct QueryCase {
    Interface curves;
    std::vector<Vec2> points;
    int depth = 0;
};

const QueryCase& query_case(int n) {
    static std::map<int, QueryCase> cache;
    auto it = cache.find(n);
    if (it != cache.end()) return it->second;
    QueryCase q;
    q.curves = Interface({shapes::circle({0.01, -0.02}, 0.7, n)});
    q.depth = std::max(2, static_cast<int>(std::ceil(std::log2(2.0 * n / (2 * 3.14159 * 0.7)))));
    const double h = 2.0 / (1 << q.depth);
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> angle(0.0, 6.283185307179586), offset(-3 * h, 3 * h);
    for (int k = 0; k < 4096; ++k) {
        const double a = angle(rng), r = 0.7 + offset(rng);
        q.points.push_back({0.01 + r * std::cos(a), -0.02 + r * std::sin(a)});
    }
    return cache.emplace(n, std::move(q)).first->second;
}

void BM_QueryNearInterface(benchmark::State& state) {
    const QueryCase& q = query_case(static_cast<int>(state.range(0)));
    const DistanceTree tree(q.curves, domain, {.depth = q.depth, .triangulate = false});
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(tree.closest_point(q.points[i]));
        i = (i + 1) % q.points.size();
    }
    state.SetComplexityN(state.range(0));
}

void BM_QueryBruteForce(benchmark::State& state) {
    const QueryCase& q = query_case(static_cast<int>(state.range(0)));
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(closest_point_brute_force(q.curves, q.points[i]));
        i = (i + 1) % q.points.size();
    }
    state.SetComplexityN(state.range(0));
}

BENCHMARK(BM_BuildTree)->DenseRange(6, 12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Triangulate)->DenseRange(6, 12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Extend)->DenseRange(6, 12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_QueryNearInterface)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Complexity(benchmark::oLogN);
BENCHMARK(BM_QueryBruteForce)->RangeMultiplier(10)->Range(1000, 10000)->Complexity(benchmark::oN);

void write_table1(const Recorder& rec, const std::string& path) {
    // The paper's Table 1 (450 MHz UltraSPARC II, 2000).
    const std::map<int, std::array<double, 4>> paper = {
        {6, {1421, 0.04, 0.02, 0}},      {7, {2957, 0.11, 0.05, 0.01}},
        {8, {6029, 0.24, 0.11, 0.01}},   {9, {12173, 0.57, 0.24, 0.02}},
        {10, {24461, 1.24, 0.51, 0.03}}, {11, {49037, 2.81, 1.11, 0.07}},
        {12, {98189, 6.35, 2.32, 0.14}}};
    std::string md =
        "# Table 1: distance tree, triangulation and extension\n\n"
        "Written by `bench/distance_bench.cpp` (run `scripts/bench`); do not edit by hand.\n\n"
        "Interface: the propeller r = 0.5 (1 + 0.5 cos 3θ), 4096 segments, domain [-1, 1]². "
        "CPU seconds on one core; the paper's figures (450 MHz UltraSPARC II) beside ours. "
        "Triangulation includes the nearest segment of every triangulation vertex; extension is "
        "the nearest-point extension of a velocity to every vertex (what the Whitney extension "
        "interpolates).\n\n"
        "| K | cells (ours) | cells (paper) | tree s (ours) | tree s (paper) | speed-up | "
        "triangulation s (ours) | (paper) | extension s (ours) | (paper) |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& [k, p] : paper) {
        const auto& build = rec.results.at(fmt::format("BM_BuildTree/{}", k));
        const auto& tri = rec.results.at(fmt::format("BM_Triangulate/{}", k));
        const auto& ext = rec.results.at(fmt::format("BM_Extend/{}", k));
        md += fmt::format(
            "| {} | {:.0f} | {:.0f} | {:.2e} | {} | {:.0f}× | {:.2e} | {} | {:.2e} | {} |\n", k,
            build.counters.at("cells").value, p[0], seconds(build), p[1], p[1] / seconds(build),
            seconds(tri), p[2], seconds(ext), p[3]);
    }
    md +=
        "\n## Signed-distance queries near the interface\n\n"
        "A circle of N segments, its tree at the depth where cells are about a segment wide, "
        "4096 points within three cell widths of the circle, one query at a time on one core.\n\n"
        "| N | tree ns/query | brute force ns/query |\n|---|---|---|\n";
    for (int n = 1000; n <= 1000000; n *= 10) {
        const auto& fast = rec.results.at(fmt::format("BM_QueryNearInterface/{}", n));
        const auto it = rec.results.find(fmt::format("BM_QueryBruteForce/{}", n));
        const std::string slow =
            it == rec.results.end() ? "" : fmt::format("{:.0f}", seconds(it->second) * 1e9);
        md += fmt::format("| {} | {:.0f} | {} |\n", n, seconds(fast) * 1e9, slow);
    }
    std::ofstream(path) << md;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string table = take_flag(argc, argv, "--table", "docs/tables/table1.md");
    slc::set_thread_count(1);
    benchmark::Initialize(&argc, argv);
    Recorder recorder;
    benchmark::RunSpecifiedBenchmarks(&recorder);
    // The table needs every row: a filtered run (--benchmark_filter) leaves it as it was.
    bool complete = true;
    for (int k = 6; k <= 12; ++k)
        for (const char* name : {"BM_BuildTree", "BM_Triangulate", "BM_Extend"})
            complete = complete && recorder.results.count(fmt::format("{}/{}", name, k)) != 0;
    for (int n = 1000; n <= 1000000; n *= 10)
        complete =
            complete && recorder.results.count(fmt::format("BM_QueryNearInterface/{}", n)) != 0;
    if (complete) write_table1(recorder, table);
    benchmark::Shutdown();
    return 0;
}
