// Coarse, fast tests of the time stepper against exact solutions (DESIGN §7): rotation, Huygens'
// principle, merging, curvature flow to extinction, area preservation, second order in time, and
// independence of the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/extension.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/problems.hpp"
#include "slc/evolve/run.hpp"
#include "slc/evolve/self_convergence.hpp"
#include "slc/evolve/step.hpp"
#include "slc/geometry/balls.hpp"
#include "slc/geometry/segment.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/velocity/factory.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc {
namespace {

RunOptions options(double t_end, int steps, int depth, int refine, double eps) {
    RunOptions o;
    o.t_end = t_end;
    o.steps = steps;
    o.step.contour.depth = depth;
    o.step.contour.refine_passes = refine;
    o.step.contour.eps = eps;
    o.step.embedded.mesh = default_mesh_size(depth);
    o.step.extension =
        Extension::nearest_point;  // the paper's method, unless a test says otherwise
    o.step.arcs = false;
    return o;
}

/// Runs a named problem with the given settings; returns the result and the error Eq. (11).
std::pair<RunResult, std::optional<double>> solve(const Problem& p, const RunOptions& o) {
    const auto law = make_velocity(p.velocity, p.velocity_params, p.module);
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    RunResult r = run(initial, *law, p.domain, o);
    const auto e = max_error(p, r.curves, r.t);
    return {std::move(r), e};
}

/// The problem `name` with its initial curves replaced; exact(x, t) the new exact distance.
template <class Exact>
Problem with_initial(const std::string& name, std::vector<std::vector<Vec2>> curves, Exact exact,
                     const std::map<std::string, double>& params = {}) {
    Problem p = make_problem(name, params);
    p.initial = std::move(curves);
    p.exact = [exact](std::span<const Vec2> xs, double t) -> std::optional<std::vector<double>> {
        std::vector<double> d;
        for (Vec2 x : xs) d.push_back(exact(x, t));
        return d;
    };
    return p;
}

TEST(Run, RotatedCircleReturnsToItsStart) {
    Problem circle = with_initial("propeller-rotation", {shapes::circle({0.5, 0.2}, 0.8, 512)},
                                  [](Vec2 x, double) {
                                      return distance(x, {0.5, 0.2}) - 0.8;
                                  });
    circle.t_end = 2 * std::numbers::pi;
    const auto [r, e] = solve(circle, options(circle.t_end, 40, 5, 2, 1e-5));
    EXPECT_EQ(r.status, RunStatus::ok);
    ASSERT_TRUE(e);
    // One revolution in 40 steps, k = 2π/40: the time error, second order, dominates; at k = 0.1
    // over t = 1 it is 0.002 (HalvingTheTimeStep...), so over t = 2π at k = 0.157 about 0.03.
    // The paper's Table 5 at 40/0/3 (a propeller, two turns) has 0.25–0.65.
    EXPECT_LT(*e, 0.05);
    EXPECT_EQ(r.curves.curve_count(), 1u);
}

TEST(Run, GrowingAndShrinkingSquaresMeetHuygens) {
    for (double speed : {1.0, -1.0}) {
        SCOPED_TRACE(::testing::Message() << "speed " << speed);
        // Huygens: growing, the square's offset has rounded corners and F0 − t is its distance;
        // shrinking, it is the square of half-width 1 − t, with sharp corners.
        const Interface square({shapes::rectangle({-1, -1}, {1, 1}, 32)});
        const DistanceTree f0(square, Box::centered_square(2.5),
                              {.depth = 8, .triangulate = false});
        const auto exact = [&](Vec2 x, double t) {
            if (speed > 0) return f0.closest_point(x).distance - speed * t;
            const double w = 1.0 + speed * t;
            const Interface inner({shapes::rectangle({-w, -w}, {w, w})});
            return closest_point_brute_force(inner, x).distance;
        };
        const Problem p =
            with_initial("triangle-normal", square.curves(), exact, {{"speed", speed}});
        const auto [r, e] = solve(p, options(0.4, 20, 6, 1, 1e-6));
        EXPECT_EQ(r.status, RunStatus::ok);
        ASSERT_TRUE(e);
        // Sharp corners shrinking, round ones growing: the error is set by the corner, which the
        // contour resolves to about a cell of the K = 6 tree (5/64 ≈ 0.08).
        EXPECT_LT(*e, 0.03);
    }
}

TEST(Run, TwoCirclesMergeIntoOneComponent) {
    const Interface two({shapes::circle({-0.5, 0}, 0.4, 256), shapes::circle({0.5, 0}, 0.4, 256)});
    const Problem p = with_initial("merging-circles", two.curves(), [&](Vec2 x, double t) {
        const Ball<2> grown[] = {{{-0.5, 0}, 0.4 + t}, {{0.5, 0}, 0.4 + t}};
        return union_of_balls_distance<2>(grown, x);
    });
    const auto [r, e] = solve(p, options(0.3, 30, 5, 2, 1e-5));
    EXPECT_EQ(r.status, RunStatus::ok);
    EXPECT_EQ(r.curves.curve_count(), 1u);
    ASSERT_TRUE(e);
    EXPECT_LT(*e, 0.03);
}

TEST(Problems, UnitSpeedOffsetsAreScoredByTheirExactDistance) {
    // Eq. 11 needs the distance to the exact Γ(t), which F0 − s t is not in the cusps of merging
    // circles nor beyond the sharp corners of a shrinking triangle.
    const Problem merging = make_problem("merging-circles");
    // At t = 0.5 the discs (radii 0.9, 0.9, 0.8) enclose an island; from its centre region the
    // nearest boundary point is a corner where two of the grown circles cross.
    const Ball<2> grown[] = {{{-0.6, 0}, 0.9}, {{0.6, 0}, 0.9}, {{0, 0.9}, 0.8}};
    const std::vector<Vec2> xs{{0, 0.55}, {0, 0.45}, {1.6, 0}};
    const auto d = merging.exact(xs, 0.5);
    ASSERT_TRUE(d);
    for (std::size_t i = 0; i < xs.size(); ++i)
        EXPECT_DOUBLE_EQ((*d)[i], union_of_balls_distance<2>(grown, xs[i]));
    EXPECT_NEAR((*d)[2], 0.1, 1e-15);
    EXPECT_FALSE(make_problem("merging-circles", {{"speed", -1.0}}).exact(xs, 0.1));

    // The shrinking triangle's corner (0, 1) moves to (0, 1 − 2t); at t = 0.2, the point (0, 0.7)
    // is 0.1 beyond it, where F0 + t = −0.15 + 0.2 says 0.05.
    const Problem shrinking = make_problem("triangle-normal", {{"speed", -1.0}});
    const std::vector<Vec2> beyond{{0, 0.7}, {0, 0}};
    const auto e = shrinking.exact(beyond, 0.2);
    ASSERT_TRUE(e);
    EXPECT_NEAR((*e)[0], 0.1, 1e-12);
    EXPECT_NEAR((*e)[1], -0.3, 1e-12);           // the inradius 0.5 less 0.2
    EXPECT_FALSE(shrinking.exact(beyond, 0.5));  // nothing is left
}

TEST(Run, NearestPointExtensionMovesTheSidesOfAShockWithTheirOwnNormals) {
    // Under a constant normal speed, a shrinking corner and the cusp of merging circles are
    // shocks: with the corner's averaged velocity interpolated into its sides, the paper's
    // extension cut the triangle's corners (E∞ 0.0315 at 80/0/5/2/1e−4) and filled the cusps
    // (0.0124 at merging-circles' own 160/0/5/2/1e−5); with each side's own velocity, 0.0108
    // and 0.0040; with the corrector's two velocities from one side of the shock, 4.9e−6 and
    // 0.0037.
    const Problem triangle = make_problem("triangle-normal", {{"speed", -1.0}});
    const auto [t, et] = solve(triangle, options(0.4, 80, 5, 2, 1e-4));
    EXPECT_EQ(t.status, RunStatus::ok);
    ASSERT_TRUE(et);
    EXPECT_LT(*et, 1e-4);
    const Problem merging = make_problem("merging-circles");
    const auto [m, em] = solve(merging, options(0.5, 160, 5, 2, 1e-5));
    EXPECT_EQ(m.status, RunStatus::ok);
    ASSERT_TRUE(em);
    EXPECT_LT(*em, 0.006);
}

TEST(Run, TheShrinkingTrianglesCornersStaySharpAtEveryStep) {
    // Fig. 13 with the paper's nearest-point extension at 80/0/5/2/1e−4, upright and tilted by
    // 10°: the distance from each exact corner (circumradius 1 − 2t) to the curve, largest over
    // the 80 steps. Where the corrector took the two sides' velocities of a shock from the two
    // levels (a point on the bisector is as near one side as the other), G jumped along the
    // bisector, refinement could not place the corner, and the cut reached 0.012 (0.0555
    // tilted); with one side along each characteristic, 1.8e−5 (1.1e−4 tilted).
    for (const double tilt : {0.0, 10.0}) {
        const Problem p = make_problem("triangle-normal", {{"speed", -1.0}, {"tilt", tilt}});
        const auto law = make_velocity(p.velocity, p.velocity_params, p.module);
        double worst = 0.0;
        const RunResult r =
            run(prepare_interface(p.initial, p.domain).curves, *law, p.domain,
                options(0.4, 80, 5, 2, 1e-4), [&](const StepReport& s) {
                    const double radius = 1.0 - 2.0 * s.t;
                    for (int j = 0; j < 3; ++j) {
                        const double a = std::numbers::pi / 2 + 2 * std::numbers::pi * j / 3 +
                                         tilt * std::numbers::pi / 180;
                        const Vec2 corner{radius * std::cos(a), radius * std::sin(a)};
                        worst = std::max(
                            worst, std::abs(closest_point_brute_force(*s.curves, corner).distance));
                    }
                    return true;
                });
        EXPECT_EQ(r.status, RunStatus::ok);
        std::printf("tilt %g: largest corner cut %.3g\n", tilt, worst);
        EXPECT_LT(worst, 1e-3);
    }
}

TEST(Run, ZalesaksDiskKeepsItsAreaOverATurnAtItsOwnSettings) {
    // One turn at 100/0/7/4/1e−6 with the nearest-point extension: the area 2.4e−4 short (front
    // tracking's published figure is 3.95e−4), the vertices within 2.84e−3 of the disk. With
    // two passes refinement had not found the slot's convex corners within a step: 6.9e−4 and
    // 3.66e−3.
    const Problem p = make_problem("zalesak");
    const auto law = make_velocity(p.velocity, p.velocity_params, p.module);
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    const RunResult r = run(initial, *law, p.domain, problem_run_options(p));
    ASSERT_EQ(r.status, RunStatus::ok);
    const double change = (area(r.curves) - area(initial)) / area(initial);
    double farthest = 0.0;
    for (std::size_t i = 0; i < r.curves.size(); ++i)
        farthest = std::max(
            farthest, std::abs(closest_point_brute_force(initial, r.curves.point(i)).distance));
    std::printf("Zalesak, one turn: area %+.3g, farthest vertex %.3g\n", change, farthest);
    EXPECT_LT(std::abs(change), 3e-4);
    EXPECT_LT(farthest, 3e-3);
}

TEST(Run, CircleUnderCurvatureFollowsTheExactRadiusAndVanishes) {
    const Problem p = make_problem("circle-curvature", {{"R0", 1.0}});
    RunOptions o = options(0.4, 40, 5, 2, 1e-5);
    o.step.embedded.smoothing = 1;
    const auto [r, e] = solve(p, o);
    EXPECT_EQ(r.status, RunStatus::ok);
    ASSERT_TRUE(e);
    // R(0.4) = sqrt(0.2) ≈ 0.447; the paper's Table 7 at 40/1/4/1 has 0.045 for R0 = sqrt 5.
    EXPECT_LT(*e, 0.02);
    const double r_mean = std::sqrt(area(r.curves) / std::numbers::pi);
    EXPECT_NEAR(r_mean, std::sqrt(1.0 - 0.8), 0.02);

    RunOptions longer = options(0.6, 60, 5, 2, 1e-5);
    longer.step.embedded.smoothing = 1;
    const auto [gone, none] = solve(p, longer);
    EXPECT_EQ(gone.status, RunStatus::vanished);
    // Extinction at R0²/2 = 0.5, resolved to within a few steps of 0.01.
    EXPECT_NEAR(gone.t, 0.5, 0.05);
    EXPECT_FALSE(none);
}

TEST(Run, AnLWithARectangularHoleKeepsItsAreaUntilTheHoleVanishesOnTime) {
    // A user's polygon with corners of 90°, convex and reflex, and a hole 0.1 from the outside,
    // under curvature flow at the default settings: the outside loses 2π of area a unit of time
    // and the hole gives it back, so the area stays 0.59 until the hole (area 0.05) vanishes at
    // t = 0.05/2π = 0.00796; then the L loses 2π alone. A corner's curvature integrates to its
    // turn (vertex_curvature); with the circle through a corner and its neighbours a step closed
    // off a speck by a corner at t = 0.001 and the run ended unstable.
    set_thread_count(1);
    const auto polygon = [](std::vector<Vec2> corners) {
        std::vector<Vec2> p;
        for (std::size_t c = 0; c < corners.size(); ++c)
            for (int k = 0; k < 40; ++k)
                p.push_back(corners[c] +
                            (k / 40.0) * (corners[(c + 1) % corners.size()] - corners[c]));
        return p;
    };
    const std::vector<std::vector<Vec2>> raw = {
        polygon({{0, 0}, {1, 0}, {1, 0.4}, {0.4, 0.4}, {0.4, 1}, {0, 1}}),
        polygon({{0.1, 0.1}, {0.1, 0.35}, {0.3, 0.35}, {0.3, 0.1}})};
    const Box domain = default_domain(raw);
    const Interface initial = prepare_interface(raw, domain).curves;
    const auto law = make_velocity("curvature", {});
    const RunOptions o = default_run_options(initial, *law, 0.0, 0.02);
    const double k = 0.02 / o.steps, vanishes = 0.05 / (2.0 * std::numbers::pi);
    const auto exact = [&](double t) {
        return t < vanishes ? 0.59 : 0.64 - 2.0 * std::numbers::pi * t;
    };
    double worst = 0.0, gone = -1.0;
    const RunResult r = run(initial, *law, domain, o, [&](const StepReport& s) {
        worst = std::max(worst, std::abs(area(*s.curves) - exact(s.t)));
        if (gone < 0.0 && s.curves->curve_count() == 1) gone = s.t;
        return true;
    });
    std::printf("hole gone by t = %.5g (exact %.5g), largest area error %.3g\n", gone, vanishes,
                worst);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.curves.curve_count(), 1u);
    EXPECT_GE(gone, vanishes);
    EXPECT_LE(gone, vanishes + 2.0 * k);
    EXPECT_LT(worst, 1.5e-3);  // 0.25% of the area; the step's area change is 2πk = 3.1e−3
}

TEST(Run, AUsersStarKeepsTheLawsAreaChangeByItsSplitSteps) {
    // Seven sharp points under curvature flow at the default settings: dA/dt = −2π. Its first
    // steps take the notches' area at the wrong rate (3.3% of the law's change by t = 0.02 in
    // whole steps); a user's run splits the steps that take it beyond 2% of the change
    // (RunOptions::area_rate_drift) or beyond their share of the run's 1% of the area
    // (RunOptions::area_step_share).
    set_thread_count(1);
    std::vector<Vec2> star;
    for (int i = 0; i < 14; ++i) {
        const double r = i % 2 == 0 ? 1.0 : 0.5, t = 2.0 * std::numbers::pi * i / 14;
        star.push_back({r * std::cos(t), r * std::sin(t)});
    }
    const Box domain = default_domain({star});
    const Interface initial = prepare_interface({star}, domain).curves;
    const auto law = make_velocity("curvature", {});
    const double t_end = 0.02, change = -2.0 * std::numbers::pi * t_end;
    const RunOptions o = default_run_options(initial, *law, 0.0, t_end);
    ASSERT_EQ(o.area_rate_drift, 0.02);
    const auto miss = [&](const RunResult& r) {
        return std::abs(area(r.curves) - area(initial) - change) / std::abs(change);
    };
    RunOptions whole = o;
    whole.area_rate_drift = 0.0;
    whole.area_step_share = 0.0;
    const RunResult unsplit = run(initial, *law, domain, whole);
    const RunResult split = run(initial, *law, domain, o);
    std::printf(
        "area change off the law's by %.3g in whole steps, %.3g split (%d steps split, "
        "%d without the run's budget)\n",
        miss(unsplit), miss(split), split.split_steps, unsplit.split_steps);
    ASSERT_EQ(unsplit.status, RunStatus::ok) << unsplit.message;
    ASSERT_EQ(split.status, RunStatus::ok) << split.message;
    EXPECT_GT(miss(unsplit), 0.025);
    EXPECT_LT(miss(split), 0.02);
    EXPECT_GT(split.split_steps, unsplit.split_steps);
    EXPECT_NEAR(split.area_law_change, change, 1e-12);
    // From the star after its first step, with no splitting allowed: the run ends unstable,
    // naming the law's change and the setting to raise.
    RunOptions first = o;
    first.t_end = t_end / o.steps;
    first.steps = 1;
    const RunResult start = run(initial, *law, domain, first);
    ASSERT_EQ(start.status, RunStatus::ok) << start.message;
    RunOptions fixed = o;
    fixed.t_start = first.t_end;
    fixed.steps = o.steps - 1;
    fixed.max_substep_halvings = 0;
    const RunResult refused = run(start.curves, *law, domain, fixed);
    EXPECT_EQ(refused.status, RunStatus::unstable);
    EXPECT_NE(refused.message.find("where the law's rate gives"), std::string::npos)
        << refused.message;
    EXPECT_NE(refused.message.find("raise the steps N"), std::string::npos);
}

TEST(Run, AThinEllipsesStepsKeepToTheirShareOfTheAreaBudget) {
    // A 1 x 0.1 ellipse under curvature flow vanishes at t = ab/2 = 0.05. At the default 40 steps
    // to t = 0.06 its first steps, at tips of curvature 100, lag the law's area by 0.15% of the
    // start's each: with only the run's 1% held, the budget is gone before half its life
    // (unstable); held to their share of it (RunOptions::area_step_share), the steps are split
    // where they lag and the ellipse vanishes within a step of 0.05, its area on the law's
    // A0 − 2πt to the 1% every step of the way.
    set_thread_count(1);
    std::vector<Vec2> ellipse;
    for (int i = 0; i < 400; ++i) {
        const double t = 2.0 * std::numbers::pi * i / 400;
        ellipse.push_back({std::cos(t), 0.1 * std::sin(t)});
    }
    const Box domain = default_domain({ellipse});
    const Interface initial = prepare_interface({ellipse}, domain).curves;
    const auto law = make_velocity("curvature", {});
    const double t_end = 0.06, vanishes = 0.05, a0 = area(initial);
    const RunOptions o = default_run_options(initial, *law, 0.0, t_end);
    ASSERT_EQ(o.area_step_share, 0.5);
    RunOptions total_only = o;
    total_only.area_step_share = 0.0;
    const RunResult spent = run(initial, *law, domain, total_only);
    EXPECT_EQ(spent.status, RunStatus::unstable);
    EXPECT_LT(spent.t, 0.5 * vanishes);

    double worst = 0.0;  // |A − (A0 − 2πt)| / A0 over the steps
    const RunResult r = run(initial, *law, domain, o, [&](const StepReport& s) {
        if (!s.curves->empty()) {
            const double exact = a0 - 2.0 * std::numbers::pi * s.t;
            worst = std::max(worst, std::abs(area(*s.curves) - exact) / a0);
        }
        return true;
    });
    std::printf(
        "without shares unstable at t = %.4g; with them %s at t = %.4g, %d steps split "
        "(in %d at most), area off the law by %.3g of A0 at worst\n",
        spent.t, to_string(r.status), r.t, r.split_steps, r.most_substeps, worst);
    ASSERT_EQ(r.status, RunStatus::vanished) << r.message;
    const double k = t_end / o.steps;
    EXPECT_GE(r.t, vanishes);
    EXPECT_LE(r.t, vanishes + k + 1e-12);
    EXPECT_GT(r.split_steps, 0);
    EXPECT_LT(worst, 0.01);
}

/// Largest distance of a vertex from the circle of radius r about the origin.
double radius_error(const Interface& curves, double r) {
    double worst = 0.0;
    for (Vec2 x : curves.points()) worst = std::max(worst, std::abs(norm(x) - r));
    return worst;
}

TEST(Run, ArcsPutTheNextContourOnTheCircleWhereChordsCutInside) {
    // A step with u = 0 contours F itself. A 16-gon inscribed in the unit circle has chords up
    // to 1 − cos(π/16) = 0.019 inside it, and the new vertices land on them; read as arcs
    // through its vertices, the polygon is the circle to O(c⁴). Under a rigid motion the arcs
    // read sides of up to two cells, so K = 3 here (cells of 0.5, sides of 0.39). The corners of
    // a square (turning by π/2) stay corners.
    const auto still = make_velocity("translation", {{"ux", 0.0}, {"uy", 0.0}});
    const Box domain = Box::centered_square(2.0);
    StepOptions o = options(1.0, 1, 3, 2, 1e-8).step;
    const Interface polygon({shapes::circle({}, 1.0, 16)});
    const double chords = radius_error(advance(polygon, 0.0, 0.1, *still, domain, o).curves, 1.0);
    o.arcs = true;
    const double arcs = radius_error(advance(polygon, 0.0, 0.1, *still, domain, o).curves, 1.0);
    std::printf("16-gon contoured: vertices off the circle by %.3e with chords, %.3e with arcs\n",
                chords, arcs);
    EXPECT_GT(chords, 0.01);
    EXPECT_LT(arcs, 1e-3);

    const Interface square(
        {{{-1, -1}, {0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}}});
    const Interface moved = advance(square, 0.0, 0.1, *still, domain, o).curves;
    for (Vec2 x : moved.points()) EXPECT_NEAR(std::max(std::abs(x.x), std::abs(x.y)), 1.0, 1e-7);
}

TEST(Run, CurveShorteningWithArcsAndTheArclengthModuleIsSecondOrderInTime) {
    // R(0) = 0.5 to t = 0.1 in [−1, 1]², K = 6, P = 2. The arclength module's curvature is exact
    // on a circle and its width √k keeps the step stable; with arcs nothing is lost to the
    // chords, so what is left is the second-order time error. With chords that loss grows with
    // the number of steps instead (measured: 3.1e−4, 5.1e−5, 9.7e−6 with arcs; 1.1e−4 at N = 20
    // with chords).
    Problem p = make_problem("circle-curvature", {{"R0", 0.5}});
    p.domain = Box::centered_square(1.0);
    const auto law = make_velocity(p.velocity, p.velocity_params, GeometryModule::arclength);
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    const double exact = std::sqrt(0.25 - 2.0 * 0.1);
    auto error = [&](int steps, bool arcs) {
        RunOptions o = options(0.1, steps, 6, 2, 1e-8);
        o.step.arcs = arcs;
        const RunResult r = run(initial, *law, p.domain, o);
        EXPECT_EQ(r.status, RunStatus::ok);
        return radius_error(r.curves, exact);
    };
    const double e5 = error(5, true), e10 = error(10, true), e20 = error(20, true);
    std::printf("curve shortening with arcs: N = 5, 10, 20: %.3e %.3e %.3e, orders %.2f %.2f\n", e5,
                e10, e20, std::log2(e5 / e10), std::log2(e10 / e20));
    EXPECT_GT(std::log2(e5 / e10), 1.8);
    EXPECT_GT(std::log2(e10 / e20), 1.8);
    EXPECT_LT(e20, 2e-5);
    const double chords = error(20, false);
    std::printf("with chords at N = 20: %.3e\n", chords);
    EXPECT_GT(chords, 5.0 * e20);
}

TEST(Run, VolumePreservingFlowKeepsTheArea) {
    Problem p = make_problem("spiral-nonlocal");
    p.initial = {shapes::polar(
        {0.1, 0}, [](double t) { return 1.0 + 0.3 * std::cos(3 * t); }, 512)};
    const double a0 = area(Interface(p.initial));
    RunOptions o = options(0.1, 20, 6, 2, 1e-6);
    o.step.embedded.smoothing = 1;
    const auto [r, e] = solve(p, o);
    EXPECT_EQ(r.status, RunStatus::ok);
    // The law has zero mean normal speed; what is lost is the contouring and time error.
    EXPECT_NEAR(area(r.curves), a0, 0.01 * a0);
}

/// The largest |A(t) − A(0)| / A(0) over the steps of the problem's run with options o, the
/// area correction off, and the run's result.
std::pair<double, RunResult> area_drift(const Problem& p, RunOptions o) {
    o.step.area_correction = false;
    const auto law = make_velocity(p.velocity, p.velocity_params, p.module);
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    const double a0 = area(initial);
    double worst = 0.0;
    RunResult r = run(initial, *law, p.domain, o, [&](const StepReport& s) {
        worst = std::max(worst, std::abs(area(*s.curves) - a0) / a0);
        return true;
    });
    return {worst, std::move(r)};
}

/// The largest distance of a vertex of one closed curve from the circle of the same area about
/// the curve's centroid.
double distance_from_its_circle(const Interface& curves) {
    const std::vector<Vec2> c = curves.curves().front();
    double a = 0.0, cx = 0.0, cy = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        const Vec2 p = c[i], q = c[(i + 1) % c.size()];
        const double w = p.x * q.y - q.x * p.y;
        a += 0.5 * w;
        cx += (p.x + q.x) * w;
        cy += (p.y + q.y) * w;
    }
    const Vec2 centre{cx / (6.0 * a), cy / (6.0 * a)};
    const double radius = std::sqrt(std::abs(a) / std::numbers::pi);
    double worst = 0.0;
    for (const Vec2 p : c) worst = std::max(worst, std::abs(norm(p - centre) - radius));
    return worst;
}

/// The largest distance of a vertex from the chord of its neighbours, among the vertices where
/// the curve turns by more than 30°: a zigzag, where a smooth curve turns by a few degrees.
double largest_zigzag(const Interface& curves) {
    double worst = 0.0;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        const auto p = curves.curve(c);
        const std::size_t n = p.size();
        for (std::size_t i = 0; i < n; ++i) {
            const Vec2 a = p[(i + n - 1) % n], b = p[i], d = p[(i + 1) % n];
            const Vec2 u = b - a, v = d - b, chord = d - a;
            const double turn = std::abs(std::atan2(cross(u, v), dot(u, v)));
            if (turn > std::numbers::pi / 6 && norm(chord) > 0.0)
                worst = std::max(worst, std::abs(cross(chord, b - a)) / norm(chord));
        }
    }
    return worst;
}

TEST(Run, APolygonUnderCurvatureFlowLeavesNoZigzagsWithAMeshThatSeesThem) {
    // Fig. 17's run a (320/1/5/4/1e−3) from t = 1.6 to 3.25. With the paper's embedded mesh
    // M = 2^(K+1) = 64 (h = 0.25) the corners' transients leave bumps narrower than the mesh,
    // which the module does not see and no step damps: zigzags of 0.053 (run b's are 0.0047).
    // With M = 128 none turns by more than 30°, and the polygon vanishes at t = 11.50 against
    // 11.62 (exactly 72/2π = 11.46).
    const Problem p = make_problem("polygon-curvature");
    RunOptions o = problem_run_options(p);
    ASSERT_EQ(o.steps, 320);
    o.steps = 80;
    o.t_end = 80 * p.t_end / 320;
    const auto law = make_velocity(p.velocity, p.velocity_params, p.module);
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    const auto zigzag = [&](int mesh) {
        o.step.embedded.mesh = mesh;
        double worst = 0.0;
        const RunResult r = run(initial, *law, p.domain, o, [&](const StepReport& s) {
            if (s.t >= 1.6) worst = std::max(worst, largest_zigzag(*s.curves));
            return true;
        });
        EXPECT_EQ(r.status, RunStatus::ok) << r.message;
        std::printf("M = %d: largest zigzag from t = 1.6 to %g: %.3g\n", mesh, r.t, worst);
        return worst;
    };
    EXPECT_GT(zigzag(64), 0.02);  // the measure sees them at the paper's mesh
    EXPECT_LT(zigzag(128), 2e-3);
}

TEST(Run, SpiralUnderEq13ReachesThePapersFinalTimeRoundAndKeepingItsArea) {
    // Fig. 18's 512/2/7/3/1e−3 run in the problem's [−5, 5]² (k/h² = 3.3): the spiral unwinds
    // into one round curve by t = 2.56 (in [−3, 3]², k/h² = 9.1, it wiggles, 25% longer than its
    // circle). Without the correction the area stays within 6.7e−6 of itself. With the embedded
    // curvature used as interpolated, noise below the mesh roughened the curve from t = 1.29 and
    // its length grew until the guard ended the run at t = 2.545; averaged along the curve over
    // a mesh spacing (EmbeddedOptions::average) it reaches t = 2.56, and with ∇F's ENO biased
    // towards the centred stencil (eno_bias) it ends 7.5e−4 from its circle (2.7e−3 with the
    // plain rule, a four-fold shape in step with the mesh).
    const Problem p = make_problem("spiral-nonlocal");
    const RunOptions o = problem_run_options(p);
    ASSERT_EQ(o.steps, 512);
    ASSERT_EQ(o.step.embedded.smoothing, 2);
    ASSERT_EQ(o.step.embedded.average, 1.0);
    ASSERT_EQ(o.step.embedded.eno_bias, 2.0);
    const auto [drift, r] = area_drift(p, o);
    EXPECT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_DOUBLE_EQ(r.t, 2.56);
    ASSERT_EQ(r.curves.curve_count(), 1u);
    const double a = area(r.curves);
    EXPECT_LT(length(r.curves) / (2.0 * std::sqrt(std::numbers::pi * a)) - 1.0, 5e-4);
    EXPECT_LT(distance_from_its_circle(r.curves), 1e-3);
    EXPECT_LT(drift, 1e-4);
}

TEST(Run, ACircleRoughenedUnderEq13EndsUnstable) {
    // A user's unit circle under Eq. 13 with the embedded module at S = 3 and the default 40
    // steps to t = 2 (k/h² = 23, far past what S = 3 keeps stable): unguarded it ends `ok`,
    // 7.7% longer and visibly bumpy. Each step grows the length by less than the step's 1%, so
    // the run-wide budget stops it, by t = 0.15. The arclength module keeps the circle.
    const std::vector<std::vector<Vec2>> points = {shapes::circle({0, 0}, 1.0, 200)};
    const Interface curves(points);
    const Box domain = default_domain(points);
    const auto embedded =
        make_velocity("volume-preserving-curvature", {}, GeometryModule::embedded);
    RunOptions o = default_run_options(curves, *embedded, 0.0, 2.0);
    o.step.embedded.smoothing = 3;
    const RunResult rough = run(curves, *embedded, domain, o);
    EXPECT_EQ(rough.status, RunStatus::unstable);
    EXPECT_NE(rough.message.find("the length has grown by"), std::string::npos) << rough.message;
    EXPECT_LT(rough.t, 0.5);
    const auto arclength =
        make_velocity("volume-preserving-curvature", {}, GeometryModule::arclength);
    const RunResult round =
        run(curves, *arclength, domain, default_run_options(curves, *arclength, 0.0, 2.0));
    EXPECT_EQ(round.status, RunStatus::ok);
    EXPECT_LT(std::abs(length(round.curves) / (2.0 * std::numbers::pi) - 1.0), 1e-3);
}

TEST(Run, MergingBubblesUnderEq13EndAsOneRoundBubbleKeepingTheirArea) {
    // Fig. 19's twelve bubbles at the paper's 2048/3/7/4/1e−4 to t = 10.24: they merge into one
    // by t = 1.28, which ends 4.0e−4 from its circle (1.9e−3 with the plain ENO rule for ∇F).
    // Without the correction the area stays within 6.9e−6 of itself; with the mean moved once a
    // step rather than until the area is the law's, it moved by 1e−4 to 3e−4 at the merges,
    // where a neck or gap thinner than a cell is cut or filled in a step.
    const Problem p = make_problem("bubbles-nonlocal");
    const RunOptions o = problem_run_options(p);
    ASSERT_EQ(o.steps, 2048);
    const auto [drift, r] = area_drift(p, o);
    EXPECT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_DOUBLE_EQ(r.t, 10.24);
    EXPECT_EQ(Interface(p.initial).curve_count(), 12u);
    ASSERT_EQ(r.curves.curve_count(), 1u);
    EXPECT_LT(distance_from_its_circle(r.curves), 1e-3);
    EXPECT_LT(drift, 1e-4);
}

TEST(Run, WulffShapesDoNotDependOnTheTilt) {
    // The Wulff problem at its own settings (K = 5: cells of 0.22) to t = 0.5, its anisotropy's
    // axes turned by 10° and by 180°/m: turned back, each run lies within a fifth of a cell of
    // the untilted one (measured: at most 0.026, m = 3 at 10°).
    for (const double m : {3.0, 4.0}) {
        const auto final_curves = [&](double tilt_degrees) {
            const Problem p = make_problem("wulff", {{"m", m}, {"tilt", tilt_degrees}});
            RunOptions o = problem_run_options(p);
            o.t_end = 0.5;
            const auto [r, e] = solve(p, o);
            EXPECT_EQ(r.status, RunStatus::ok);
            const double a = -tilt_degrees * std::numbers::pi / 180.0;
            std::vector<std::vector<Vec2>> back;
            for (const auto& curve : r.curves.curves()) {
                back.emplace_back();
                for (const Vec2 q : curve)
                    back.back().push_back({std::cos(a) * q.x - std::sin(a) * q.y,
                                           std::sin(a) * q.x + std::cos(a) * q.y});
            }
            return Interface(back);
        };
        const Interface untilted = final_curves(0.0);
        for (const double tilt : {10.0, 180.0 / m}) {
            SCOPED_TRACE(::testing::Message() << "m " << m << ", tilt " << tilt);
            EXPECT_LT(interface_distance(untilted, final_curves(tilt)), 0.04);
        }
    }
}

TEST(Run, HalvingTheTimeStepCutsTheTimeErrorFourfold) {
    // Rotation of an off-centre circle at high spatial resolution (K = 7, P = 3): the error is
    // the second-order time error.
    const Problem p = with_initial(
        "propeller-rotation", {shapes::circle({0.6, 0}, 0.5, 1024)}, [](Vec2 x, double t) {
            return distance(x, {0.6 * std::cos(t), 0.6 * std::sin(t)}) - 0.5;
        });
    const double t_end = 1.0;
    const auto [coarse, e1] = solve(p, options(t_end, 5, 7, 3, 1e-8));
    const auto [fine, e2] = solve(p, options(t_end, 10, 7, 3, 1e-8));
    ASSERT_TRUE(e1 && e2);
    const double order = std::log2(*e1 / *e2);
    std::printf("time error %.3g -> %.3g, observed order %.2f\n", *e1, *e2, order);
    EXPECT_GT(order, 1.6);
}

TEST(Run, DirectFlowFieldTracesTheFeetBelowTheContourTolerance) {
    // The same rotation with the law sampled directly: the foot of each characteristic by the
    // fourth-order Runge–Kutta rule in as many substeps as bring it within a tenth of ε, so the
    // step size leaves no mark: one Runge–Kutta step would give 8.3e-4 at N = 4 and 4.2e-5 at
    // N = 8; measured 8.3e-6 and 1.2e-5, the error of the initial 1024-gon's chords.
    const Problem p = with_initial(
        "propeller-rotation", {shapes::circle({0.6, 0}, 0.5, 1024)}, [](Vec2 x, double t) {
            return distance(x, {0.6 * std::cos(t), 0.6 * std::sin(t)}) - 0.5;
        });
    RunOptions o = options(2.0, 4, 7, 3, 1e-8);
    o.step.extension = Extension::direct;
    const auto [coarse, e1] = solve(p, o);
    o.steps = 8;
    const auto [fine, e2] = solve(p, o);
    ASSERT_TRUE(e1 && e2);
    std::printf("errors at N = 4 and 8: %.3g, %.3g\n", *e1, *e2);
    EXPECT_LT(*e1, 2e-5);
    EXPECT_LT(*e2, 2e-5);
    // One contour per step instead of two.
    const auto law = make_velocity(p.velocity, p.velocity_params, p.module);
    const StepResult one = advance(Interface(p.initial), 0.0, 0.25, *law, p.domain, o.step);
    EXPECT_EQ(one.stats.predictor.g_evals, 0u);
    EXPECT_GT(one.stats.corrector.g_evals, 0u);
}

TEST(Run, StepSettlesFarTreePointsWithTheTreeOfExactValues) {
    // The predictor of one merging-circles step, contoured here with every tree point evaluated,
    // must have the tree, the root finding and the refinement of the step's own contour, which
    // settles the points far from Γ by the bound |G(x) − G(y)| ≤ |x − y| + 2k max|W| and by
    // F(x) ± k|W(x)|, evaluating G only where a split test or a crossed triangle needs it.
    const Problem p = make_problem("merging-circles");
    const auto law = make_velocity(p.velocity, p.velocity_params, p.module);
    const Interface initial = prepare_interface(p.initial, p.domain).curves;
    const RunOptions o = options(0.5, 10, 6, 2, 1e-6);
    const double k = 0.05;
    const StepResult step = advance(initial, 0.0, k, *law, p.domain, o.step);

    const DistanceTree tree(initial, p.domain, {.depth = o.step.resolved_tree_depth()});
    const std::vector<Vec2> u = vertex_velocities(*law, 0.0, initial, GeometryContext{&tree});
    auto g = [&](std::span<const Vec2> xs, std::span<double> out) {
        for (std::size_t i = 0; i < xs.size(); ++i) {
            const Vec2 w = nearest_point_extension<Vec2>(initial, u, tree.closest_point(xs[i]));
            out[i] = tree.closest_point(xs[i] - k * w).distance;
        }
    };
    const ContourStats every = contour(g, p.domain, o.step.contour).stats;
    const ContourStats& settled = step.stats.predictor;
    EXPECT_GT(settled.settled, every.settled);
    EXPECT_LT(settled.g_evals_tree, every.g_evals_tree);
    EXPECT_EQ(settled.g_evals_tree + settled.settled, every.g_evals_tree + every.settled);
    EXPECT_EQ(settled.cells, every.cells);
    EXPECT_EQ(settled.vertices, every.vertices);
    EXPECT_EQ(settled.g_evals_roots, every.g_evals_roots);
    EXPECT_EQ(settled.g_evals_refine, every.g_evals_refine);
}

TEST(Run, DistanceTreeDepthChangesOnlyTheCost) {
    // The default L is K + ⌊P/2⌋ (K + P for the Whitney extension, which interpolates on the
    // tree); with the nearest-point extension every use of the trees is an exact distance, so the
    // paper's L = K + P and any other depth give the same curves bit for bit.
    const Problem p = make_problem("merging-circles");
    RunOptions o = options(0.1, 4, 5, 3, 1e-5);
    EXPECT_EQ(o.step.resolved_tree_depth(), 6);
    o.step.extension = Extension::whitney;
    EXPECT_EQ(o.step.resolved_tree_depth(), 8);
    o.step.extension = Extension::nearest_point;
    const auto [fast, e1] = solve(p, o);
    for (int depth : {4, 8}) {
        o.step.tree_depth = depth;
        const auto [other, e2] = solve(p, o);
        EXPECT_EQ(other.curves.curves(), fast.curves.curves()) << "L = " << depth;
    }
}

TEST(Run, ResultDoesNotDependOnTheThreadCount) {
    const Problem p = make_problem("merging-circles");
    const RunOptions o = options(0.2, 8, 4, 1, 1e-4);
    set_thread_count(1);
    const auto [one, e1] = solve(p, o);
    set_thread_count(2);
    const auto [two, e2] = solve(p, o);
    set_thread_count(0);
    ASSERT_EQ(one.curves.size(), two.curves.size());
    for (std::size_t i = 0; i < one.curves.size(); ++i)
        EXPECT_EQ(one.curves.point(i), two.curves.point(i));
    EXPECT_EQ(one.g_evals, two.g_evals);
}

TEST(Run, AFlowThatFailsNearTheCurveIsReportedOnAnyThreadCount) {
    // The field is not finite (or the user's function throws) only near the curve, where the
    // contouring tree evaluates G in batches large enough for all threads: the failure must
    // reach the caller, the same on one thread as on two, and run() must report it as status.
    const Interface circle(std::vector<std::vector<Vec2>>{shapes::circle({0.0, 0.0}, 0.25, 64)});
    const Box domain = Box::centered_square(1.0);
    auto near_right = [](Vec2 x) { return x.x > 0.2 && x.x < 0.3 && std::abs(x.y) < 0.05; };
    const auto not_finite = field_law("holed", [&](double, Vec2 x) {
        return near_right(x) ? Vec2{std::nan(""), 0.0} : Vec2{1.0, 0.0};
    });
    const auto throwing = field_law("refusing", [&](double, Vec2 x) {
        if (near_right(x)) throw std::domain_error("the field refuses this point");
        return Vec2{1.0, 0.0};
    });
    StepOptions o;
    o.contour.depth = 5;
    o.extension = Extension::direct;
    std::vector<std::string> messages;
    for (int threads : {1, 2}) {
        set_thread_count(threads);
        try {
            advance(circle, 0.0, 0.1, *not_finite, domain, o);
            ADD_FAILURE() << "expected NumericalFailure on " << threads << " threads";
        } catch (const NumericalFailure& e) {
            messages.push_back(e.what());
        }
        EXPECT_THROW(advance(circle, 0.0, 0.1, *throwing, domain, o), std::domain_error);
        RunOptions r;
        r.t_end = 0.2;
        r.steps = 2;
        r.step = o;
        const RunResult result = run(circle, *not_finite, domain, r);
        EXPECT_EQ(result.status, RunStatus::error);
        EXPECT_NE(result.message.find("'holed' is not finite"), std::string::npos)
            << result.message;
    }
    set_thread_count(0);
    ASSERT_EQ(messages.size(), 2u);
    EXPECT_EQ(messages[0], messages[1]);
    EXPECT_NE(messages[0].find("velocity 'holed' is not finite"), std::string::npos) << messages[0];
}

TEST(Run, RejectsBadOptionsAndReportsFailuresAsStatus) {
    const Problem p = make_problem("merging-circles");
    const auto law = make_velocity(p.velocity, p.velocity_params);
    const Interface initial(p.initial);
    EXPECT_THROW(run(initial, *law, p.domain, options(0.5, 0, 4, 0, 1e-4)), InvalidInput);
    EXPECT_THROW(run(initial, *law, p.domain, options(-1, 4, 4, 0, 1e-4)), InvalidInput);
    // Growing for a long time reaches the domain boundary: status error naming the time.
    const RunResult r = run(initial, *law, p.domain, options(3.0, 12, 4, 0, 1e-4));
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_NE(r.message.find("t = "), std::string::npos) << r.message;
}

}  // namespace
}  // namespace slc
