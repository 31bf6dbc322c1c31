// Users' own curves at default settings keep the exact law of their velocity (docs/defaults.md):
// curvature flow loses area at 2π per curve, the volume-preserving flow keeps it and rounds the
// curve, normal speed gives the exact offset (corners included), a full turn gives the shape back,
// and the same curve scaled by 1e−6 or 1e6 gives the same relative error.
#include <gtest/gtest.h>

#include <cstdio>

#include "slc/core/parallel.hpp"
#include "user_cases.hpp"

namespace slc {
namespace {

using namespace user_cases;

std::string name(const Case& c) {
    return c.shape + " under " + c.velocity + " to t = " + std::to_string(c.t_end);
}

TEST(Defaults, EveryUserCaseKeepsItsExactLaw) {
    set_thread_count(1);  // the results do not depend on it; CI runs tests side by side
    for (const Case& c : cases()) {
        const Outcome o = evaluate(c, 1.0);
        std::printf("%-55s status %s, %zu components, error %.3g (target %.0e), roundness %.5f\n",
                    name(c).c_str(), to_string(o.status), o.components, o.error, c.target,
                    o.roundness);
        EXPECT_EQ(o.status, RunStatus::ok) << name(c);
        EXPECT_EQ(o.components, o.expected_components) << name(c);
        EXPECT_LE(o.error, c.target) << name(c);
        if (c.law == Law::area_kept) {
            EXPECT_GE(o.roundness, 0.999) << name(c);
        }
    }
}

TEST(Defaults, ScaledCurvesGiveTheSameRelativeError) {
    // ε, η and the domain follow the curve's size; time scales with length for first-order laws
    // and with its square for curvature laws.
    set_thread_count(1);
    for (const Case& c : cases()) {
        if (!(c.shape == "circle" && c.velocity == "curvature") &&
            !(c.shape == "star" && c.velocity == "unit-normal" && !c.params.count("speed")))
            continue;
        const double at_one = evaluate(c, 1.0).error;
        for (double scale : {1e-6, 1e6}) {
            const Outcome o = evaluate(c, scale);
            std::printf("%s at scale %g: error %.3g against %.3g at scale 1\n", name(c).c_str(),
                        scale, o.error, at_one);
            EXPECT_EQ(o.status, RunStatus::ok);
            EXPECT_LE(o.error, 2.0 * at_one) << name(c) << " at scale " << scale;
            EXPECT_GE(o.error, 0.5 * at_one) << name(c) << " at scale " << scale;
        }
    }
}

}  // namespace
}  // namespace slc
