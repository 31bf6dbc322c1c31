// Benchmarks of contouring in space (paper §2 with d = 3, Tables 2 and 3 in 3D): the exact
// signed distance of a torus (smooth, non-convex, genus one) contoured linearly at K = 3..8 and
// adaptively to convergence with K/ε = 3/1e−2 ... 6/1e−5, on one thread. Writes
// docs/tables/table2_3d.md and table3_3d.md itself. When OpenVDB is found at configure time, the
// same distance sampled in a narrow band and meshed by OpenVDB's volumeToMesh at voxels 1/32 to
// 1/256, beside slc's contours of the same accuracy: the region `contour-openvdb` of the page
// (docs/performance.md).
//
// Usage: surface_contour_bench [--tables DIR] [--page PATH] [--check-page]
//                              [google-benchmark flags]
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "doc_regions.hpp"
#include "slc/contour/surface_contour.hpp"
#include "slc/core/memory.hpp"
#include "slc/core/parallel.hpp"

#ifdef SLC_HAVE_OPENVDB
#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>
#endif

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

/// The largest |F| over the centroids of the triangles: the measure both sides of the
/// comparison with OpenVDB share (OpenVDB's vertices are not on the surface, slc's are).
double centroid_error(const Surface& s) {
    double worst = 0.0;
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        worst = std::max(worst, std::abs(torus_distance((tri.a + tri.b + tri.c) / 3.0)));
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
    state.counters["centroid_error"] = centroid_error(result.surface);
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

#ifdef SLC_HAVE_OPENVDB
/// The torus's exact distance sampled by OpenVDB's rules for a level set (a narrow band of
/// ±3 voxels, the rest of the grid its sign by flood fill) at voxel 1/range(0), and meshed by
/// volumeToMesh (isovalue 0, adaptivity 0), all timed. The band is found block by block: a
/// block of 8³ voxels whose centre lies farther from the torus than the band and the block's
/// half-diagonal is skipped whole, so the sampling costs about the band's voxels.
void BM_OpenVdbSurface(benchmark::State& state) {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const double h = 1.0 / static_cast<double>(state.range(0));
    constexpr double band = 3.0;
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    for (auto _ : state) {
        auto grid = openvdb::FloatGrid::create(static_cast<float>(band * h));
        grid->setTransform(openvdb::math::Transform::createLinearTransform(h));
        grid->setGridClass(openvdb::GRID_LEVEL_SET);
        auto acc = grid->getAccessor();
        // The torus's box and the band, in voxels, rounded out to whole blocks.
        const Vec3 reach{major_radius + minor_radius + band * h,
                         major_radius + minor_radius + band * h, minor_radius + band * h};
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = static_cast<int>(std::floor((centre[a] - reach[a]) / h / 8.0)) * 8;
            hi[a] = static_cast<int>(std::ceil((centre[a] + reach[a]) / h / 8.0)) * 8;
        }
        const double skip = band * h + 8.0 * h * std::sqrt(3.0) / 2.0;
        for (int bi = lo[0]; bi < hi[0]; bi += 8)
            for (int bj = lo[1]; bj < hi[1]; bj += 8)
                for (int bk = lo[2]; bk < hi[2]; bk += 8) {
                    const Vec3 middle{(bi + 3.5) * h, (bj + 3.5) * h, (bk + 3.5) * h};
                    if (std::abs(torus_distance(middle)) > skip) continue;
                    for (int i = bi; i < bi + 8; ++i)
                        for (int j = bj; j < bj + 8; ++j)
                            for (int k = bk; k < bk + 8; ++k) {
                                const double d = torus_distance({i * h, j * h, k * h});
                                if (std::abs(d) < band * h)
                                    acc.setValue(openvdb::Coord(i, j, k), static_cast<float>(d));
                            }
                }
        openvdb::tools::signedFloodFill(grid->tree());
        points.clear();
        triangles.clear();
        quads.clear();
        openvdb::tools::volumeToMesh(*grid, points, triangles, quads, 0.0, 0.0);
        benchmark::DoNotOptimize(points.data());
    }
    // As a surface of triangles: each quad cut along a diagonal.
    Surface s;
    for (const auto& p : points) s.vertices.push_back({p.x(), p.y(), p.z()});
    for (const auto& t : triangles) s.triangles.push_back({t.x(), t.y(), t.z()});
    for (const auto& q : quads) {
        s.triangles.push_back({q.x(), q.y(), q.z()});
        s.triangles.push_back({q.x(), q.z(), q.w()});
    }
    state.counters["triangles"] = static_cast<double>(s.size());
    state.counters["centroid_error"] = centroid_error(s);
}
BENCHMARK(BM_OpenVdbSurface)->RangeMultiplier(2)->Range(32, 256)->Unit(benchmark::kMillisecond);
constexpr bool have_openvdb = true;
#else
constexpr bool have_openvdb = false;
#endif

/// slc's contours beside OpenVDB's: each slc row (linear at K = 5..8 and refined at K = 5,
/// ε = 1e−4, with δ = 0 as `slc contour --function torus` takes a distance) against OpenVDB's
/// voxel whose centroid error is nearest in ratio.
std::string openvdb_region(const Recorder& rec) {
    if (!have_openvdb)
        return "OpenVDB was not found when this benchmark was built (`apt-get install "
               "libopenvdb-dev`, or `scripts/bench`): nothing measured.\n";
    struct Peer {
        int voxels;
        double triangles, error, seconds;
    };
    std::vector<Peer> peers;
    for (int r = 32; r <= 256; r *= 2) {
        const auto& run = rec.results.at(fmt::format("BM_OpenVdbSurface/{}", r));
        peers.push_back({r, run.counters.at("triangles").value,
                         run.counters.at("centroid_error").value, seconds(run)});
    }
    std::string md =
        "| slc | triangles | centroid error | CPU ms | OpenVDB voxel | triangles | centroid error "
        "| CPU ms | slc ÷ OpenVDB, time | slc ÷ OpenVDB, triangles |\n"
        "|---|---:|---:|---:|---|---:|---:|---:|---:|---:|\n";
    auto ms = [](double s) {
        return s < 0.1 ? fmt::format("{:.3g}", s * 1e3) : fmt::format("{:.0f}", s * 1e3);
    };
    auto row = [&](const std::string& label, const std::string& name) {
        const auto& run = rec.results.at(name);
        const double error = run.counters.at("centroid_error").value;
        const double triangles = run.counters.at("triangles").value;
        const Peer& p = *std::min_element(peers.begin(), peers.end(), [&](auto& a, auto& b) {
            return std::abs(std::log(a.error / error)) < std::abs(std::log(b.error / error));
        });
        md += fmt::format(
            "| {} | {:.0f} | {:.3g} | {} | 1/{} | {:.0f} | {:.3g} | {} | {:.2f} | {:.2f} |\n",
            label, triangles, error, ms(seconds(run)), p.voxels, p.triangles, p.error,
            ms(p.seconds), seconds(run) / p.seconds, triangles / p.triangles);
    };
    for (int k = 5; k <= 8; ++k)
        row(fmt::format("K {}", k), fmt::format("BM_LinearSurface/{}/1", k));
    row("K 5, ε 1e−4", "BM_AdaptiveSurface/5/1");
    return md;
}

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
    const std::string page = take_flag(argc, argv, "--page", "docs/performance.md");
    if (take_switch(argc, argv, "--check-page")) {
        check_regions(page, {"contour-openvdb"});
        fmt::print(stderr, "{} holds every region this program writes\n", page);
        return 0;
    }
    require_regions(page, {"contour-openvdb"});  // before the measurements, not after
    slc::set_thread_count(1);
    slc::keep_freed_memory();  // as the slc tool does: the timings are the tool's
#ifdef SLC_HAVE_OPENVDB
    openvdb::initialize();
#endif
    benchmark::Initialize(&argc, argv);
    Recorder recorder;
    benchmark::RunSpecifiedBenchmarks(&recorder);
    const auto& r = recorder.results;
    if (r.count("BM_LinearSurface/3/0") != 0 && r.count("BM_LinearSurface/8/1") != 0)
        write_table2(recorder, tables + "/table2_3d.md");
    if (r.count("BM_AdaptiveSurface/3/0") != 0 && r.count("BM_AdaptiveSurface/6/2") != 0)
        write_table3(recorder, tables + "/table3_3d.md");
    if (r.count("BM_LinearSurface/8/1") != 0 && r.count("BM_AdaptiveSurface/5/1") != 0 &&
        (!have_openvdb || r.count("BM_OpenVdbSurface/256") != 0))
        write_regions(page, {{"contour-openvdb", openvdb_region(recorder)}});
    benchmark::Shutdown();
    return 0;
}
