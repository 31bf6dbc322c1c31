// slc study --initial: the self-convergence study of a curve or a surface without an exact
// solution, written as table.md, table.csv, table.json, convergence.svg/.png and final_r.json
// (final_r.obj for a surface) for each run r.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "slc/evolve/problems.hpp"
#include "slc/evolve/self_convergence.hpp"
#include "slc/evolve/surface_study.hpp"

namespace slc::cli {

/// Runs p's curves under law at `resolutions` resolutions of base (3..5) and writes the tables
/// and the picture to dir; progress lines on stderr unless quiet. Throws InvalidInput as
/// self_convergence() does.
void write_self_convergence_study(const Problem& p, const VelocityLaw& law, const RunOptions& base,
                                  int resolutions, bool quiet, const std::filesystem::path& dir);

/// A surface's law as the command line gave it, for the tables: a built-in law's name, or
/// "speed" or "field" with the expression; --param's values.
struct SurfaceLawText {
    std::string name;
    std::string expression;
    std::map<std::string, double> params;
};

/// Runs p's surface (as given, each run contouring it as the steps read it) under p's law at
/// `resolutions` resolutions of base (3..5) and writes the tables, the picture and each run's
/// final surface to dir; progress lines on stderr unless quiet. Throws as
/// surface_self_convergence() does.
void write_surface_self_convergence_study(const SurfaceProblem& p, const SurfaceLawText& law,
                                          const SurfaceRunOptions& base, int resolutions,
                                          bool quiet, const std::filesystem::path& dir);

}  // namespace slc::cli
