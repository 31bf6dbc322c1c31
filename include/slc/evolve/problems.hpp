/// @file
/// The paper's experiments (§4.4–4.7) and the two standard benchmarks (Zalesak's disk, the single
/// vortex) as named problems: initial curves, domain, velocity law, the paper's parameters as
/// defaults, and the exact solution where one is known.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/evolve/run.hpp"
#include "slc/evolve/step.hpp"
#include "slc/velocity/factory.hpp"

namespace slc {

/// A problem's own parameters (set with --param like the velocity's, for instance tilt, R0).
struct ProblemParameter {
    std::string name;     ///< as in --param name=value
    double value = 0.0;   ///< the value in use (the default unless set)
    std::string meaning;  ///< one line for --help
};

/// The paper's 5×5 convergence study (§4.2): row r runs N0·2^r steps, depth K0 + r, ε0/10^r and
/// smoothing[r]; columns P = 0..4.
struct StudyPlan {
    int steps = 40;                                ///< N0, the steps of row 0
    int depth = 3;                                 ///< K0, the depth of row 0
    double eps = 1e-3;                             ///< ε0, the tolerance of row 0
    std::vector<int> smoothing = {0, 0, 0, 0, 0};  ///< S of each row
    std::string
        paper_table;  ///< the paper's table in its reference CSV ("table5_rotation"), if any
};

/// A named problem: initial curves, domain, law and the paper's settings as defaults.
struct Problem {
    std::string name;                        ///< as in --problem NAME
    std::string description;                 ///< what it is and where in the paper
    std::vector<std::vector<Vec2>> initial;  ///< the initial curves, not yet validated
    Box domain;                              ///< the square the curves must stay in
    double t_start = 0.0;  ///< the initial curves' time (an interface file's "time")
    double t_end = 1.0;    ///< a, the final time
    /// The size ℓ of the curves, which scales the lengths the command line defaults to (ε from
    /// -K is 10^−K ℓ): 1 for a named problem, the half-width of a user's curves.
    double length_scale = 1.0;
    /// The law: a built-in one by make_velocity name, or "speed" or "field" (velocity_expression
    /// is its text) or "field-file" (velocity_file names the file); see problem_law().
    std::string velocity;
    VelocityParams velocity_params;   ///< its parameters, or the expression's constants
    std::string velocity_expression;  ///< for "speed" and "field": the expression
    std::string velocity_file;        ///< for "field-file": the lattice velocity's file
    /// For "field-file": the field is zero outside the lattice (zero_outside_extent) instead of
    /// unknown there, where a run refuses the curves.
    bool velocity_zero_outside = false;
    std::optional<GeometryModule> module;  ///< overrides the law's default geometry module
    /// The settings of its runs: N, K, P, ε, η, S, the extension, arcs and area correction, the
    /// triangle safeguard, thin depth, guards, domain doublings and stop count. A named problem
    /// holds the paper's (nearest-point extension, chords, uniform K, fixed box, a 5% area
    /// guard); a user's curve (curve_problem) the defaults of default_run_options, at the depth
    /// its domain takes. problem_run_options sets their t_start, t_end and embedded mesh size.
    RunOptions run;
    std::vector<ProblemParameter> parameters;  ///< the problem's own parameters, in use
    StudyPlan study;                           ///< the settings of `slc study`
    /// The exact signed distance to Γ(t) at points, when known at time t (else nullopt).
    std::function<std::optional<std::vector<double>>(std::span<const Vec2>, double)> exact;
    /// A named problem (make_problem); false for a user's curves (curve_problem).
    bool named = true;
    /// A user's curves under a flow field: unless N is given, 10 steps evaluated directly (its
    /// default), 40 with another extension, whose steps have a time error (run_options).
    bool flow_field = false;
};

/// One line per problem, in a fixed order, for --help and errors.
struct ProblemInfo {
    std::string name;     ///< as in --problem NAME
    std::string summary;  ///< one line
};
/// Every named problem, in a fixed order: propeller-rotation, triangle-normal, merging-circles,
/// wulff, circle-curvature, polygon-curvature, spiral-nonlocal, bubbles-nonlocal, coarsening,
/// zalesak, vortex.
const std::vector<ProblemInfo>& problem_catalog();

/// The problem `name` with parameters set from params: keys naming a problem parameter set it,
/// the others are velocity parameters (checked by make_velocity). Throws InvalidInput for an
/// unknown problem ("unknown problem 'x'; known: ...").
Problem make_problem(const std::string& name, const std::map<std::string, double>& params = {});

/// The options of a run of the problem at its own settings: its time interval, N, K, P, ε, η, S,
/// extension, arcs, area correction, triangle safeguard and domain doublings; M = 2^(K+1) and the
/// rest the defaults of DESIGN §4.
RunOptions problem_run_options(const Problem& problem);

/// The law of problem: speed_expression_law(velocity_expression, velocity_params, module) for
/// velocity "speed", field_expression_law(velocity_expression, velocity_params) for "field",
/// grid_field_law(velocity_file) for "field-file", else make_velocity(velocity,
/// velocity_params, module). Throws InvalidInput as those do.
std::unique_ptr<VelocityLaw> problem_law(const Problem& problem,
                                         std::optional<GeometryModule> module);

/// The error of the paper's Equation (11): the largest |F(x, t)| over the vertices and segment
/// midpoints of curves, F the exact signed distance; nullopt when the problem has no exact solution
/// at t.
std::optional<double> max_error(const Problem& problem, const Interface& curves, double t);

}  // namespace slc
