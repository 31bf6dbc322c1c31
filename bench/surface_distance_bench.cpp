// Benchmarks of the surface distance tree (paper §1.3 with d = 3, a 3D Table 1): octree cells,
// build time and closest-point query time for icospheres of N = 1280..1310720 triangles, beside
// a brute-force baseline (small N) and, when CGAL is found at configure time, CGAL's AABB_tree
// build and closest-point queries on the same triangles and points. Single-threaded, so that the
// times compare. CGAL's answers are checked against ours (counter "max_gap", the largest
// difference of the two distances relative to the sphere's radius). Writes
// docs/tables/table1_3d.md itself.
//
// Usage: surface_distance_bench [--table PATH] [google-benchmark flags]
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "slc/core/memory.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/geometry/validate_surface.hpp"

#ifdef SLC_HAVE_CGAL
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#endif

namespace {

using namespace slc;
using namespace slc::bench;

/// The icospheres measured: 20·4^k triangles for k = 3..8 (1280..1310720).
constexpr int first_level = 3;
constexpr int last_level = 8;

const Box3 domain = Box3::centered_cube(1.0);

/// The icosphere of radius 0.5 near the origin with 20·4^k triangles.
const Surface& sphere_of(int k) {
    static std::map<int, Surface> cache;
    auto [it, added] = cache.try_emplace(k);
    if (added) it->second = sphere({0.013, -0.007, 0.005}, 0.5, k);
    return it->second;
}

/// 10^4 deterministic query points within 0.05 of the sphere: the points a time step asks about.
const std::vector<Vec3>& near_points() {
    static const std::vector<Vec3> xs = [] {
        std::mt19937 rng(42);
        std::normal_distribution<double> g(0.0, 1.0);
        std::uniform_real_distribution<double> r(0.45, 0.55);
        std::vector<Vec3> out;
        for (int i = 0; i < 10000; ++i) {
            const Vec3 d{g(rng), g(rng), g(rng)};
            out.push_back(Vec3{0.013, -0.007, 0.005} + r(rng) / norm(d) * d);
        }
        return out;
    }();
    return xs;
}

/// 10^3 deterministic query points within 0.1 of the sphere's centre, where every patch of the
/// sphere is nearly as near as the nearest (a distance field on a grid asks about such points).
const std::vector<Vec3>& deep_points() {
    static const std::vector<Vec3> xs = [] {
        std::mt19937 rng(43);
        std::uniform_real_distribution<double> u(-0.1, 0.1);
        std::vector<Vec3> out;
        for (int i = 0; i < 1000; ++i)
            out.push_back(Vec3{0.013, -0.007, 0.005} + Vec3{u(rng), u(rng), u(rng)});
        return out;
    }();
    return xs;
}

/// The deep queries stop at 20·4^6 triangles: a query there scans a large part of the sphere.
constexpr int last_deep_level = 6;

void BM_SurfaceTreeBuild(benchmark::State& state) {
    const Surface& s = sphere_of(static_cast<int>(state.range(0)));
    const int depth = SurfaceDistanceTree::default_depth(s, domain);
    std::size_t cells = 0;
    for (auto _ : state) {
        const SurfaceDistanceTree tree(s, domain, {.depth = depth});
        cells = tree.tree().size();
        benchmark::DoNotOptimize(cells);
    }
    state.counters["triangles"] = static_cast<double>(s.size());
    state.counters["depth"] = depth;
    state.counters["cells"] = static_cast<double>(cells);
}

/// What every surface a user gives costs before its tree: the checks of prepare_surface (closed,
/// manifold, no two triangles meeting, components oriented by their nesting).
void BM_PrepareSurface(benchmark::State& state) {
    const Surface& s = sphere_of(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        state.PauseTiming();
        Surface raw = s;
        state.ResumeTiming();
        const PreparedSurface prepared = prepare_surface(std::move(raw));
        benchmark::DoNotOptimize(prepared.surface.size());
    }
    state.counters["triangles"] = static_cast<double>(s.size());
}

/// The tree's signed closest points of xs, timed.
void tree_queries(benchmark::State& state, const std::vector<Vec3>& xs) {
    const Surface& s = sphere_of(static_cast<int>(state.range(0)));
    const SurfaceDistanceTree tree(s, domain,
                                   {.depth = SurfaceDistanceTree::default_depth(s, domain)});
    for (auto _ : state) {
        double sum = 0.0;
        for (const Vec3 x : xs) sum += tree.closest_point(x).distance;
        benchmark::DoNotOptimize(sum);
    }
    state.counters["triangles"] = static_cast<double>(s.size());
    state.counters["per_query"] = benchmark::Counter(
        static_cast<double>(xs.size()),
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_SurfaceTreeQuery(benchmark::State& state) { tree_queries(state, near_points()); }

void BM_SurfaceTreeDeepQuery(benchmark::State& state) { tree_queries(state, deep_points()); }

void BM_BruteForceQuery(benchmark::State& state) {
    const Surface& s = sphere_of(static_cast<int>(state.range(0)));
    const PseudoNormals normals = pseudo_normals(s);
    const auto& xs = near_points();
    for (auto _ : state) {
        double sum = 0.0;
        for (std::size_t i = 0; i < 100; ++i)
            sum += closest_point_brute_force(s, normals, xs[i]).distance;
        benchmark::DoNotOptimize(sum);
    }
    state.counters["triangles"] = static_cast<double>(s.size());
    state.counters["per_query"] = benchmark::Counter(
        100.0, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

#ifdef SLC_HAVE_CGAL
using Kernel = CGAL::Simple_cartesian<double>;
using CgalTriangles = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, CgalTriangles::const_iterator>;
using CgalTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

CgalTriangles cgal_triangles(const Surface& s) {
    CgalTriangles out;
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        auto p = [](Vec3 v) { return Kernel::Point_3(v.x, v.y, v.z); };
        out.emplace_back(p(tri.a), p(tri.b), p(tri.c));
    }
    return out;
}

void BM_CgalBuild(benchmark::State& state) {
    const Surface& s = sphere_of(static_cast<int>(state.range(0)));
    const CgalTriangles triangles = cgal_triangles(s);
    for (auto _ : state) {
        // The constructor only stores the triangles; build() makes the hierarchy, which CGAL
        // would otherwise make at the first query.
        CgalTree tree(triangles.cbegin(), triangles.cend());
        tree.build();
        tree.accelerate_distance_queries();
        benchmark::DoNotOptimize(&tree);
    }
    state.counters["triangles"] = static_cast<double>(s.size());
}

/// CGAL's closest points of xs, timed; the largest difference of the two (unsigned) distances
/// relative to the radius, outside the timed loop, in counter max_gap.
void cgal_queries(benchmark::State& state, const std::vector<Vec3>& xs) {
    const Surface& s = sphere_of(static_cast<int>(state.range(0)));
    const CgalTriangles triangles = cgal_triangles(s);
    CgalTree tree(triangles.cbegin(), triangles.cend());
    tree.build();
    tree.accelerate_distance_queries();
    for (auto _ : state) {
        double sum = 0.0;
        for (const Vec3 x : xs) {
            const Kernel::Point_3 p = tree.closest_point(Kernel::Point_3(x.x, x.y, x.z));
            sum += p.x();
        }
        benchmark::DoNotOptimize(sum);
    }
    const SurfaceDistanceTree ours(s, domain,
                                   {.depth = SurfaceDistanceTree::default_depth(s, domain)});
    double gap = 0.0;
    for (const Vec3 x : xs) {
        const double theirs = std::sqrt(tree.squared_distance(Kernel::Point_3(x.x, x.y, x.z)));
        gap = std::max(gap, std::abs(theirs - std::abs(ours.closest_point(x).distance)) / 0.5);
    }
    state.counters["triangles"] = static_cast<double>(s.size());
    state.counters["max_gap"] = gap;
}

void BM_CgalQuery(benchmark::State& state) { cgal_queries(state, near_points()); }

void BM_CgalDeepQuery(benchmark::State& state) { cgal_queries(state, deep_points()); }

BENCHMARK(BM_CgalBuild)->DenseRange(first_level, last_level)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CgalQuery)->DenseRange(first_level, last_level)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CgalDeepQuery)
    ->DenseRange(first_level, last_deep_level)
    ->Unit(benchmark::kMillisecond);
constexpr bool have_cgal = true;
#else
constexpr bool have_cgal = false;
#endif

BENCHMARK(BM_SurfaceTreeBuild)->DenseRange(first_level, last_level)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PrepareSurface)->DenseRange(first_level, last_level)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceTreeQuery)->DenseRange(first_level, last_level)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceTreeDeepQuery)
    ->DenseRange(first_level, last_deep_level)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BruteForceQuery)->DenseRange(first_level, 5)->Unit(benchmark::kMillisecond);

/// A run's time as text in the given unit (1e3: ms, 1e6: µs), or "—" when it was not run.
std::string time_of(const Recorder& rec, const std::string& name, double unit) {
    const auto it = rec.results.find(name);
    return it == rec.results.end() ? "—" : fmt::format("{:.3g}", seconds(it->second) * unit);
}

/// Seconds per query of a run that counts them (counter per_query), or a negative number.
double per_query(const Recorder& rec, const std::string& name) {
    const auto it = rec.results.find(name);
    if (it == rec.results.end()) return -1.0;
    return seconds(it->second) / static_cast<double>(near_points().size());
}

void write_table(const Recorder& rec, const std::string& path) {
    std::string md =
        "# Table 1 in 3D: surface distance tree beside CGAL's AABB_tree\n\n"
        "Written by `bench/surface_distance_bench.cpp` (run `scripts/bench`); do not edit by "
        "hand.\n\n"
        "Icospheres of radius 0.5 near the origin with N = 20·4^k triangles in the domain "
        "[−1, 1]³, the tree at its default depth (cells four to eight mean edges wide). CPU time "
        "on one thread, the least of the repetitions. Build: everything a query needs — the "
        "pseudo-normals, the triangle hierarchy, the octree and its cells' triangle lists "
        "(ours); the AABB tree, by `build()` (which CGAL would otherwise defer to the first "
        "query), and the search tree of `accelerate_distance_queries()` (CGAL). Query: one "
        "closest point (ours also signed) for each of 10^4 fixed points within 0.05 of the "
        "sphere. Deep query: one closest point for each of 10^3 fixed points within 0.1 of the "
        "sphere's centre (up to N = 81920), where a patch's bounding box reaches towards the point "
        "and bounds nothing; the hierarchy's slabs across the patches' normals do. Brute force: a "
        "scan of every triangle. The last build column is the build time divided by N log₂ N: "
        "constant when the build is O(N log N). Validation: `prepare_surface`, which every "
        "surface a user gives passes before its tree is built (closed, manifold, no two "
        "triangles meeting, components oriented by their nesting); CGAL checks none of it.\n\n";
    if (!have_cgal)
        md +=
            "NOTE: CGAL was not found when this benchmark was built (`apt-get install "
            "libcgal-dev`, or `scripts/bench`), so its columns are empty.\n\n";
    md +=
        "| N | depth | cells | build ms | CGAL build ms | build ÷ CGAL | build ns / N log₂ N "
        "| validation ms | build + validation ÷ CGAL "
        "| query µs | CGAL query µs | query ÷ CGAL | deep query µs | CGAL deep query µs | brute "
        "force µs |\n"
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    double gap = 0.0;
    for (int k = first_level; k <= last_level; ++k) {
        const auto& build = rec.results.at(fmt::format("BM_SurfaceTreeBuild/{}", k));
        const double n = build.counters.at("triangles").value;
        const double ours_build = seconds(build);
        const double ours_query = per_query(rec, fmt::format("BM_SurfaceTreeQuery/{}", k));
        const auto cgal_build = rec.results.find(fmt::format("BM_CgalBuild/{}", k));
        const double cgal_query = per_query(rec, fmt::format("BM_CgalQuery/{}", k));
        const auto cgal_run = rec.results.find(fmt::format("BM_CgalQuery/{}", k));
        if (cgal_run != rec.results.end())
            gap = std::max(gap, cgal_run->second.counters.at("max_gap").value);
        const auto cgal_deep = rec.results.find(fmt::format("BM_CgalDeepQuery/{}", k));
        if (cgal_deep != rec.results.end())
            gap = std::max(gap, cgal_deep->second.counters.at("max_gap").value);
        // µs a deep query: the run's time over its 10^3 points.
        auto deep_us = [&](const char* name) {
            const auto it = rec.results.find(fmt::format("{}/{}", name, k));
            return it == rec.results.end() ? std::string()
                                           : fmt::format("{:.3g}", seconds(it->second) * 1e3);
        };
        const std::string build_ratio =
            cgal_build == rec.results.end()
                ? "—"
                : fmt::format("{:.2f}", ours_build / seconds(cgal_build->second));
        const double validation = seconds(rec.results.at(fmt::format("BM_PrepareSurface/{}", k)));
        const std::string checked_ratio =
            cgal_build == rec.results.end()
                ? "—"
                : fmt::format("{:.2f}", (ours_build + validation) / seconds(cgal_build->second));
        const std::string query_ratio =
            cgal_query > 0.0 ? fmt::format("{:.2f}", ours_query / cgal_query) : "—";
        const auto brute = rec.results.find(fmt::format("BM_BruteForceQuery/{}", k));
        const std::string brute_us =
            brute == rec.results.end() ? "" : fmt::format("{:.3g}", seconds(brute->second) * 1e4);
        md += fmt::format(
            "| {:.0f} | {:.0f} | {:.0f} | {:.3g} | {} | {} | {:.1f} | {:.3g} | {} | {:.3g} | {} | "
            "{} | {} | {} | {} |\n",
            n, build.counters.at("depth").value, build.counters.at("cells").value, ours_build * 1e3,
            time_of(rec, fmt::format("BM_CgalBuild/{}", k), 1e3), build_ratio,
            ours_build / (n * std::log2(n)) * 1e9, validation * 1e3, checked_ratio,
            ours_query * 1e6, cgal_query > 0.0 ? fmt::format("{:.3g}", cgal_query * 1e6) : "—",
            query_ratio, deep_us("BM_SurfaceTreeDeepQuery"), deep_us("BM_CgalDeepQuery"), brute_us);
    }
    if (have_cgal)
        md += fmt::format(
            "\nThe two agree on every query point: the largest difference of the distances is "
            "{:.1e} of the radius.\n",
            gap);
    std::ofstream(path) << md;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string table = take_flag(argc, argv, "--table", "docs/tables/table1_3d.md");
    slc::set_thread_count(1);
    slc::keep_freed_memory();  // as the slc tool does: the timings are the tool's
    benchmark::Initialize(&argc, argv);
    Recorder recorder;
    benchmark::RunSpecifiedBenchmarks(&recorder);
    // The table needs every row: a filtered run (--benchmark_filter) leaves it as it was.
    bool complete = true;
    for (int k = first_level; k <= last_level; ++k) {
        for (const char* name : {"BM_SurfaceTreeBuild", "BM_PrepareSurface", "BM_SurfaceTreeQuery",
                                 "BM_CgalBuild", "BM_CgalQuery"}) {
            if (!have_cgal && std::string(name).starts_with("BM_Cgal")) continue;
            complete = complete && recorder.results.count(fmt::format("{}/{}", name, k)) != 0;
        }
    }
    if (complete) write_table(recorder, table);
    benchmark::Shutdown();
    return 0;
}
