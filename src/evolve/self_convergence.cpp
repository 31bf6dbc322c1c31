// Self-convergence studies: runs at successive resolutions compared with each other.
#include "slc/evolve/self_convergence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "resolution_study.hpp"
#include "slc/core/error.hpp"
#include "slc/distance/distance_tree.hpp"

namespace slc {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

/// The largest |F(x; to)| over the vertices and segment midpoints x of from; both non-empty.
double one_sided_distance(const Interface& from, const Interface& to) {
    const std::vector<Vec2> points = vertices_and_midpoints(from);
    // The tree's square holds both interfaces, so that its cells near `to` are as fine as its
    // segments whichever side the points lie; depth as for any distance tree: the level whose
    // cells are about as long as the mean segment.
    const Box both = unite(bounding_box(from.points()), bounding_box(to.points()));
    const double half = 0.5 * std::max({both.width(), both.height(), 1e-300}) * 1.25;
    const Box square = Box::square(both.center(), half);
    const double mean = length(to) / static_cast<double>(to.size());
    const int deepest = Quadtree::max_resolvable_depth(square);
    const int level =
        static_cast<int>(std::ceil(std::log2(square.width() / std::max(mean, 1e-300))));
    const DistanceTree tree(
        to, square,
        {.depth = std::clamp(level, std::min(2, deepest), std::min(16, deepest)),
         .triangulate = false});
    const std::vector<double> d = tree.signed_distances(points);
    double largest = 0.0;
    for (double v : d) largest = std::max(largest, std::abs(v));
    return largest;
}

}  // namespace

RunOptions resolution_options(const RunOptions& base, int level) {
    RunOptions o = base;
    const int steps = level >= 0 ? base.steps << level : base.steps >> -level;
    const int depth = base.step.contour.depth + level;
    if (steps < 1 || depth < 1) {
        throw InvalidInput(
            fmt::format("resolution {} of {} steps at depth K = {} would have {} steps and K = {}; "
                        "both must be "
                        "at least 1",
                        level, base.steps, base.step.contour.depth, steps, depth));
    }
    o.steps = steps;
    o.step.contour.depth = depth;
    const double scale = std::ldexp(1.0, level);  // 2^level
    o.step.contour.eps = std::max(base.step.contour.resolved_eps() / (scale * scale),
                                  base.step.contour.resolved_eta());
    o.step.embedded.mesh =
        std::max(8, static_cast<int>(std::lround(base.step.embedded.mesh * scale)));
    if (base.step.tree_depth > 0) o.step.tree_depth = std::max(1, base.step.tree_depth + level);
    return o;
}

double interface_distance(const Interface& a, const Interface& b) {
    if (a.empty() && b.empty()) return 0.0;
    if (a.empty() || b.empty()) return infinity;
    return std::max(one_sided_distance(a, b), one_sided_distance(b, a));
}

double final_distance(const RunResult& a, const RunResult& b) {
    if (a.status != b.status || a.t != b.t || a.curves.empty() || b.curves.empty()) return infinity;
    return interface_distance(a.curves, b.curves);
}

double error_estimate(double distance, double order) {
    const double p = std::clamp(order, min_estimate_order, max_estimate_order);
    return distance / (std::exp2(p) - 1.0);
}

void check_resolutions(int resolutions) {
    if (resolutions < 3 || resolutions > 5) {
        throw InvalidInput(
            fmt::format("a self-convergence study has 3 to 5 resolutions, got {}", resolutions));
    }
}

void observe_orders(std::span<const double> distances, std::vector<std::optional<double>>& orders,
                    std::optional<ErrorEstimate>& estimate) {
    orders.clear();
    for (std::size_t r = 0; r + 1 < distances.size(); ++r) {
        const double coarse = distances[r], fine = distances[r + 1];
        const bool defined =
            std::isfinite(coarse) && std::isfinite(fine) && coarse > 0.0 && fine > 0.0;
        orders.push_back(defined ? std::optional(std::log2(coarse / fine)) : std::nullopt);
    }
    estimate.reset();
    const double last = distances.back();
    if (std::isfinite(last)) {
        const std::optional<double> p = orders.empty() ? std::nullopt : orders.back();
        const double used = std::clamp(p.value_or(1.0), min_estimate_order, max_estimate_order);
        estimate = ErrorEstimate{error_estimate(last, used), used, p.has_value()};
    }
}

SelfConvergenceResult self_convergence(const Interface& initial, const VelocityLaw& law,
                                       const Box& domain, const RunOptions& base, int resolutions,
                                       const SelfConvergenceObserver& observer) {
    return detail::resolution_study(
        resolutions, [&](int r) { return resolution_options(base, r); },
        [&](const RunOptions& o) { return run(initial, law, domain, o); }, observer);
}

}  // namespace slc
