// slc study --initial: the self-convergence study of a curve without an exact solution, written
// as table.md, table.csv, table.json, convergence.svg/.png and final_r.json for each run r.
#pragma once

#include <filesystem>

#include "slc/evolve/problems.hpp"
#include "slc/evolve/self_convergence.hpp"

namespace slc::cli {

/// Runs p's curves under law at `resolutions` resolutions of base (3..5) and writes the tables
/// and the picture to dir; progress lines on stderr unless quiet. Throws InvalidInput as
/// self_convergence() does.
void write_self_convergence_study(const Problem& p, const VelocityLaw& law, const RunOptions& base,
                                  int resolutions, bool quiet, const std::filesystem::path& dir);

}  // namespace slc::cli
