// What the steps of curves and surfaces share (internal to evolve): feet of characteristics of a
// flow field, a normal law's checked speeds, and the normal law's predictor and corrector.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc::detail {

/// Where the characteristics through xs at t + k of a flow field were at t: dy/dt = u(y, t)
/// integrated backward by the classical fourth-order Runge–Kutta rule, each stage one batch (a
/// law written in Python, say, sees whole arrays). NumericalFailure naming the law and the point
/// when a velocity is not finite.
template <int dim>
std::vector<typename Space<dim>::Point> departure_points(
    const BasicVelocityLaw<dim>& law, double t, double k,
    std::span<const typename Space<dim>::Point> xs) {
    const std::size_t m = xs.size();
    const double half = 0.5 * k;
    std::vector<typename Space<dim>::Point> y(m);
    const auto k1 = field_velocities(law, t + k, xs);
    for (std::size_t i = 0; i < m; ++i) y[i] = xs[i] - half * k1[i];
    const auto k2 = field_velocities(law, t + half, y);
    for (std::size_t i = 0; i < m; ++i) y[i] = xs[i] - half * k2[i];
    const auto k3 = field_velocities(law, t + half, y);
    for (std::size_t i = 0; i < m; ++i) y[i] = xs[i] - k * k3[i];
    const auto k4 = field_velocities(law, t, y);
    for (std::size_t i = 0; i < m; ++i)
        y[i] = xs[i] - (k / 6.0) * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    return y;
}

/// "(x, y)" or "(x, y, z)", for messages.
inline std::string point_text(Vec2 p) { return fmt::format("({}, {})", p.x, p.y); }
inline std::string point_text(Vec3 p) { return fmt::format("({}, {}, {})", p.x, p.y, p.z); }

/// V(t, x_i, n_i) for a batch, one call of the law; NumericalFailure naming the point unless all
/// are finite.
template <int dim>
void checked_normal_speeds(const BasicVelocityLaw<dim>& law, double t,
                           std::span<const typename Space<dim>::Point> xs,
                           std::span<const typename Space<dim>::Point> n, std::span<double> v) {
    law.normal_speeds(t, xs, n, v);
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!std::isfinite(v[i])) {
            throw NumericalFailure(fmt::format("velocity '{}' is not finite at t = {} near {}",
                                               law.name(), t, point_text(xs[i])));
        }
    }
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
