// The problem of slc run and slc study: a named one, or the user's curve with its defaults.
#include "commands/problem_source.hpp"

#include <algorithm>
#include <filesystem>

#include "commands/run_options.hpp"
#include "slc/core/error.hpp"
#include "slc/evolve/defaults.hpp"

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
    const auto law = make_velocity(o.velocity, params, std::nullopt);
    return curve_problem(std::filesystem::path(o.initial).stem().string(), in.curves, in.domain,
                         in.time, *o.t_end, *law, o.velocity, params);
}

}  // namespace slc::cli
