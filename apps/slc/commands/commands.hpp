// The subcommands of the slc tool. Each registers itself on the application; its callback parses
// nothing further, validates, calls the library and prints. No numerics live here.
#pragma once

#include <CLI/CLI.hpp>

namespace slc::cli {

void add_distance_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_tree_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_study_command(CLI::App& app);
void add_contour_command(CLI::App& app);

}  // namespace slc::cli
