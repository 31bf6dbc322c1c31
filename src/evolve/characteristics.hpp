// Feet of characteristics of a flow field, for curves and surfaces alike (internal to evolve).
#pragma once

#include <span>
#include <vector>

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

}  // namespace slc::detail
