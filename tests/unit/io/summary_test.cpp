// Tests of summary.json: η as the run held it, raised to what doubles resolve in the domain the
// run reached, for curves and for surfaces.
#include "slc/io/summary.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "slc/core/tolerances.hpp"
#include "slc/evolve/problems.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/velocity/factory.hpp"

namespace slc {
namespace {

TEST(Summary, EtaIsRaisedToTheRoundingFloorOfTheDomainTheRunReached) {
    // η = 1e−300 is below rounding anywhere: the contours held the floor of the domain each step
    // ran in, the largest once the domain had doubled three times.
    const Problem p = make_problem("circle-curvature");
    RunOptions o;
    o.step.contour.eta = 1e-300;
    RunResult r;
    r.curves = Interface(p.initial);
    r.domain_doublings = 3;
    const auto law = make_velocity(p.velocity, p.velocity_params, p.module);
    const double grown = tolerance::rounding_floor(doubled_domain(p.domain, 3));
    EXPECT_GT(grown, tolerance::rounding_floor(p.domain));
    EXPECT_EQ(run_summary(p, o, r, *law)["params"]["eta"].get<double>(), grown);
    r.domain_doublings = 0;
    EXPECT_EQ(run_summary(p, o, r, *law)["params"]["eta"].get<double>(),
              tolerance::rounding_floor(p.domain));

    const SurfaceProblem s = make_surface_problem("sphere-rotation");
    SurfaceRunOptions so;
    so.step.contour.eta = 1e-300;
    SurfaceRunResult sr;
    sr.surface = s.initial;
    sr.domain_doublings = 2;
    EXPECT_EQ(surface_run_summary(s, s.initial, so, sr)["params"]["eta"].get<double>(),
              tolerance::rounding_floor(doubled_domain(s.domain, 2)));
}

TEST(Summary, TheVolumeAsTheStepsReadTheSurfaceIsTheSpheresWhereItsTrianglesFallShort) {
    // sphere-rotation's start, a contour of the sphere of radius 1/4: its triangles hold 5e-4
    // less than the sphere, the curved patches through its vertices (step_volume) about 2e-6.
    const SurfaceProblem p = make_surface_problem("sphere-rotation");
    SurfaceRunOptions o;
    SurfaceRunResult r;
    r.surface = p.initial;
    const nlohmann::json s = surface_run_summary(p, p.initial, o, r);
    const double exact = 4.0 / 3.0 * std::numbers::pi * 0.25 * 0.25 * 0.25;
    const double triangles = s["volume"].get<double>(), read = s["volume_read"].get<double>();
    EXPECT_GT(std::abs(triangles / exact - 1.0), 1e-4);
    EXPECT_LT(std::abs(read / exact - 1.0), 1e-5);
    EXPECT_EQ(read, step_volume(p.initial, o.step));
    EXPECT_EQ(s["volume_read_change"].get<double>(), 0.0);
}

TEST(Summary, ContourStatisticsHaveTheSameKeysInBothDimensions) {
    ContourStats curves;
    curves.finest_at = {0.25, -0.5};
    curves.unconverged_roots = 3;
    SurfaceContourStats surface;
    surface.finest_at = {0.25, -0.5, 1.0};
    surface.unconverged_roots = 4;
    const nlohmann::json c = contour_stats_json(curves);
    const nlohmann::json s = contour_stats_json(surface);
    for (const char* key : {"cells",
                            "leaves",
                            "thin_cells",
                            "thin_budget_reached",
                            "finest_cell",
                            "finest_at",
                            "vertices",
                            "g_evals",
                            "g_evals_tree",
                            "g_evals_roots",
                            "g_evals_refine",
                            "g_evals_per_vertex",
                            "settled",
                            "bound_evals",
                            "gamma",
                            "perturbed",
                            "unconverged_roots",
                            "passes",
                            "splits",
                            "rejected",
                            "specks",
                            "triangles"}) {
        EXPECT_TRUE(c.contains(key)) << key;
        EXPECT_TRUE(s.contains(key)) << key;
    }
    EXPECT_EQ(c["finest_at"], nlohmann::json({0.25, -0.5}));
    EXPECT_EQ(s["finest_at"], nlohmann::json({0.25, -0.5, 1.0}));
    EXPECT_EQ(c["unconverged_roots"], 3);
    EXPECT_EQ(s["unconverged_roots"], 4);
    EXPECT_TRUE(c["max_midpoint_value"].is_null());
    for (const char* key : {"curves", "segments", "pruned", "joined", "slivers"})
        EXPECT_TRUE(c.contains(key) && !s.contains(key)) << key;
    for (const char* key : {"tetrahedra", "collapses", "flips", "residual"})
        EXPECT_TRUE(s.contains(key) && !c.contains(key)) << key;
}

}  // namespace
}  // namespace slc
