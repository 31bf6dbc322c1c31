// Tests of batched bracketed root finding (paper §2.1 "Bisection"): every method converges to
// |G| ≤ η inside the bracket; Brent and Illinois are far cheaper than bisection on smooth G and
// safe on bad G; a jump stalls cleanly; one batch per round.
#include "slc/contour/root_finding.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "slc/core/error.hpp"

namespace slc {
namespace {

constexpr double eta = 1e-10;
constexpr RootMethod all_methods[] = {RootMethod::brent, RootMethod::illinois,
                                      RootMethod::bisection};

/// Random brackets of length about 0.1 across the circle |x| = 0.6, where G = |x| − 0.6.
std::vector<Bracket> circle_brackets(unsigned seed, int n) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(0.0, 6.283185307179586), off(0.01, 0.09);
    std::vector<Bracket> out;
    for (int k = 0; k < n; ++k) {
        const double a = angle(rng), b = angle(rng);
        const Vec2 inside = (0.6 - off(rng)) * Vec2{std::cos(a), std::sin(a)};
        const Vec2 outside = inside + 0.1 * Vec2{std::cos(b), std::sin(b)};
        if (norm(outside) <= 0.6) continue;
        out.push_back({inside, outside, norm(inside) - 0.6, norm(outside) - 0.6});
    }
    return out;
}

const auto circle_g = [](std::span<const Vec2> x, std::span<double> v) {
    for (std::size_t i = 0; i < x.size(); ++i) v[i] = norm(x[i]) - 0.6;
};

TEST(FindRoots, EveryMethodConvergesInsideTheBracket) {
    const auto brackets = circle_brackets(7, 500);
    for (RootMethod method : all_methods) {
        const auto roots = find_roots(circle_g, brackets, {.eta = eta, .method = method});
        ASSERT_EQ(roots.size(), brackets.size());
        for (std::size_t i = 0; i < roots.size(); ++i) {
            EXPECT_TRUE(roots[i].converged);
            EXPECT_LE(std::abs(roots[i].value), eta);
            // The reported value is G at the reported point (up to the rounding of |x|).
            EXPECT_NEAR(std::abs(norm(roots[i].point) - 0.6), std::abs(roots[i].value), 1e-15);
            EXPECT_GT(roots[i].t, 0.0);
            EXPECT_LT(roots[i].t, 1.0);
        }
    }
}

TEST(FindRoots, BrentAndIllinoisAreFarCheaperThanBisectionOnSmoothG) {
    const auto brackets = circle_brackets(11, 500);
    auto mean_evaluations = [&](RootMethod method) {
        double total = 0.0;
        for (const Root& r : find_roots(circle_g, brackets, {.eta = eta, .method = method}))
            total += r.evaluations;
        return total / static_cast<double>(brackets.size());
    };
    // Bisection halves a bracket of length 0.1 until |G| ≤ 1e−10: about log2(1e9) ≈ 30 steps.
    EXPECT_GT(mean_evaluations(RootMethod::bisection), 25.0);
    EXPECT_LT(mean_evaluations(RootMethod::brent), 5.0);
    EXPECT_LT(mean_evaluations(RootMethod::illinois), 6.0);
}

TEST(FindRoots, SafeguardsKeepBadFunctionsNearBisectionCost) {
    // x^9 − 1e−6 on [0, 1]: flat near the root and steep at the far end, the case where plain
    // regula falsi crawls from one side.
    const auto flat = [](std::span<const Vec2> x, std::span<double> v) {
        for (std::size_t i = 0; i < x.size(); ++i) v[i] = std::pow(x[i].x, 9) - 1e-6;
    };
    const Bracket b{{0.0, 0.0}, {1.0, 0.0}, -1e-6, 1.0 - 1e-6};
    const int bisection =
        find_roots(flat, {&b, 1}, {.eta = 1e-14, .method = RootMethod::bisection})[0].evaluations;
    for (RootMethod method : {RootMethod::brent, RootMethod::illinois}) {
        const Root r = find_roots(flat, {&b, 1}, {.eta = 1e-14, .method = method})[0];
        EXPECT_TRUE(r.converged);
        EXPECT_LE(std::abs(r.value), 1e-14);
        EXPECT_LE(r.evaluations, 3 * bisection);
    }
}

TEST(FindRoots, JumpAcrossZeroStallsAtTheJump) {
    const auto step = [](std::span<const Vec2> x, std::span<double> v) {
        for (std::size_t i = 0; i < x.size(); ++i) v[i] = x[i].x < 0.3 ? -1.0 : 1.0;
    };
    const Bracket b{{0.0, 0.5}, {1.0, 0.5}, -1.0, 1.0};
    for (RootMethod method : all_methods) {
        const Root r = find_roots(step, {&b, 1}, {.eta = eta, .method = method})[0];
        EXPECT_FALSE(r.converged);
        // The bracket shrinks to a few units of rounding around the jump.
        EXPECT_NEAR(r.point.x, 0.3, 1e-14);
        EXPECT_GT(r.t, 0.0);
        EXPECT_LT(r.t, 1.0);
        EXPECT_LT(r.evaluations, 200);
    }
}

TEST(FindRoots, JumpSlopeGivesUpAJumpEarlyAndLeavesSmoothRootsAlone) {
    // A jump of 0.2 across zero at x = 0.3 on a bracket of length 1: with Λ_jump = 1024 the
    // secant |G(lo)| + |G(hi)| > 1024 |hi − lo| once the bracket is below 2e−4, after about a
    // dozen evaluations instead of fifty.
    const auto jump = [](std::span<const Vec2> x, std::span<double> v) {
        for (std::size_t i = 0; i < x.size(); ++i) v[i] = x[i].x < 0.3 ? x[i].x - 0.4 : x[i].x;
    };
    const Bracket b{{0.0, 0.5}, {1.0, 0.5}, -0.4, 1.0};
    for (RootMethod method : all_methods) {
        SCOPED_TRACE(static_cast<int>(method));
        const Root slow = find_roots(jump, {&b, 1}, {.eta = eta, .method = method})[0];
        const Root fast =
            find_roots(jump, {&b, 1}, {.eta = eta, .method = method, .jump_slope = 1024.0})[0];
        EXPECT_FALSE(slow.converged);
        EXPECT_FALSE(fast.converged);
        EXPECT_GT(slow.evaluations, 45);
        EXPECT_LT(fast.evaluations, 20);
        EXPECT_NEAR(fast.point.x, 0.3, 2e-4);
    }
    // On smooth G (slope 1) nothing changes: the same roots, the same evaluations.
    const auto brackets = circle_brackets(13, 300);
    for (RootMethod method : all_methods) {
        const auto plain = find_roots(circle_g, brackets, {.eta = eta, .method = method});
        const auto guarded =
            find_roots(circle_g, brackets, {.eta = eta, .method = method, .jump_slope = 1024.0});
        for (std::size_t i = 0; i < plain.size(); ++i) {
            EXPECT_EQ(guarded[i].point, plain[i].point);
            EXPECT_EQ(guarded[i].evaluations, plain[i].evaluations);
        }
    }
    const Bracket unit{{0.0, 0.0}, {1.0, 0.0}, -0.5, 0.5};
    EXPECT_THROW(find_roots(circle_g, {&unit, 1}, {.eta = eta, .jump_slope = 0.0}), InvalidInput);
}

TEST(FindRoots, EachRoundIsOneBatch) {
    const auto brackets = circle_brackets(3, 300);
    int calls = 0;
    std::size_t points = 0;
    const auto counting = [&](std::span<const Vec2> x, std::span<double> v) {
        ++calls;
        points += x.size();
        circle_g(x, v);
    };
    const auto roots = find_roots(counting, brackets, {.eta = eta});
    int most = 0;
    std::size_t total = 0;
    for (const Root& r : roots) {
        most = std::max(most, r.evaluations);
        total += static_cast<std::size_t>(r.evaluations);
    }
    EXPECT_EQ(calls, most);
    EXPECT_EQ(points, total);
}

TEST(FindRoots, EndWithinEtaIsTheRootWithoutEvaluation) {
    const Bracket b{{0.6, 0.0}, {1.0, 0.0}, 0.0, 0.4};
    const Root r = find_roots(circle_g, {&b, 1}, {.eta = eta})[0];
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.evaluations, 0);
    EXPECT_EQ(r.t, 0.0);
}

TEST(FindRoots, BracketWithoutSignChangeIsInvalid) {
    const Bracket same{{0.0, 0.0}, {1.0, 0.0}, 0.5, 0.7};
    EXPECT_THROW(find_roots(circle_g, {&same, 1}, {}), InvalidInput);
    const Bracket nan{{0.0, 0.0}, {1.0, 0.0}, std::nan(""), 0.7};
    EXPECT_THROW(find_roots(circle_g, {&nan, 1}, {}), InvalidInput);
    EXPECT_THROW(find_roots(circle_g, {}, {.eta = 0.0}), InvalidInput);
}

}  // namespace
}  // namespace slc
