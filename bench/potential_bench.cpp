// The cost of the Mullins–Sekerka law's speeds against the number of points: p three-lobed
// particles of 64 vertices each on a lattice (M = 64p samples), the whole evaluation (splines,
// the dense system assembled, factored or preconditioned, solved, the stiff modes filtered, V
// read back at the vertices). LU up to 600 samples, GMRES beyond. One core. Writes
// docs/tables/potential.md.
//
// Usage: potential_bench [--table PATH] [google-benchmark flags]
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "slc/core/parallel.hpp"
#include "slc/velocity/potential_laws.hpp"

namespace {

using namespace slc;
using namespace slc::bench;

/// p particles of radius 0.05 (1 + 0.1 cos 3θ), 0.2 apart on a square lattice, 64 vertices each.
Interface particles(int p) {
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(p))));
    std::vector<std::vector<Vec2>> curves;
    for (int i = 0; i < p; ++i) {
        const Vec2 c{0.2 * (i % side), 0.2 * (i / side)};
        std::vector<Vec2> curve;
        for (int j = 0; j < 64; ++j) {
            const double a = 2 * std::numbers::pi * j / 64 + 0.7 * i;
            const double r = 0.05 * (1 + 0.1 * std::cos(3 * a));
            curve.push_back(c + r * Vec2{std::cos(a), std::sin(a)});
        }
        curves.push_back(curve);
    }
    return Interface(curves);
}

void BM_MullinsSekerkaSpeeds(benchmark::State& state) {
    const Interface curves = particles(static_cast<int>(state.range(0)));
    const MullinsSekerka law;
    for (auto _ : state) {
        std::vector<double> v = law.normal_speeds(curves, 1e-5);
        benchmark::DoNotOptimize(v.data());
    }
    state.counters["samples"] = static_cast<double>(curves.size());
}
BENCHMARK(BM_MullinsSekerkaSpeeds)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Unit(benchmark::kMillisecond);

const int sizes[] = {4, 8, 16, 32, 64, 128};

void write_table(const Recorder& rec, const std::string& path) {
    std::string md =
        "# The potential laws' cost against the number of points\n\n"
        "Written by `bench/potential_bench.cpp` (run `scripts/bench`); do not edit by hand.\n\n"
        "`mullins-sekerka`'s speeds of p three-lobed particles (radius 0.05, 64 vertices each, "
        "0.2 apart on a square lattice): splines, the dense single-layer system assembled and "
        "factored (LU, up to 600 samples) or preconditioned curve by curve (GMRES, beyond), "
        "solved, the stiff modes filtered, V read back at the vertices. A step evaluates them "
        "twice (predictor and corrector). CPU seconds on one core; the last column is the time "
        "over M², constant where the dense system's O(M²) assembly and products dominate.\n\n"
        "| particles | samples M | s per evaluation | s / M² |\n"
        "|---|---|---|---|\n";
    for (const int p : sizes) {
        const auto& r = rec.results.at(fmt::format("BM_MullinsSekerkaSpeeds/{}", p));
        const double m = r.counters.at("samples").value;
        md += fmt::format("| {} | {:.0f} | {:.3g} | {:.2e} |\n", p, m, seconds(r),
                          seconds(r) / (m * m));
    }
    std::ofstream(path) << md;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string table = take_flag(argc, argv, "--table", "docs/tables/potential.md");
    slc::set_thread_count(1);
    benchmark::Initialize(&argc, argv);
    Recorder recorder;
    benchmark::RunSpecifiedBenchmarks(&recorder);
    bool all = true;
    for (const int p : sizes)
        all = all && recorder.results.count(fmt::format("BM_MullinsSekerkaSpeeds/{}", p)) != 0;
    if (all) write_table(recorder, table);
    benchmark::Shutdown();
    return 0;
}
