// Benchmarks of the surface distance tree (paper §1.3 with d = 3, a 3D Table 1): octree cells,
// build time and closest-point query time for icospheres of N = 1280..1310720 triangles, beside
// a brute-force baseline (small N) and, when CGAL is found at configure time, CGAL's AABB_tree
// closest-point queries on the same triangles and points. Single-threaded, so that the times
// compare. CGAL's answers are checked against ours (counter "max_gap", the largest difference
// of the two distances relative to the sphere's radius).
//
// Usage: surface_distance_bench [google-benchmark flags]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "slc/core/parallel.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/geometry/surface_shapes.hpp"

#ifdef SLC_HAVE_CGAL
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#endif

namespace {

using namespace slc;

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

void BM_SurfaceTreeBuild(benchmark::State& state) {
    set_thread_count(1);
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

void BM_SurfaceTreeQuery(benchmark::State& state) {
    set_thread_count(1);
    const Surface& s = sphere_of(static_cast<int>(state.range(0)));
    const SurfaceDistanceTree tree(s, domain,
                                   {.depth = SurfaceDistanceTree::default_depth(s, domain)});
    const auto& xs = near_points();
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
        CgalTree tree(triangles.cbegin(), triangles.cend());
        tree.accelerate_distance_queries();
        benchmark::DoNotOptimize(&tree);
    }
    state.counters["triangles"] = static_cast<double>(s.size());
}

void BM_CgalQuery(benchmark::State& state) {
    const Surface& s = sphere_of(static_cast<int>(state.range(0)));
    const CgalTriangles triangles = cgal_triangles(s);
    CgalTree tree(triangles.cbegin(), triangles.cend());
    tree.accelerate_distance_queries();
    const auto& xs = near_points();
    for (auto _ : state) {
        double sum = 0.0;
        for (const Vec3 x : xs) {
            const Kernel::Point_3 p = tree.closest_point(Kernel::Point_3(x.x, x.y, x.z));
            sum += p.x();
        }
        benchmark::DoNotOptimize(sum);
    }
    // Agreement of the two (unsigned) distances, outside the timed loop.
    const SurfaceDistanceTree ours(s, domain,
                                   {.depth = SurfaceDistanceTree::default_depth(s, domain)});
    double gap = 0.0;
    for (const Vec3 x : xs) {
        const double theirs = std::sqrt(tree.squared_distance(Kernel::Point_3(x.x, x.y, x.z)));
        gap = std::max(gap, std::abs(theirs - std::abs(ours.closest_point(x).distance)) / 0.5);
    }
    state.counters["triangles"] = static_cast<double>(s.size());
    state.counters["max_gap"] = gap;
    state.counters["per_query"] = benchmark::Counter(
        static_cast<double>(xs.size()),
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_CgalBuild)->DenseRange(3, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CgalQuery)->DenseRange(3, 8)->Unit(benchmark::kMillisecond);
#endif

BENCHMARK(BM_SurfaceTreeBuild)->DenseRange(3, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceTreeQuery)->DenseRange(3, 8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BruteForceQuery)->DenseRange(3, 5)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
