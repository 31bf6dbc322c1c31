// slc: the command-line tool. Bad input exits with status 2, a numerical failure (or out of memory,
// or an internal error) with status 3, a run stopped by SIGINT or SIGTERM with 130 or 143, each
// with one line on stderr.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <string>

#include "commands/commands.hpp"
#include "commands/common.hpp"
#include "slc/core/error.hpp"
#include "slc/core/memory.hpp"
#include "slc/core/stop.hpp"

namespace {

/// The first line of a message, so that the tool always prints one line.
std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

int main(int argc, char** argv) {
    slc::keep_freed_memory();  // runs and studies free and allocate the same arrays every step
    CLI::App app{"slc: moving interfaces by semi-Lagrangian contouring (J. Strain, JCP 2001)"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "slc 0.1.0");
    app.formatter(slc::cli::help_formatter());
    slc::cli::add_run_command(app);
    slc::cli::add_study_command(app);
    slc::cli::add_contour_command(app);
    slc::cli::add_distance_command(app);
    slc::cli::add_render_command(app);
    slc::cli::add_tree_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // Help and version are "errors" with exit code 0; a real parse error exits 2.
        if (e.get_exit_code() == 0) return app.exit(e);
        fmt::print(stderr, "slc: {}\n", e.what());
        return 2;
    } catch (const slc::cli::Interrupted& e) {
        fmt::print(stderr, "slc: {}\n", e.what());
        return e.status();
    } catch (const slc::StopRequested&) {
        // A stop that no command turned into its own message (none should): as Ctrl-C.
        fmt::print(stderr, "slc: interrupted\n");
        return 130;
    } catch (const slc::InvalidInput& e) {
        fmt::print(stderr, "slc: {}\n", e.what());
        return 2;
    } catch (const slc::NumericalFailure& e) {
        fmt::print(stderr, "slc: error: {}\n", e.what());
        return 3;
    } catch (const std::bad_alloc&) {
        fmt::print(stderr,
                   "slc: error: out of memory: lower -K, -L or the number of points, raise "
                   "--eps, or run on a larger machine\n");
        return 3;
    } catch (const std::filesystem::filesystem_error& e) {
        // A path the user gave that cannot be read or written: bad input.
        fmt::print(stderr, "slc: {}: {}\n", e.path1().string(), e.code().message());
        return 2;
    } catch (const std::exception& e) {
        // A broken invariant: one line, and the status of a numerical failure, never a crash.
        fmt::print(stderr, "slc: error: {} (please report it)\n", first_line(e.what()));
        return 3;
    } catch (...) {
        fmt::print(stderr, "slc: error: an unknown internal error (please report it)\n");
        return 3;
    }
    return 0;
}
