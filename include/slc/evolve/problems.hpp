// The paper's experiments (§4.4–4.7) and the two standard benchmarks (Zalesak's disk, the single
// vortex) as named problems: initial curves, domain, velocity law, the paper's parameters as
// defaults, and the exact solution where one is known.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/evolve/step.hpp"
#include "slc/velocity/factory.hpp"

namespace slc {

/// A problem's own parameters (set with --param like the velocity's, e.g. tilt, R0).
struct ProblemParameter {
    std::string name;
    double value = 0.0;
    std::string meaning;
};

/// The paper's 5×5 convergence study (§4.2): row r runs N0·2^r steps, depth K0 + r, ε0/10^r and
/// smoothing[r]; columns P = 0..4.
struct StudyPlan {
    int steps = 40;
    int depth = 3;
    double eps = 1e-3;
    std::vector<int> smoothing = {0, 0, 0, 0, 0};
    std::string
        paper_table;  ///< the paper's table in its reference CSV ("table5_rotation"), if any
};

struct Problem {
    std::string name;
    std::string description;  ///< what it is and where in the paper
    std::vector<std::vector<Vec2>> initial;
    Box domain;
    double t_start = 0.0;  ///< the initial curves' time (an interface file's "time")
    double t_end = 1.0;
    int steps = 40;     ///< N
    int depth = 5;      ///< K
    int refine = 2;     ///< P
    double eps = 1e-5;  ///< ε
    int smoothing = 0;  ///< S
    std::string velocity;
    VelocityParams velocity_params;
    std::optional<GeometryModule> module;  ///< overrides the law's default geometry module
    std::vector<ProblemParameter> parameters;
    StudyPlan study;
    /// The exact signed distance to Γ(t) at points, when known at time t (else nullopt).
    std::function<std::optional<std::vector<double>>(std::span<const Vec2>, double)> exact;
};

/// One line per problem, in a fixed order, for --help and errors.
struct ProblemInfo {
    std::string name;
    std::string summary;
};
const std::vector<ProblemInfo>& problem_catalog();

/// The problem `name` with parameters set from params: keys naming a problem parameter set it,
/// the others are velocity parameters (checked by make_velocity). Throws InvalidInput for an
/// unknown problem ("unknown problem 'x'; known: ...").
Problem make_problem(const std::string& name, const std::map<std::string, double>& params = {});

/// The paper's Eq. (11): the largest |F(x, t)| over the vertices and segment midpoints of curves,
/// F the exact signed distance; nullopt when the problem has no exact solution at t.
std::optional<double> max_error(const Problem& problem, const Interface& curves, double t);

}  // namespace slc
