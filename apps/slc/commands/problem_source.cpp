// The problem of slc run and slc study: a named one, or the user's curve with its defaults.
#include "commands/problem_source.hpp"

#include <filesystem>
#include <string>

#include "commands/run_options.hpp"
#include "slc/core/error.hpp"
#include "slc/evolve/defaults.hpp"

namespace slc::cli {

void add_problem_source_options(CLI::App& cmd, ProblemSource& o) {
    auto* problem = cmd.add_option("--problem", o.problem, problem_help());
    auto* initial = cmd.add_option(
        "--initial", o.initial,
        "Curves (an interface file, .json) or a closed triangle surface (.obj, .stl, "
        ".ply; or .vdb, an OpenVDB file whose first level-set grid is contoured at about its "
        "voxel size) to move instead of a problem");
    problem->excludes(initial);
    cmd.add_option("--velocity", o.velocity, velocity_help())->excludes(problem);
    cmd.add_option("--speed", o.speed,
                   "Normal speed v as an expression of x, y, t, C (curvature, -1/R on a circle), "
                   "nx, ny (outward unit normal) and --param constants: u = v N, v > 0 moves "
                   "outward (\"1\" grows circles, \"C\" is curvature flow, \"a + C\" with "
                   "--param a=0.5). For surfaces also z and nz, C the mean curvature (-2/R on a "
                   "sphere). Instead of --velocity")
        ->excludes(problem);
    cmd.add_option("--field", o.field,
                   "Flow field u,v as two expressions of x, y, t and --param constants, separated "
                   "by a comma (\"-y, x\" rotates about the origin); for surfaces u,v,w of x, "
                   "y, z, t (\"-y, x, 0\"). Instead of --velocity")
        ->excludes(problem);
    cmd.add_option("--field-file", o.field_file,
                   "Steady flow field on a uniform lattice, bilinearly interpolated: CSV lines "
                   "x,y,u,v (any order, header optional) or legacy VTK STRUCTURED_POINTS (.vtk, "
                   "ASCII) with a 2- or 3-component point-data array. The curves must stay "
                   "inside the lattice. For a surface: an OpenVDB file (.vdb) whose first vector "
                   "grid (vec3s or vec3d) is trilinearly interpolated; the surface must stay "
                   "within its active voxels. Instead of --velocity")
        ->excludes(problem);
    cmd.add_option("--field-outside", o.field_outside,
                   "Where the --field-file field is not given: 'error' (the default: a run that "
                   "leaves the lattice, or the grid's active voxels, ends with an error naming "
                   "the time and the place) or 'zero' (the field is zero there, and what leaves "
                   "stops)")
        ->check(CLI::IsMember({"error", "zero"}))
        ->needs("--field-file");
    cmd.add_option("--param", o.params,
                   "key=value: a parameter of the velocity law or the problem, or a constant of "
                   "--speed and --field expressions (repeatable)");
    cmd.add_option("--t-end", o.t_end,
                   "Final time a (a problem's own by default); with --initial the run starts at "
                   "the file's \"time\" (0 if absent)");
    add_domain_options(cmd, o.domain,
                       "; a run of a user's curves or surface doubles it about its centre, K a "
                       "level deeper, as they near its edge (up to six times; a named problem "
                       "keeps its own)");
}

Problem resolve_problem(const ProblemSource& o) {
    const auto params = parse_params(o.params);
    if (!o.problem.empty()) {
        Problem p = make_problem(o.problem, params);
        if (o.t_end) p.t_end = *o.t_end;
        if (o.domain.half_width || o.domain.box) p.domain = resolve_domain(o.domain, p.initial);
        return p;
    }
    const std::string chosen =
        one_velocity_law({{"--velocity", !o.velocity.empty()},
                          {"--speed", o.speed.has_value()},
                          {"--field", o.field.has_value()},
                          {"--field-file", o.field_file.has_value()}},
                         "--initial needs --velocity NAME, or --speed, --field or --field-file");
    if (!o.t_end) throw InvalidInput("--initial needs --t-end");
    LoadedInterface in = load_interface(o.initial, o.domain);
    // The law first: its defaults are the run's, and a lattice must hold the curves.
    Problem law_source;
    law_source.velocity = o.velocity.empty() ? chosen.substr(2) : o.velocity;  // "speed", ...
    law_source.velocity_expression = o.speed ? *o.speed : o.field.value_or("");
    law_source.velocity_file = o.field_file.value_or("");
    law_source.velocity_zero_outside = o.field_outside == "zero";
    law_source.velocity_params = params;
    const auto law = problem_law(law_source, std::nullopt);
    require_inside_extent(*law, in.curves);
    Problem p = curve_problem(std::filesystem::path(o.initial).stem().string(), in.curves,
                              in.domain, in.time, *o.t_end, *law, law_source.velocity, params);
    p.velocity_expression = law_source.velocity_expression;
    p.velocity_file = law_source.velocity_file;
    p.velocity_zero_outside = law_source.velocity_zero_outside;
    return p;
}

}  // namespace slc::cli
