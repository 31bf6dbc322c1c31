// Writes docs/defaults.md: users' own curves under the built-in laws at default settings
// (default_run_options, what `slc run --initial` uses), each checked against its exact law at
// three scales, with the CPU seconds of its run on one thread. The same cases are asserted, at
// scale 1 and without times, by tests/accuracy/defaults_test.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "slc/core/parallel.hpp"
#include "user_cases.hpp"

namespace {

using namespace slc;
using namespace slc::user_cases;

std::string law_text(const Case& c) {
    switch (c.law) {
        case Law::circle_radius:
            return "R² = R0² − 2t: vertex radius error / R0";
        case Law::area_rate:
            return "dA/dt = −2π per curve (+2π per hole): error of ΔA / ΔA";
        case Law::area_kept:
            return "area kept, round: ΔA / A0 (roundness 4πA/L²)";
        case Law::offset:
            return "Γ(t) = {F0 = s t}: max |F0 − s t| / ℓ";
        case Law::rigid:
            return "full turn gives Γ(0): max |F0| / ℓ";
    }
    return "";
}

std::string params_text(const Case& c) {
    std::string s;
    for (const auto& [k, v] : c.params) s += fmt::format("{}{}={}", s.empty() ? "" : ", ", k, v);
    return s.empty() ? "" : " (" + s + ")";
}

}  // namespace

int main(int argc, char** argv) {
    std::string out = "docs/defaults.md";
    for (int i = 1; i + 1 < argc; ++i)
        if (std::string(argv[i]) == "--out") out = argv[i + 1];
    set_thread_count(1);
    std::string rows;
    int met = 0, total = 0;
    for (const Case& c : cases()) {
        for (double scale : {1e-6, 1.0, 1e6}) {
            const Outcome o = evaluate(c, scale);
            const bool ok = o.met(c);
            met += ok ? 1 : 0;
            ++total;
            const std::string round =
                c.law == Law::area_kept ? fmt::format(" ({:.5f})", o.roundness) : "";
            rows += fmt::format(
                "| {} | {}{} | {:g} | {:g} | {} | {} | {:.2e}{} | {:.0e} | {} | {:.2f} |\n",
                c.shape, c.velocity, params_text(c), c.t_end * std::pow(scale, c.time_power), scale,
                to_string(o.status), o.components, o.error, round, c.target,
                ok ? "met" : "**not met**", o.cpu_s);
            std::fprintf(stderr, "%s %s x%g: %s error %.3g cpu %.2f\n", c.shape.c_str(),
                         c.velocity.c_str(), scale, ok ? "met" : "NOT MET", o.error, o.cpu_s);
        }
    }
    std::string laws;
    std::vector<Law> listed;
    for (const Case& c : cases()) {
        if (std::find(listed.begin(), listed.end(), c.law) != listed.end()) continue;
        listed.push_back(c.law);
        laws += fmt::format("- {}: {}\n", c.velocity, law_text(c));
    }
    std::ofstream f(out);
    f << "# Default settings on users' own curves\n\n"
      << "Written by `build/bin/defaults_bench` (`scripts/bench`); "
         "`tests/accuracy/defaults_test.cpp` asserts the same cases at scale 1.\n\n"
      << "Each row is a curve of a user's own moved by a built-in law with nothing set but the "
         "law and the final time, as `slc run --initial FILE --velocity LAW --t-end T` runs it "
         "(`default_run_options`: N = 40 (10 under a flow field evaluated directly, whose steps "
         "each add their contour's error; under `mullins-sekerka` and `hele-shaw` up to 2,000 "
         "for the start's sharpest turn, 4tσ|C|³), K = 5, ε = 1e−5 ℓ, η = 1e−10 ℓ with ℓ the "
         "curves' half-width; curvature laws with the arclength module, arcs and P = 2; other laws "
         "refined until converged, evaluated off the curve where the law allows it, with arcs; a "
         "domain "
         "that doubles when the curves near its edge). The error is measured against the law's "
         "exact solution; the same shape scaled by 1e−6 and 1e6 (time by the scale, or its square "
         "for curvature laws) must give the same relative error. CPU seconds of the time loop on "
         "one thread.\n\n"
      << "Exact laws:\n\n"
      << laws << "\n"
      << fmt::format("{} of {} rows meet their target.\n\n", met, total)
      << "| shape | law | t | scale | status | components | error | target | | CPU s |\n"
      << "|---|---|---|---|---|---|---|---|---|---|\n"
      << rows;
    std::fprintf(stderr, "wrote %s: %d of %d rows met\n", out.c_str(), met, total);
    return 0;
}
