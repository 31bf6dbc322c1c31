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

/// The method options of the command line: the library's settings (RunOverrides) that the flags
/// set, and what the tool applies itself; unset ones take the problem's values or the defaults of
/// DESIGN §4 (apply_overrides).
struct MethodOptions {
    /// -N, -K, -P, --eps, --eta, -L, --rho, --mesh, --eno-order, -S, --arcs, --arc-width,
    /// --thin-depth and --area-correction as given.
    RunOverrides settings;
    std::optional<std::string> extension;  ///< --extension by name: settings.extension from it
    std::string geometry;                  ///< empty: the law's (or the problem's) own
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
