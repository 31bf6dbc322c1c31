// Tests of the time loop: a run continued from the state an observer saw ends with the same
// curves, bit for bit, and the same counters, as the run never stopped; each step's CPU time;
// a law's extent, which the curves may not leave.
#include "slc/evolve/run.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <optional>

#include "slc/core/error.hpp"
#include "slc/core/stop.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/velocity/grid_field.hpp"
#include "slc/velocity/laws.hpp"

namespace slc {
namespace {

RunOptions six_steps() {
    RunOptions o;
    o.t_start = 0.25;
    o.t_end = 1.0;
    o.steps = 6;
    o.step.contour.depth = 4;
    o.step.contour.refine_passes = 1;
    return o;
}

bool same_bits(const Interface& a, const Interface& b) {
    if (a.size() != b.size() || a.curve_count() != b.curve_count()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const Vec2 p = a.points()[i], q = b.points()[i];
        if (std::bit_cast<std::uint64_t>(p.x) != std::bit_cast<std::uint64_t>(q.x) ||
            std::bit_cast<std::uint64_t>(p.y) != std::bit_cast<std::uint64_t>(q.y))
            return false;
    }
    return true;
}

TEST(Run, ResumedFromAnyStepEndsBitForBitAsTheUninterruptedRun) {
    const Interface square({{{-1, -1}, {0.5, -1}, {0.5, 0.5}, {-1, 0.5}}});
    const Rotation law(2.0);
    const Box domain = Box::centered_square(2.0);
    const RunOptions options = six_steps();
    std::vector<RunResult> seen;
    const RunResult whole = run(square, law, domain, options, [&](const StepReport& s) {
        seen.push_back(*s.run);
        return true;
    });
    ASSERT_EQ(whole.status, RunStatus::ok);
    ASSERT_EQ(seen.size(), 6u);
    for (int n = 1; n < 6; ++n) {
        SCOPED_TRACE(n);
        const RunResult& from = seen[static_cast<std::size_t>(n - 1)];
        EXPECT_EQ(from.steps_done, n);
        const RunResult rest = resume(from, law, domain, options);
        EXPECT_EQ(rest.status, RunStatus::ok);
        EXPECT_EQ(rest.steps_done, 6);
        EXPECT_EQ(rest.t, whole.t);
        EXPECT_TRUE(same_bits(rest.curves, whole.curves));
        EXPECT_EQ(rest.g_evals, whole.g_evals);
        EXPECT_EQ(rest.vertices_produced, whole.vertices_produced);
    }
}

// A stop requested within a step (as Ctrl-C does, slc/core/stop.hpp) ends the run at the next
// stage of that step: status interrupted, with the interface and time of the last whole step,
// from which resume() goes on as if nothing had happened. Here the law asks for the stop while
// the third step evaluates it.
TEST(Run, AStopWithinAStepKeepsTheLastWholeStep) {
    const Interface square({{{-1, -1}, {0.5, -1}, {0.5, 0.5}, {-1, 0.5}}});
    const Box domain = Box::centered_square(2.0);
    const RunOptions options = six_steps();  // steps of 0.125 from t = 0.25
    const LocalLaw stopping("stopping", {}, [](double t, const VertexState& s) {
        if (t > 0.55) request_stop();
        return Vec2{-s.point.y, s.point.x};
    });
    std::vector<RunResult> seen;
    clear_stop();
    const RunResult stopped = run(square, stopping, domain, options, [&](const StepReport& s) {
        seen.push_back(*s.run);
        return true;
    });
    ASSERT_TRUE(stop_requested());
    clear_stop();
    EXPECT_EQ(stopped.status, RunStatus::interrupted);
    ASSERT_EQ(stopped.steps_done, 2);
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(stopped.t, 0.5);
    EXPECT_TRUE(same_bits(stopped.curves, seen[1].curves));
}

TEST(Run, ResumeRejectsAStateThatIsNotOfThisRun) {
    const Interface square({{{-1, -1}, {0.5, -1}, {0.5, 0.5}, {-1, 0.5}}});
    const Rotation law(2.0);
    const Box domain = Box::centered_square(2.0);
    RunResult from;
    from.curves = square;
    from.steps_done = 2;
    from.t = 0.5;  // after 2 of 6 steps from 0.25 to 1 the time is 0.5 exactly
    EXPECT_NO_THROW(resume(from, law, domain, six_steps()));
    from.t = 0.5000000000000001;
    EXPECT_THROW(resume(from, law, domain, six_steps()), InvalidInput);
    from.t = 1.0;
    from.steps_done = 6;
    EXPECT_THROW(resume(from, law, domain, six_steps()), InvalidInput);
    from.steps_done = -1;
    EXPECT_THROW(resume(from, law, domain, six_steps()), InvalidInput);
}

TEST(Run, ReportsEachStepsCpuTimeWithinTheRunsTotal) {
    const Interface square({{{-1, -1}, {0.5, -1}, {0.5, 0.5}, {-1, 0.5}}});
    const Rotation law(2.0);
    const Box domain = Box::centered_square(2.0);
    double sum = 0.0;
    int negative = 0;
    const RunResult r = run(square, law, domain, six_steps(), [&](const StepReport& s) {
        sum += s.step_cpu_s;
        negative += s.step_cpu_s < 0.0;
        return true;
    });
    ASSERT_EQ(r.status, RunStatus::ok);
    EXPECT_EQ(negative, 0);
    // The steps alone, without the loop's bookkeeping and the observer: at most the run's total.
    EXPECT_LE(sum, r.cpu_s);
}

TEST(Run, EndsWhenNoMoreComponentsThanAskedAreLeft) {
    // Two circles shrinking at unit speed: the one of radius 0.22 vanishes at t = 0.22, within
    // step 5 (k = 0.05); asked to stop at one component the run ends there, status ok, not at 0.45.
    const Interface two(std::vector<std::vector<Vec2>>{shapes::circle({-0.8, 0.0}, 0.22, 64),
                                                       shapes::circle({0.6, 0.0}, 0.6, 128)});
    RunOptions o;
    o.t_end = 0.45;
    o.steps = 9;
    o.step.contour.depth = 6;
    o.stop_components = 1;
    const RunResult r = run(two, NormalSpeed(-1.0), Box::centered_square(2.0), o);
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_EQ(r.steps_done, 5);
    EXPECT_NEAR(r.t, 0.25, 1e-12);
    EXPECT_EQ(r.curves.curve_count(), 1u);
    EXPECT_NE(r.message.find("1 components left"), std::string::npos) << r.message;
    o.stop_components = 0;
    EXPECT_EQ(run(two, NormalSpeed(-1.0), Box::centered_square(2.0), o).steps_done, 9);
}

TEST(Run, EndsWithAnErrorWhenTheCurvesLeaveTheLawsExtent) {
    // u = (1, 0) on the lattice [−1, 1]²: a circle of radius 0.2 about (0.5, 0) reaches x = 1
    // at t = 0.3, between steps 2 and 3 of 0.125.
    GridVelocity g{{-1, -1}, {1, 1}, 3, 3, std::vector<Vec2>(9, Vec2{1, 0})};
    const GridField field(g, "lattice");
    const Interface start({shapes::circle({0.5, 0}, 0.2, 64)});
    RunOptions o = six_steps();
    o.t_start = 0.0;
    o.t_end = 0.75;
    const RunResult r = run(start, field, Box::centered_square(2.0), o);
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_EQ(r.steps_done, 2);
    EXPECT_NE(r.message.find("the curves left the region where velocity 'lattice' is known"),
              std::string::npos)
        << r.message;
    EXPECT_FALSE(vertex_outside_extent(field, r.curves));  // the last curves inside it
    // Curves outside it from the start are bad input.
    const Interface outside({shapes::circle({1.5, 0}, 0.2, 64)});
    EXPECT_THROW(run(outside, field, Box::centered_square(2.0), o), InvalidInput);
}

TEST(Run, CurvesCarriedOutOfTheDomainWithinAStepAreAnErrorNotAVanishing) {
    // u = (40, 0) takes a circle of radius 0.2 from the origin past x = 2 within a step of
    // 0.125 (none split): the contour in [−2, 2]² is empty, but the curves left the domain;
    // they did not vanish.
    const Translation fast({40.0, 0.0});
    const Interface start({shapes::circle({0.0, 0.0}, 0.2, 64)});
    RunOptions o = six_steps();
    o.max_substep_halvings = 0;
    const RunResult r = run(start, fast, Box::centered_square(2.0), o);
    EXPECT_EQ(r.status, RunStatus::error);
    EXPECT_EQ(r.steps_done, 0);
    EXPECT_NE(r.message.find("the flow carries the curves out of the domain [-2, 2] x [-2, 2]"),
              std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find("(--domain, --box), or take more steps (-N)"), std::string::npos);
}

}  // namespace
}  // namespace slc
