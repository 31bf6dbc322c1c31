// The problem of slc run and slc study: a named one, or the user's curve with its defaults.
#include "commands/problem_source.hpp"

#include <algorithm>
#include <filesystem>

#include "commands/run_options.hpp"
#include "slc/core/error.hpp"

namespace slc::cli {

void add_problem_source_options(CLI::App& cmd, ProblemSource& o) {
    auto* problem = cmd.add_option("--problem", o.problem, problem_help());
    auto* initial = cmd.add_option("--initial", o.initial,
                                   "Interface file (JSON) to move instead of a problem");
    problem->excludes(initial);
    cmd.add_option("--velocity", o.velocity, velocity_help())->excludes(problem);
    cmd.add_option("--param", o.params,
                   "key=value: a parameter of the velocity law or the problem (repeatable)");
    cmd.add_option("--t-end", o.t_end,
                   "Final time a (a problem's own by default); with --initial the run starts at "
                   "the file's \"time\" (0 if absent)");
    add_domain_options(cmd, o.domain);
}

Problem resolve_problem(const ProblemSource& o) {
    const auto params = parse_params(o.params);
    if (!o.problem.empty()) {
        Problem p = make_problem(o.problem, params);
        if (o.t_end) p.t_end = *o.t_end;
        if (o.domain.half_width || o.domain.box) p.domain = resolve_domain(o.domain, p.initial);
        return p;
    }
    if (o.velocity.empty()) throw InvalidInput("--initial needs --velocity NAME");
    if (!o.t_end) throw InvalidInput("--initial needs --t-end");
    LoadedInterface in = load_interface(o.initial, o.domain);
    Problem p;
    p.name = std::filesystem::path(o.initial).stem().string();
    p.initial = in.curves.curves();
    p.domain = in.domain;
    p.t_start = in.time;
    p.t_end = *o.t_end;
    p.velocity = o.velocity;
    p.velocity_params = params;
    p.steps = 40;
    p.depth = 5;
    // Lengths relative to the curves' size, so that a curve scaled by any factor (and time by
    // the factor for first-order laws, its square for curvature laws) runs alike.
    const Box bounds = bounding_box(in.curves.points());
    p.length_scale = 0.5 * std::max(bounds.width(), bounds.height());
    p.eps = 1e-5 * p.length_scale;
    p.eta = 1e-10 * p.length_scale;
    // Refinement to convergence: a pass splits only the segments whose midpoint misses ε, so
    // the cost goes where the curve needs it, and corners that the tree cuts are found again.
    // Curvature laws take the paper's two passes: their curvature is noisier where refinement
    // leaves the vertices unevenly spaced.
    const GeometryNeeds needs = make_velocity(p.velocity, params, std::nullopt)->needs();
    p.refine = needs.curvature ? 2 : ContourOptions::until_converged;
    p.triangle_safeguard = false;
    p.max_domain_doublings = 6;
    return p;
}

}  // namespace slc::cli
