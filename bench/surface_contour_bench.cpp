// Benchmarks of contouring in space (paper §2 with d = 3, Tables 2 and 3 in 3D): the exact
// signed distance of a torus (smooth, non-convex, genus one) contoured linearly at K = 3..8 and
// adaptively to convergence with K/ε = 3/1e−2 ... 6/1e−5, on one thread. Writes
// docs/tables/table2_3d.md and table3_3d.md itself.
//
// Usage: surface_contour_bench [--tables DIR] [google-benchmark flags]
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <string>

#include "bench_support.hpp"
#include "slc/contour/surface_contour.hpp"
#include "slc/core/parallel.hpp"

namespace {

using namespace slc;
using namespace slc::bench;

/// The torus about the z axis, radii 0.55 and 0.2, moved off the octree's planes.
constexpr double major_radius = 0.55, minor_radius = 0.2;
const Vec3 centre{0.013, -0.007, 0.005};
const Box3 domain = Box3::centered_cube(1.0);

double torus_distance(Vec3 x) {
    const Vec3 p = x - centre;
    return std::hypot(std::hypot(p.x, p.y) - major_radius, p.z) - minor_radius;
}

/// The largest |F| over the vertices, the edge midpoints and the centroids.
double surface_error(const Surface& s) {
    double worst = 0.0;
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        for (const Vec3 p : {tri.a, 0.5 * (tri.a + tri.b), 0.5 * (tri.b + tri.c),
                             0.5 * (tri.c + tri.a), (tri.a + tri.b + tri.c) / 3.0})
            worst = std::max(worst, std::abs(torus_distance(p)));
    }
    return worst;
}

void run(benchmark::State& state, const SurfaceContourOptions& o) {
    const auto g = pointwise<Vec3>(torus_distance);
    SurfaceContour result;
    for (auto _ : state) {
        result = contour_surface(g, domain, o);
        benchmark::DoNotOptimize(result);
    }
    const SurfaceContourStats& s = result.stats;
    state.counters["cells"] = static_cast<double>(s.cells);
    state.counters["tetrahedra"] = static_cast<double>(s.tetrahedra);
    state.counters["triangles"] = static_cast<double>(s.triangles);
    state.counters["error"] = surface_error(result.surface);
    state.counters["evals_per_vertex"] = s.g_evals_per_vertex;
    state.counters["passes"] = s.passes;
    state.counters["converged"] = s.converged ? 1.0 : 0.0;
    state.counters["genus"] = static_cast<double>(genus(result.surface));
}

/// Every tree point evaluated (range(1) = 0 or 2), or the points a distance (δ = 0) settles left
/// out (1).
std::optional<double> slack_of(const benchmark::State& state) {
    return state.range(1) == 1 ? std::optional(0.0) : std::nullopt;
}

void BM_LinearSurface(benchmark::State& state) {
    run(state, {.depth = static_cast<int>(state.range(0)), .distance_slack = slack_of(state)});
}

void BM_AdaptiveSurface(benchmark::State& state) {
    const int k = static_cast<int>(state.range(0));
    // range(1) = 2: the vertices roots to η = 10⁻¹⁰ rather than the default ε/100.
    run(state, {.depth = k,
                .refine_passes = SurfaceContourOptions::until_converged,
                .eps = std::pow(10.0, -(k - 1)),
                .eta = state.range(1) == 2 ? std::optional(1e-10) : std::nullopt,
                .distance_slack = slack_of(state)});
}

BENCHMARK(BM_LinearSurface)
    ->ArgsProduct({benchmark::CreateDenseRange(3, 8, 1), {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AdaptiveSurface)
    ->ArgsProduct({benchmark::CreateDenseRange(3, 6, 1), {0, 1, 2}})
    ->Unit(benchmark::kMillisecond);

const std::string setup =
    "The exact signed distance of a torus about the z axis (radii 0.55 and 0.2, centre (0.013, "
    "−0.007, 0.005)) in [−1, 1]³, contoured by `contour_surface` on one thread, γ = 1, η "
    "unset (`resolved_eta`: 1e−10 for the linear contour, ε/100 when refining). Error: the "
    "largest |F| over the vertices, the edge midpoints and the centroids of the triangles. CPU "
    "time, the least of the repetitions. The genus of every result is "
    "checked: ";

const std::string settled_note =
    "The last two columns contour the same distance with `distance_slack` δ = 0 (the bound "
    "|G(x) − G(y)| ≤ |x − y| of a distance): tree points whose neighbours already settle their "
    "sign and split test are not evaluated, and the surface is the same to the last bit (unit "
    "test `SurfaceContour.DistanceSlackSkipsFarPointsAndChangesNothing`).\n\n";

double counter(const Recorder& rec, const std::string& name, const char* what) {
    return rec.results.at(name).counters.at(what).value;
}

std::string genus_note(const Recorder& rec, const char* prefix, int first, int last) {
    bool all_one = true;
    for (int k = first; k <= last; ++k)
        for (int variant = 0; rec.results.count(fmt::format("{}/{}/{}", prefix, k, variant));
             ++variant)
            all_one &= counter(rec, fmt::format("{}/{}/{}", prefix, k, variant), "genus") == 1.0;
    return all_one ? "1 (the torus's) in every row.\n\n" : "NOT 1 in some row: see the table.\n\n";
}

void write_table2(const Recorder& rec, const std::string& path) {
    std::string md =
        "# Table 2 in 3D: linear contouring of a surface (P = 0)\n\n"
        "Written by `bench/surface_contour_bench.cpp` (run `scripts/bench`); do not edit by "
        "hand.\n\n" +
        setup + genus_note(rec, "BM_LinearSurface", 3, 8) +
        "The linear contour is the zero set of the piecewise-linear interpolant on the octree's "
        "tetrahedra. Its error should fall at second order in the finest cell edge h = 2^(1−K): "
        "the order column is log₂ of the ratio of successive errors. " +
        settled_note +
        "| K | cells | tetrahedra | triangles | error | order | G evals / vertex | cpu ms | "
        "G evals / vertex, δ = 0 | cpu ms, δ = 0 |\n"
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    double previous = 0.0;
    for (int k = 3; k <= 8; ++k) {
        const std::string name = fmt::format("BM_LinearSurface/{}/0", k);
        const std::string settled = fmt::format("BM_LinearSurface/{}/1", k);
        const double error = counter(rec, name, "error");
        md += fmt::format(
            "| {} | {:.0f} | {:.0f} | {:.0f} | {:.3g} | {} | {:.2f} | {:.3g} | {:.2f} | {:.3g} "
            "|\n",
            k, counter(rec, name, "cells"), counter(rec, name, "tetrahedra"),
            counter(rec, name, "triangles"), error,
            previous > 0.0 ? fmt::format("{:.2f}", std::log2(previous / error)) : std::string(""),
            counter(rec, name, "evals_per_vertex"), 1e3 * seconds(rec.results.at(name)),
            counter(rec, settled, "evals_per_vertex"), 1e3 * seconds(rec.results.at(settled)));
        previous = error;
    }
    std::ofstream(path) << md;
}

void write_table3(const Recorder& rec, const std::string& path) {
    std::string md =
        "# Table 3 in 3D: adaptive contouring of a surface\n\n"
        "Written by `bench/surface_contour_bench.cpp` (run `scripts/bench`); do not edit by "
        "hand.\n\n" +
        setup + genus_note(rec, "BM_AdaptiveSurface", 3, 6) +
        "Refinement runs until no edge midpoint or centroid has |G| > ε (`until_converged`). A "
        "surface within ε needs triangles of edge about √(ε/κ), so their number should grow as "
        "1/ε: the column triangles × ε then stays about constant. The vertices are roots of G to "
        "ε/100, the default η when refining: the last column finds them to η = 1e−10 instead "
        "(every tree point evaluated), as the paper's root finder does. " +
        settled_note +
        "| K / ε | triangles | error | converged | passes | G evals / vertex | cpu ms | "
        "triangles × ε | G evals / vertex, δ = 0 | cpu ms, δ = 0 | G evals / vertex, η = "
        "1e−10 |\n"
        "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (int k = 3; k <= 6; ++k) {
        const std::string name = fmt::format("BM_AdaptiveSurface/{}/0", k);
        const std::string settled = fmt::format("BM_AdaptiveSurface/{}/1", k);
        const std::string tight = fmt::format("BM_AdaptiveSurface/{}/2", k);
        const double eps = std::pow(10.0, -(k - 1));
        const double triangles = counter(rec, name, "triangles");
        md += fmt::format(
            "| {} / 1e−{} | {:.0f} | {:.3g} | {} | {:.0f} | {:.2f} | {:.3g} | {:.3g} | {:.2f} | "
            "{:.3g} | {:.2f} |\n",
            k, k - 1, triangles, counter(rec, name, "error"),
            counter(rec, name, "converged") == 1.0 ? "yes" : "no", counter(rec, name, "passes"),
            counter(rec, name, "evals_per_vertex"), 1e3 * seconds(rec.results.at(name)),
            triangles * eps, counter(rec, settled, "evals_per_vertex"),
            1e3 * seconds(rec.results.at(settled)), counter(rec, tight, "evals_per_vertex"));
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
    if (r.count("BM_LinearSurface/3/0") != 0 && r.count("BM_LinearSurface/8/1") != 0)
        write_table2(recorder, tables + "/table2_3d.md");
    if (r.count("BM_AdaptiveSurface/3/0") != 0 && r.count("BM_AdaptiveSurface/6/2") != 0)
        write_table3(recorder, tables + "/table3_3d.md");
    benchmark::Shutdown();
    return 0;
}
