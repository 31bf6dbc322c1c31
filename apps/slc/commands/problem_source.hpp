// The problem a command runs, shared by `slc run` and `slc study`: a named problem (--problem)
// or the user's curve (--initial) under a built-in law (--velocity, --param, --t-end), with the
// defaults a user's curve gets.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "commands/common.hpp"
#include "slc/evolve/problems.hpp"

namespace slc::cli {

/// --problem, or --initial with a law (--velocity, --speed, --field or --field-file) and
/// --t-end; --param, --domain and --box.
struct ProblemSource {
    std::string problem;
    std::string initial;
    std::string velocity;
    std::optional<std::string> speed;       ///< --speed EXPR: a normal speed
    std::optional<std::string> field;       ///< --field EXPR,EXPR: a flow field
    std::optional<std::string> field_file;  ///< --field-file PATH: a flow field on a lattice
    /// --field-outside: "error" (the default), or "zero": the --field-file field is zero outside
    /// its lattice (or grid).
    std::string field_outside = "error";
    std::optional<double> t_end;
    DomainOptions domain;
    std::vector<std::string> params;
};

/// Adds the options of ProblemSource to cmd (--problem and --initial exclusive, the law's
/// options only with --initial).
void add_problem_source_options(CLI::App& cmd, ProblemSource& source);

/// The problem to run: a named one (its --t-end and domain overridden when given), or one
/// assembled from the user's file and law with the defaults of a user's curve: N = 40, K = 5,
/// ε = 1e−5 ℓ and η = 1e−10 ℓ (ℓ the curves' half-width), P = 2 for laws that need curvature and
/// refinement until converged otherwise, no triangle safeguard, a domain that may double six
/// times. Throws InvalidInput for --initial without a law or with more than one, without
/// --t-end, for bad expressions and files, and for initial curves outside a --field-file's
/// lattice.
Problem resolve_problem(const ProblemSource& source);

}  // namespace slc::cli
