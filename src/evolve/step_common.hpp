// What the steps of curves and surfaces share (internal to evolve): feet of characteristics of a
// flow field, the checks of a velocity and of a normal law's speeds, and the normal law's
// predictor and corrector.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/point_text.hpp"
#include "slc/evolve/step.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc::detail {

/// The classical fourth-order Runge–Kutta rule for dy/dt = u(y, t), integrated backward from xs
/// at t + k to t in `substeps` equal steps (forward from t + k for a negative k), each stage one
/// batch (a law written in Python, say, sees whole arrays).
template <int dim>
std::vector<PointOf<dim>> runge_kutta_feet(const BasicVelocityLaw<dim>& law, double t, double k,
                                           std::span<const PointOf<dim>> xs, int substeps) {
    const std::size_t m = xs.size();
    const double h = k / substeps, half = 0.5 * h;
    using Point = PointOf<dim>;
    // v the latest stage's velocities, sum the stages' velocities k1 + 2 k2 + 2 k3 + k4 added in
    // that order.
    std::vector<Point> x(xs.begin(), xs.end()), y(m), v(m), sum(m);
    for (int s = substeps; s > 0; --s) {
        const double top = t + s * h;  // this substep goes from top back to top − h
        field_velocities(law, top, std::span<const Point>(x), std::span<Point>(v));
        parallel_for_cheap(m, [&](std::size_t i) {
            sum[i] = v[i];
            y[i] = x[i] - half * v[i];
        });
        field_velocities(law, top - half, std::span<const Point>(y), std::span<Point>(v));
        parallel_for_cheap(m, [&](std::size_t i) {
            sum[i] = sum[i] + 2.0 * v[i];
            y[i] = x[i] - half * v[i];
        });
        field_velocities(law, top - half, std::span<const Point>(y), std::span<Point>(v));
        parallel_for_cheap(m, [&](std::size_t i) {
            sum[i] = sum[i] + 2.0 * v[i];
            y[i] = x[i] - h * v[i];
        });
        field_velocities(law, top - h, std::span<const Point>(y), std::span<Point>(v));
        parallel_for_cheap(m, [&](std::size_t i) { x[i] -= (h / 6.0) * (sum[i] + v[i]); });
    }
    return x;
}

/// The feet of a flow field's characteristics are traced to this fraction of the contour's ε
/// (departure_substeps): the contour then carries the flow's error, not the time step's.
constexpr double departure_tolerance = 0.1;

/// Whether a run steps its flow field directly: each step traces its feet to
/// departure_tolerance ε whatever its length, so a step's error is its contour's, and a run that
/// breaks its law does better in fewer steps, not more (a sphere turned by 6 rad at K = 3 without
/// refinement drifts by 1% of its volume by t = 3.9 in 40 steps, by 0.09% over the run in 10).
template <class Law, class StepOptions>
bool flows_directly(const Law& law, const StepOptions& step) {
    return law.is_field() && step.resolved_extension(law) == Extension::direct;
}

/// Why such a run asks for fewer steps, in its messages.
inline constexpr const char* fewer_steps_reason = "a flow field's steps add their contours' errors";

/// Fewest substeps a step's feet take. A step's error at the tolerance is systematic where the
/// field is steady, and the steps add it up: one substep a step of a rotation lags by k⁵/120 of
/// the radius, and `sphere-rotation` (32 steps, ε = 1e−4) ends 1.27e−4 from the exact sphere with
/// one, 1.01e−4 with two, which leave a sixteenth of that.
constexpr int min_departure_substeps = 2;

/// Most substeps a step's feet take: a field whose feet do not settle by then (a discontinuous
/// one) keeps them.
constexpr int max_departure_substeps = 64;

/// How many equal substeps of the Runge–Kutta rule trace the feet of a step from t + k back to t
/// to within about `tolerance`, at most max_departure_substeps: the sample points (the
/// interface's vertices, which the new one lies near) are traced in 1, 2, 4, … substeps until one
/// doubling, s to 2s, moves no foot by more than 15·tolerance. By Richardson's estimate for a
/// fourth-order rule the error of n substeps is then E(n) = (2s/n)⁴ e with e = moved/15 ≤
/// tolerance that of 2s, so the count is the least n with E(n) ≤ tolerance, between s and 2s
/// (the next power of two would be up to sixteen times more accurate than asked, at up to twice
/// the cost), and never below min_departure_substeps. One count for the whole step, so that G
/// stays continuous (a count chosen point by point would make G jump where it changes).
template <int dim>
int departure_substeps(const BasicVelocityLaw<dim>& law, double t, double k,
                       std::span<const PointOf<dim>> sample, double tolerance) {
    if (sample.empty()) return min_departure_substeps;
    auto feet = runge_kutta_feet(law, t, k, sample, 1);
    int substeps = 1;
    while (substeps < max_departure_substeps) {
        auto finer = runge_kutta_feet(law, t, k, sample, 2 * substeps);
        double moved = 0.0;
        for (std::size_t i = 0; i < sample.size(); ++i)
            moved = std::max(moved, norm(finer[i] - feet[i]));
        substeps *= 2;
        if (moved <= 15.0 * tolerance) {
            const double error = moved / 15.0;  // that of `substeps`
            const int least = static_cast<int>(
                std::ceil(substeps * std::pow(error / tolerance, 0.25) * (1.0 - 1e-12)));
            return std::clamp(least, std::max(min_departure_substeps, substeps / 2), substeps);
        }
        feet = std::move(finer);
    }
    return substeps;
}

/// "(x, y)" or "(x, y, z)" with 6 digits, for messages (point_text, slc/core/point_text.hpp).
template <class Point>
std::string point_text6(Point p) {
    return point_text(p, 6);
}

/// W(x) at a point where the step evaluates it (an extension or a law may give it anywhere),
/// checked: NumericalFailure naming the law, the time and the point unless finite.
template <class Point>
Point checked_velocity(Point w, const std::string& law, double t, Point x) {
    if (!is_finite(w)) {
        throw NumericalFailure(
            fmt::format("velocity '{}' is not finite at t = {} near {}", law, t, point_text(x)));
    }
    return w;
}

/// V(t, x_i, n_i) for a batch, one call of the law; NumericalFailure naming the point unless all
/// are finite.
template <int dim>
void checked_normal_speeds(const BasicVelocityLaw<dim>& law, double t,
                           std::span<const PointOf<dim>> xs, std::span<const PointOf<dim>> n,
                           std::span<double> v) {
    law.normal_speeds(t, xs, n, v);
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!std::isfinite(v[i])) {
            throw NumericalFailure(fmt::format("velocity '{}' is not finite at t = {} near {}",
                                               law.name(), t, point_text(xs[i])));
        }
    }
}

/// What a normal law's step needs of a level's distance field at a batch of points: F there
/// (`distance` of the closest point) and the normal the law sees (`normal` at the point and its
/// closest point), one closest-point query of `tree` each, on all worker threads.
template <class Tree, class Point, class Distance, class Normal>
void distances_and_normals(const Tree& tree, std::span<const Point> xs, std::span<double> f,
                           std::span<Point> n, Distance distance, Normal normal) {
    parallel_for(
        xs.size(),
        [&](std::size_t i) {
            const auto p = tree.closest_point(xs[i]);
            f[i] = distance(p);
            n[i] = normal(xs[i], p);
        },
        expensive_grain);
}

/// The predictor of a normal law's step at a batch: G̃(x) = F(x) − k V(x, N(x)), F and N the
/// distance field of the level `now` (a Level with distances_and_normals and normal_speeds).
template <class Level, class Point>
void normal_predictor(const Level& now, double k, std::span<const Point> xs, std::span<double> g) {
    std::vector<double> v(xs.size());
    std::vector<Point> n(xs.size());
    now.distances_and_normals(xs, g, n);
    now.normal_speeds(xs, n, v);
    for (std::size_t i = 0; i < xs.size(); ++i) g[i] -= k * v[i];
}

/// The trapezoidal corrector of a normal law's step at a batch: G(x) = F(x) − k/2 (V at the
/// foot x − k V N at t + V at x at t + k, with the predicted level's normal).
template <class Level, class Point>
void normal_corrector(const Level& now, const Level& next, double k, std::span<const Point> xs,
                      std::span<double> g) {
    const std::size_t m = xs.size();
    std::vector<double> v(m), v_foot(m), f_next(m), v_next(m);
    std::vector<Point> n(m), feet(m), n_next(m);
    now.distances_and_normals(xs, g, n);
    now.normal_speeds(xs, n, v);
    for (std::size_t i = 0; i < m; ++i) feet[i] = xs[i] - k * v[i] * n[i];
    now.normal_speeds(feet, n, v_foot);
    next.distances_and_normals(xs, f_next, n_next);
    next.normal_speeds(xs, n_next, v_next);
    for (std::size_t i = 0; i < m; ++i) g[i] -= 0.5 * k * (v_foot[i] + v_next[i]);
}

}  // namespace slc::detail
