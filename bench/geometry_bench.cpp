// Benchmarks of the geometry modules (paper §3, §4.3): the embedded module (local mesh, exact F,
// ENO normals and curvature, interpolation) at M = 2^6..2^12 beside the cost of building the
// distance tree for the same curve, and the intrinsic module. Writes docs/tables/geometry.md.
//
// The curve is a smooth non-convex blob like the simple interface of the paper's Fig. 9, with M
// segments: about what a contouring tree of depth K = log2(M) − 1 resolves (M = 2^(K+1) is the
// paper's default), and the distance tree has depth L = K (P = 0).
//
// Usage: geometry_bench [--table PATH] [--figure PATH] [google-benchmark flags]
// --figure also draws the local mesh of a small case (docs/figures/geometry_local_mesh.png).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>

#include "bench_support.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry_modules/embedded.hpp"
#include "slc/geometry_modules/intrinsic.hpp"
#include "slc/io/render.hpp"

namespace {

using namespace slc;
using namespace slc::bench;

const Box domain = Box::centered_square(1.0);

/// The blob r(θ) = 0.55 (1 + 0.25 cos 2θ + 0.1 sin 3θ) with m segments, cached per m.
const Interface& blob(int m) {
    static std::map<int, Interface> cache;
    auto it = cache.find(m);
    if (it == cache.end()) {
        auto r = [](double t) {
            return 0.55 * (1 + 0.25 * std::cos(2 * t) + 0.1 * std::sin(3 * t));
        };
        it = cache.emplace(m, Interface({shapes::polar({0.02, -0.03}, r, m)})).first;
    }
    return it->second;
}

int tree_depth(int m) { return static_cast<int>(std::lround(std::log2(m))) - 1; }

void BM_EmbeddedGeometry(benchmark::State& state) {
    const int m = static_cast<int>(state.range(0)), s = static_cast<int>(state.range(1));
    const Interface& curves = blob(m);
    const DistanceTree tree(curves, domain, {.depth = tree_depth(m), .triangulate = false});
    const EmbeddedOptions options{.mesh = m, .eno_order = 3, .smoothing = s};
    for (auto _ : state) {
        const VertexGeometry g = embedded_geometry(tree, options);
        benchmark::DoNotOptimize(g.curvature.data());
    }
    const LocalMesh mesh(curves, domain.lo, domain.width() / m, 3 + s);
    state.counters["mesh_points"] = static_cast<double>(mesh.size());
    state.counters["x_intervals"] = static_cast<double>(mesh.rows().size());
    state.SetComplexityN(m);
}

void BM_BuildDistanceTree(benchmark::State& state) {
    const int m = static_cast<int>(state.range(0));
    const bool triangulate = state.range(1) != 0;
    for (auto _ : state) {
        const DistanceTree tree(blob(m), domain,
                                {.depth = tree_depth(m), .triangulate = triangulate});
        benchmark::DoNotOptimize(tree.tree().size());
    }
    state.SetComplexityN(m);
}

void BM_IntrinsicGeometry(benchmark::State& state) {
    const int m = static_cast<int>(state.range(0));
    for (auto _ : state) {
        const VertexGeometry g = intrinsic_geometry(blob(m));
        benchmark::DoNotOptimize(g.curvature.data());
    }
}

void mesh_sizes(benchmark::internal::Benchmark* b, std::initializer_list<int64_t> extra) {
    for (int64_t m = 64; m <= 4096; m *= 2) {
        if (extra.size() == 0) b->Args({m});
        for (int64_t e : extra) b->Args({m, e});
    }
}

BENCHMARK(BM_EmbeddedGeometry)->Apply([](auto* b) {
                                  mesh_sizes(b, {0, 2});
                              }) -> Unit(benchmark::kMillisecond);
BENCHMARK(BM_BuildDistanceTree)->Apply([](auto* b) {
                                   mesh_sizes(b, {0, 1});
                               }) -> Unit(benchmark::kMillisecond);
BENCHMARK(BM_IntrinsicGeometry)
    ->Apply([](auto* b) { mesh_sizes(b, {}); }) -> Unit(benchmark::kMillisecond);

void write_table(const Recorder& rec, const std::string& path) {
    std::string md =
        "# Geometry modules: embedded mesh against the distance tree\n\n"
        "Written by `bench/geometry_bench.cpp` (run `scripts/bench`); do not edit by hand.\n\n"
        "Curve: the blob r = 0.55 (1 + 0.25 cos 2θ + 0.1 sin 3θ) (a simple interface like the "
        "paper's "
        "Fig. 9) with M segments, domain [-1, 1]², h = 2/M. Embedded module: E = 3, S = 0 or 2 "
        "(range R = E + S), the whole module (local mesh, exact F from the tree, ENO normals and "
        "curvature, smoothing, interpolation to the vertices). Distance tree of depth L = log2(M) "
        "− 1, "
        "with and without its triangulation. CPU seconds on one core.\n\n"
        "| M | mesh points (S = 0) | embedded s (S = 0) | embedded s (S = 2) | tree s | "
        "triangulated tree s | embedded / tree | intrinsic s |\n"
        "|---|---|---|---|---|---|---|---|\n";
    for (int m = 64; m <= 4096; m *= 2) {
        const auto& e0 = rec.results.at(fmt::format("BM_EmbeddedGeometry/{}/0", m));
        const auto& e2 = rec.results.at(fmt::format("BM_EmbeddedGeometry/{}/2", m));
        const auto& t0 = rec.results.at(fmt::format("BM_BuildDistanceTree/{}/0", m));
        const auto& t1 = rec.results.at(fmt::format("BM_BuildDistanceTree/{}/1", m));
        const auto& in = rec.results.at(fmt::format("BM_IntrinsicGeometry/{}", m));
        md += fmt::format("| {} | {:.0f} | {:.2e} | {:.2e} | {:.2e} | {:.2e} | {:.2f} | {:.2e} |\n",
                          m, e0.counters.at("mesh_points").value, seconds(e0), seconds(e2),
                          seconds(t0), seconds(t1), seconds(e0) / seconds(t0), seconds(in));
    }
    std::ofstream(path) << md;
}

/// The paper's Fig. 9 for the blob at M = 64, E = 3, S = 0: the interface with the embedded
/// normals at every sixth vertex, and the local mesh of range R = 3 viewed as its x-intervals
/// and as its y-intervals, side by side.
void draw_local_mesh(const std::string& path) {
    const int m = 64;
    const Interface& curves = blob(128);
    const DistanceTree tree(curves, domain, {.depth = 6, .triangulate = false});
    const EmbeddedOptions options{.mesh = m, .eno_order = 3, .smoothing = 0};
    const EmbeddedFields fields = embedded_fields(tree, options);
    const VertexGeometry g = interpolate_geometry(fields, curves.points(), options.eno_order);
    std::vector<Vec2> at, normal;
    for (std::size_t i = 0; i < curves.size(); i += 6) {
        at.push_back(curves.point(i));
        normal.push_back(g.normals[i]);
    }
    const LocalMesh& mesh = fields.mesh;
    const Box view{{-0.85, -0.85}, {0.85, 0.85}};
    std::vector<Figure> panels;
    panels.emplace_back(view, "(a) the interface and its embedded normals");
    panels.back().add_curves(curves, "interface", palette_color(2), 1.5);
    panels.back().add_arrows(at, normal, 0.12, palette_color(4));
    const std::span<const LocalMesh::Interval> rows = mesh.rows(), columns = mesh.columns();
    for (const bool by_rows : {true, false}) {
        std::vector<Box> runs;
        for (const auto& r : by_rows ? rows : columns) {
            runs.push_back(by_rows ? Box{mesh.position(r.lo, r.line), mesh.position(r.hi, r.line)}
                                   : Box{mesh.position(r.line, r.lo), mesh.position(r.line, r.hi)});
        }
        panels.emplace_back(
            view, fmt::format("({}) {} points in {} {}-intervals", by_rows ? 'b' : 'c', mesh.size(),
                              runs.size(), by_rows ? 'x' : 'y'));
        panels.back().add_boxes(runs, palette_color(0), 0.8);
        panels.back().add_points(mesh.points(), palette_color(0), 1.2);
        panels.back().add_curves(curves, "interface", palette_color(2), 1.5);
    }
    Figure::save_grid(panels, 3, path);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string table = take_flag(argc, argv, "--table", "docs/tables/geometry.md");
    const std::string figure = take_flag(argc, argv, "--figure", "");
    if (!figure.empty()) draw_local_mesh(figure);
    slc::set_thread_count(1);
    benchmark::Initialize(&argc, argv);
    Recorder recorder;
    benchmark::RunSpecifiedBenchmarks(&recorder);
    if (recorder.results.count("BM_IntrinsicGeometry/4096") != 0 &&
        recorder.results.count("BM_EmbeddedGeometry/4096/2") != 0 &&
        recorder.results.count("BM_BuildDistanceTree/4096/1") != 0) {
        write_table(recorder, table);
    }
    benchmark::Shutdown();
    return 0;
}
