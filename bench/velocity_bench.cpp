// Benchmarks of velocity laws typed as expressions (muparser) beside the built-in laws they
// spell: one call of the law on a batch of points (normal speeds, a flow field sampled), and one
// whole step of a circle at the defaults of a user's curve, where the law is a small part of the
// cost. Sizes in the names; on all cores, as slc runs.
//
// Usage: velocity_bench [google-benchmark flags]
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "slc/evolve/defaults.hpp"
#include "slc/evolve/step.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/velocity/expression.hpp"
#include "slc/velocity/laws.hpp"

namespace {

using namespace slc;

/// n points on the unit circle and their outward normals.
struct Batch {
    std::vector<Vec2> points, normals;
    explicit Batch(std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
            const double a = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
            normals.push_back({std::cos(a), std::sin(a)});
            points.push_back(normals.back());
        }
    }
};

/// The laws compared, by benchmark argument.
std::unique_ptr<VelocityLaw> normal_law_number(int which) {
    switch (which) {
        case 0:
            return std::make_unique<NormalSpeed>(1.0);
        case 1:
            return speed_expression_law("1");
        case 2:
            return std::make_unique<AnisotropicNormalSpeed>(1.0, 4.0, 0.2);
        default:
            return speed_expression_law("R + e*cos(m*atan2(ny, nx))",
                                        {{"R", 1.0}, {"m", 4.0}, {"e", 0.2}});
    }
}
const char* const normal_law_names[] = {"unit-normal", "speed 1", "anisotropic",
                                        "speed R+e*cos(m*atan2(ny,nx))"};

void BM_NormalSpeeds(benchmark::State& state) {
    const auto law = normal_law_number(static_cast<int>(state.range(0)));
    const Batch b(static_cast<std::size_t>(state.range(1)));
    std::vector<double> v(b.points.size());
    for (auto _ : state) {
        law->normal_speeds(0.0, b.points, b.normals, v);
        benchmark::DoNotOptimize(v.data());
    }
    state.SetLabel(normal_law_names[state.range(0)]);
    state.SetItemsProcessed(state.iterations() * state.range(1));
}
BENCHMARK(BM_NormalSpeeds)->ArgsProduct({{0, 1, 2, 3}, {2048, 16384}});

void BM_FieldSample(benchmark::State& state) {
    const std::unique_ptr<VelocityLaw> law =
        state.range(0) == 0 ? std::make_unique<Rotation>() : field_expression_law("-y, x");
    const Batch b(static_cast<std::size_t>(state.range(1)));
    std::vector<Vec2> u(b.points.size());
    for (auto _ : state) {
        law->sample(0.0, b.points, u);
        benchmark::DoNotOptimize(u.data());
    }
    state.SetLabel(state.range(0) == 0 ? "rotation" : "field -y, x");
    state.SetItemsProcessed(state.iterations() * state.range(1));
}
BENCHMARK(BM_FieldSample)->ArgsProduct({{0, 1}, {2048, 16384}});

/// One step of a circle of 2048 vertices at the defaults of a user's curve with K = 7 (about
/// 2000 vertices in each contour).
void BM_Step(benchmark::State& state) {
    const auto law = normal_law_number(static_cast<int>(state.range(0)));
    const Interface circle({shapes::circle({}, 1.0, 2048)});
    RunOptions o = default_run_options(circle, *law, 0.0, 0.1);
    o.step.contour.depth = 7;
    const Box domain = Box::centered_square(2.0);
    std::size_t vertices = 0;
    for (auto _ : state) {
        const StepResult r = advance(circle, 0.0, 0.01, *law, domain, o.step);
        vertices = r.curves.size();
        benchmark::DoNotOptimize(r.curves.points().data());
    }
    state.SetLabel(normal_law_names[state.range(0)]);
    state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(BM_Step)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
