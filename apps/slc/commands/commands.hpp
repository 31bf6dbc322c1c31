// The subcommands of the slc tool. Each registers itself on the application; its callback parses
// nothing further, validates, calls the library and prints. No numerics live here.
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

namespace slc::cli {

/// A command stopped by a signal after writing its results: main prints the message and exits
/// with 128 + the signal's number (130 for SIGINT, 143 for SIGTERM), as a shell reports it.
class Interrupted : public std::runtime_error {
public:
    Interrupted(int signal, const std::string& what) : std::runtime_error(what), signal_(signal) {}
    /// The exit status.
    int status() const { return 128 + signal_; }

private:
    int signal_;
};

void add_distance_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_tree_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_study_command(CLI::App& app);
void add_contour_command(CLI::App& app);

}  // namespace slc::cli
