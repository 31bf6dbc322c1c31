// Tests of the pieces of surface studies and estimates: the options of a resolution, the
// distance between two surfaces against its exact value for spheres, and self-convergence.
#include "slc/evolve/surface_study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "slc/core/error.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/geometry/surface_shapes.hpp"

namespace slc {
namespace {

TEST(SurfaceResolution, HalvesAndDoublesNKAndEps) {
    SurfaceRunOptions base;
    base.steps = 10;
    base.step.contour = {.depth = 5, .refine_passes = 2, .eps = 1e-3, .eta = 1e-10};
    const SurfaceRunOptions coarse = surface_resolution_options(base, -1);
    EXPECT_EQ(coarse.steps, 5);
    EXPECT_EQ(coarse.step.contour.depth, 4);
    EXPECT_DOUBLE_EQ(*coarse.step.contour.eps, 4e-3);
    EXPECT_EQ(coarse.step.contour.refine_passes, 2);
    const SurfaceRunOptions fine = surface_resolution_options(base, 2);
    EXPECT_EQ(fine.steps, 40);
    EXPECT_EQ(fine.step.contour.depth, 7);
    EXPECT_DOUBLE_EQ(*fine.step.contour.eps, 1e-3 / 16);
    // ε from the default 10^−K, and never below η.
    base.step.contour.eps.reset();
    EXPECT_DOUBLE_EQ(*surface_resolution_options(base, -1).step.contour.eps, 4e-5);
    base.step.contour.eta = 1e-4;
    EXPECT_DOUBLE_EQ(*surface_resolution_options(base, 2).step.contour.eps, 1e-4);
    base.steps = 1;
    EXPECT_THROW(surface_resolution_options(base, -1), InvalidInput);
}

TEST(SurfaceDistance, OfConcentricSpheresIsTheirRadii) {
    // Icospheres' vertices lie on the sphere, their centroids inside by the sag: the distance of
    // two concentric ones is the difference of radii, up to the sag of the coarser.
    const Surface a = sphere({0.1, 0.0, -0.2}, 0.5, 4), b = sphere({0.1, 0.0, -0.2}, 0.45, 4);
    const double d = surface_distance(a, b);
    EXPECT_GE(d, 0.05 - 1e-12);
    EXPECT_LE(d, 0.05 + 1e-3);  // the centroids' sag on a 4-times-split icosphere: 3e-4
    EXPECT_DOUBLE_EQ(surface_distance(a, b), surface_distance(b, a));
    EXPECT_LE(surface_distance(a, a), 1e-15);  // a centroid's rounding
    EXPECT_EQ(surface_distance(Surface{}, Surface{}), 0.0);
    EXPECT_EQ(surface_distance(a, Surface{}), std::numeric_limits<double>::infinity());
}

TEST(SurfaceSelfConvergence, RejectsResolutionsOutOfRange) {
    const Surface ball = sphere({}, 0.3, 2);
    const auto law = make_surface_velocity("unit-normal", {});
    SurfaceRunOptions base;
    base.t_end = 0.1;
    for (int r : {0, 2, 6}) {
        EXPECT_THROW(surface_self_convergence(ball, *law, Box3::cube({}, 1.0), base, r),
                     InvalidInput);
    }
}

TEST(SurfaceSelfConvergence, ReportsRunsThatCannotBeCompared) {
    // A sphere of radius 0.3 shrinking at unit speed vanishes at t = 0.3: every run ends empty.
    const Surface ball = sphere({0.01, -0.02, 0.03}, 0.3, 2);
    const auto law = make_surface_velocity("unit-normal", {{"speed", -1.0}});
    SurfaceRunOptions base;
    base.t_end = 0.5;
    base.steps = 1;
    base.step.contour = {
        .depth = 2, .refine_passes = SurfaceContourOptions::until_converged, .eps = 2e-2};
    std::vector<int> seen;
    const SurfaceSelfConvergenceResult s =
        surface_self_convergence(ball, *law, Box3::cube({}, 0.5), base, 3,
                                 [&](const SurfaceResolutionRun& r) { seen.push_back(r.level); });
    EXPECT_EQ(seen, (std::vector{0, 1, 2}));
    ASSERT_EQ(s.runs.size(), 3u);
    for (const SurfaceResolutionRun& r : s.runs) {
        EXPECT_EQ(r.result.status, RunStatus::vanished);
        EXPECT_EQ(r.options.steps, 1 << r.level);
        EXPECT_EQ(r.options.step.contour.depth, 2 + r.level);
    }
    ASSERT_EQ(s.distances.size(), 2u);
    for (double d : s.distances) EXPECT_EQ(d, std::numeric_limits<double>::infinity());
    ASSERT_EQ(s.orders.size(), 1u);
    EXPECT_FALSE(s.orders[0]);
    EXPECT_FALSE(s.estimate);
}

}  // namespace
}  // namespace slc
