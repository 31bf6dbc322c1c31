// The cost of the Mullins–Sekerka law's speeds against the number of points: p three-lobed
// particles of 64 vertices each on a lattice (M = 64p samples), the whole evaluation (splines,
// the system set up and solved, the stiff modes filtered, V read back at the vertices), summed
// dense and fast. One core. Writes docs/tables/potential.md.
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

/// p particles, summed as `how` says.
void BM_MullinsSekerkaSpeeds(benchmark::State& state, int p, Summation how) {
    const Interface curves = particles(p);
    MullinsSekerka law;
    law.set_summation(how);
    for (auto _ : state) {
        std::vector<double> v = law.normal_speeds(curves, 1e-5);
        benchmark::DoNotOptimize(v.data());
    }
    state.counters["samples"] = static_cast<double>(curves.size());
}

/// The dense system up to 128 particles (8,192 samples; it is refused beyond 10,000), the fast
/// summation up to 1,024 (65,536).
const int dense_sizes[] = {4, 8, 16, 32, 64, 128};
const int fast_sizes[] = {4, 8, 16, 32, 64, 128, 256, 512, 1024};

void register_benchmarks() {
    for (const int p : dense_sizes)
        benchmark::RegisterBenchmark(fmt::format("BM_MullinsSekerkaSpeeds/{}/dense", p).c_str(),
                                     BM_MullinsSekerkaSpeeds, p, Summation::dense)
            ->Unit(benchmark::kMillisecond);
    for (const int p : fast_sizes)
        benchmark::RegisterBenchmark(fmt::format("BM_MullinsSekerkaSpeeds/{}/fast", p).c_str(),
                                     BM_MullinsSekerkaSpeeds, p, Summation::fast)
            ->Unit(benchmark::kMillisecond);
}

void write_table(const Recorder& rec, const std::string& path) {
    std::string md =
        "# The potential laws' cost against the number of points\n\n"
        "Written by `bench/potential_bench.cpp` (run `scripts/bench`); do not edit by hand.\n\n"
        "`mullins-sekerka`'s speeds of p three-lobed particles (radius 0.05, 64 vertices each, "
        "0.2 apart on a square lattice): splines, the single-layer system set up and solved, the "
        "stiff modes filtered, V read back at the vertices. A step evaluates them twice "
        "(predictor and corrector). Dense: the matrix assembled and factored (LU, up to 600 "
        "samples) or GMRES over it (beyond; refused beyond 10,000 samples). Fast: GMRES over the "
        "fast summation (a treecode of the logarithm, Kress's correction by FFT). `slc` sums "
        "dense up to 3,000 samples and fast beyond. CPU seconds on one core; the last two "
        "columns are the times over M² and over M log₂ M.\n\n"
        "| particles | samples M | dense, s | fast, s | dense s / M² | fast s / (M log₂ M) |\n"
        "|---|---|---|---|---|---|\n";
    for (const int p : fast_sizes) {
        const auto& fast = rec.results.at(fmt::format("BM_MullinsSekerkaSpeeds/{}/fast", p));
        const double m = fast.counters.at("samples").value;
        const auto dense = rec.results.find(fmt::format("BM_MullinsSekerkaSpeeds/{}/dense", p));
        const std::string dense_s =
            dense == rec.results.end() ? "—" : fmt::format("{:.3g}", seconds(dense->second));
        const std::string dense_m2 = dense == rec.results.end()
                                         ? "—"
                                         : fmt::format("{:.2e}", seconds(dense->second) / (m * m));
        md += fmt::format("| {} | {:.0f} | {} | {:.3g} | {} | {:.2e} |\n", p, m, dense_s,
                          seconds(fast), dense_m2, seconds(fast) / (m * std::log2(m)));
    }
    std::ofstream(path) << md;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string table = take_flag(argc, argv, "--table", "docs/tables/potential.md");
    slc::set_thread_count(1);
    benchmark::Initialize(&argc, argv);
    register_benchmarks();
    Recorder recorder;
    benchmark::RunSpecifiedBenchmarks(&recorder);
    bool all = true;
    for (const int p : dense_sizes)
        all =
            all && recorder.results.count(fmt::format("BM_MullinsSekerkaSpeeds/{}/dense", p)) != 0;
    for (const int p : fast_sizes)
        all = all && recorder.results.count(fmt::format("BM_MullinsSekerkaSpeeds/{}/fast", p)) != 0;
    if (all) write_table(recorder, table);
    benchmark::Shutdown();
    return 0;
}
