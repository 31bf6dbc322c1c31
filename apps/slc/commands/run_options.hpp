// The method parameters shared by `slc run` and `slc study` (DESIGN §4), their resolution against
// a problem's defaults, and the summary.json of a run.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "slc/evolve/overrides.hpp"
#include "slc/evolve/problems.hpp"
#include "slc/evolve/run.hpp"
#include "slc/io/summary.hpp"

namespace slc::cli {

/// N, K, P, ε, η, ρ, M, E, S, L, the extension, the geometry module, arcs and threads; unset ones
/// take the problem's values or the defaults of DESIGN §4.
struct MethodOptions {
    std::optional<int> steps;
    std::optional<int> depth;
    std::optional<int> refine;
    std::optional<double> eps;
    std::optional<double> eta;
    std::optional<int> thin_depth;
    std::optional<double> rho;
    std::optional<int> mesh;
    std::optional<int> eno_order;
    std::optional<int> smooth;
    std::optional<int> tree_depth;
    std::optional<std::string> extension;  ///< unset: the problem's, else the law's default
    std::string geometry;                  ///< empty: the law's (or the problem's) own
    std::optional<bool> arcs;              ///< --arcs / --no-arcs; unset: as extension
    /// --area-correction / --no-area-correction; unset: on for area-keeping laws, off for named
    /// problems (StepOptions::area_correction)
    std::optional<bool> area_correction;
    std::optional<double> arc_width;
    int threads = 0;
};

void add_method_options(CLI::App& cmd, MethodOptions& options);

/// The geometry module --geometry names, if given.
std::optional<GeometryModule> geometry_module(const MethodOptions& method);

/// The settings of the command line as the library's RunOverrides (all but the geometry module
/// and threads, which the tool applies itself).
RunOverrides overrides_of(const MethodOptions& method);

/// The run's options: command line over problem defaults over DESIGN §4 defaults
/// (apply_overrides, its messages naming the flags).
RunOptions resolve_run_options(const MethodOptions& method, const Problem& problem);

/// --param key=value pairs; InvalidInput for a malformed one.
std::map<std::string, double> parse_params(const std::vector<std::string>& params);

/// Help texts listing the problems and the velocity laws with their parameters.
std::string problem_help();
std::string velocity_help();

}  // namespace slc::cli
