// How many Runge–Kutta substeps trace a flow field's feet (step_common.hpp): the least count
// whose feet are within the tolerance, by Richardson's estimate, the same rule for curves and
// surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "slc/velocity/laws.hpp"
#include "slc/velocity/surface_laws.hpp"
#include "step_common.hpp"

namespace slc::detail {
namespace {

/// The largest distance between the feet of `substeps` and `reference`.
template <int dim>
double worst(const BasicVelocityLaw<dim>& law, double t, double k, std::span<const PointOf<dim>> xs,
             int substeps, const std::vector<PointOf<dim>>& reference) {
    const auto feet = runge_kutta_feet(law, t, k, xs, substeps);
    double out = 0.0;
    for (std::size_t i = 0; i < xs.size(); ++i) out = std::max(out, norm(feet[i] - reference[i]));
    return out;
}

/// The count chosen is within the tolerance and at most one more than the least count that is,
/// found by trying every count against the reference feet.
template <int dim>
void expect_least(const BasicVelocityLaw<dim>& law, double t, double k,
                  std::span<const PointOf<dim>> xs, const std::vector<PointOf<dim>>& reference,
                  double tolerance) {
    const int n = departure_substeps(law, t, k, xs, tolerance);
    int least = 1;
    while (worst(law, t, k, xs, least, reference) > tolerance) ++least;
    EXPECT_LE(worst(law, t, k, xs, n, reference), tolerance) << "k " << k << ", count " << n;
    EXPECT_GE(n, least - 1) << "k " << k << ", tolerance " << tolerance;
    EXPECT_LE(n, least + 1) << "k " << k << ", tolerance " << tolerance;
}

TEST(DepartureSubsteps, TakesTheLeastCountWithinTheToleranceForASurfaceTurned) {
    // A ring of radius 1 about the z axis: the exact feet are the points turned back by k.
    const SurfaceRotation law;
    std::vector<Vec3> xs;
    for (int i = 0; i < 64; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 64;
        xs.push_back({std::cos(a), std::sin(a), 0.3});
    }
    for (const double k : {0.3, 0.7, 1.5}) {
        std::vector<Vec3> exact;
        for (const Vec3& x : xs)
            exact.push_back({std::cos(-k) * x.x - std::sin(-k) * x.y,
                             std::sin(-k) * x.x + std::cos(-k) * x.y, x.z});
        for (const double tolerance : {1e-5, 3e-6, 1e-7})
            expect_least<3>(law, 0.0, k, xs, exact, tolerance);
    }
}

TEST(DepartureSubsteps, TakesTheLeastCountWithinTheToleranceForACurveInAVortex) {
    // The single vortex, time-dependent and nonlinear: the reference feet from 512 substeps;
    // the tolerances need fewer than max_departure_substeps.
    const SingleVortex law(8.0);
    std::vector<Vec2> xs;
    for (int i = 0; i < 64; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 64;
        xs.push_back({0.5 + 0.15 * std::cos(a), 0.75 + 0.15 * std::sin(a)});
    }
    for (const double k : {0.1, 0.4, 1.0}) {
        const auto reference = runge_kutta_feet<2>(law, 0.5, k, xs, 512);
        for (const double tolerance : {1e-5, 3e-6, 1e-6})
            expect_least<2>(law, 0.5, k, xs, reference, tolerance);
    }
}

}  // namespace
}  // namespace slc::detail
