// Pieces every subcommand shares: reading and validating an interface, resolving the domain,
// threads, output folders and JSON summaries.
#pragma once

#include <CLI/CLI.hpp>
#include <chrono>
#include <ctime>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "commands/output_folder.hpp"
#include "slc/core/box.hpp"
#include "slc/core/box3.hpp"
#include "slc/core/error.hpp"
#include "slc/evolve/guards.hpp"
#include "slc/evolve/keeping_topology.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/evolve/run.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/io/interface_json.hpp"

namespace slc::cli {

/// The --domain b / --box x0,y0,x1,y1 pair of options.
struct DomainOptions {
    std::optional<double> half_width;
    std::optional<std::string> box;
};

/// Adds --domain and --box (mutually exclusive) to a subcommand; `more` ends the help of
/// --domain.
void add_domain_options(CLI::App& cmd, DomainOptions& options, std::string_view more = {});

/// The help's formatter: each option's description (and each command's in the list) wrapped at
/// spaces to lines of `help_width` characters, continuation lines under its column; a line of a
/// description keeps its own indentation (the lists of problems and laws, whose items hang). Set on
/// the app before its subcommands are added, which take it from there.
inline constexpr std::size_t help_width = 100;
std::shared_ptr<CLI::Formatter> help_formatter();

/// Adds the subcommand `name` to app and makes the options its flags fill: shared, so that its
/// callback, which runs after parsing, can hold them. Returns both.
template <class Options>
std::pair<CLI::App*, std::shared_ptr<Options>> add_command(CLI::App& app, std::string name,
                                                           std::string description) {
    return {app.add_subcommand(std::move(name), std::move(description)),
            std::make_shared<Options>()};
}

/// Adds --initial FILE (an interface file, `initial_help`) and, instead of it, `builtin` NAME (a
/// built-in shape: "--shape" or "--function", `builtin_help`), each excluding the other. Returns
/// what the command's callback calls first: it throws InvalidInput unless one of them was given.
std::function<void()> add_initial_or_builtin(CLI::App& cmd, std::string& initial,
                                             const std::string& initial_help,
                                             const std::string& builtin, std::string& name,
                                             const std::string& builtin_help);

/// The square domain: from --domain or --box, else the square centred on the curves' bounding
/// box with half-width 1.5 times its larger half-side (room for the curves to move). Throws
/// InvalidInput for a non-square box, a non-positive size or non-finite numbers.
Box resolve_domain(const DomainOptions& options, const std::vector<std::vector<slc::Vec2>>& raw);

/// An interface read from a JSON file, its domain resolved (resolve_domain) and the curves
/// validated against it. Notes of what validation changed (reoriented curves) go to stderr,
/// prefixed with the file name.
struct LoadedInterface {
    Interface curves;
    double time = 0.0;
    Box domain;
};
LoadedInterface load_interface(const std::string& path, const DomainOptions& domain);

/// The cubic domain of a surface (DESIGN §8): from --domain b ([-b, b]^3) or --box
/// x0,y0,z0,x1,y1,z1 (a box is taken as the cube around it, sharing its centre), else the cube
/// centred on the surface's bounding box with half-width 1.5 times its largest half-side.
Box3 resolve_domain3(const DomainOptions& options, const Box3& bounds);

/// A surface read from an .obj, .stl, .ply or .vdb file, validated (prepare_surface), with its
/// domain resolved; every vertex must lie in the domain. Notes of what validation changed (reversed
/// components) go to stderr, prefixed with the file name.
struct LoadedSurface {
    Surface surface;
    Box3 domain;
};
LoadedSurface load_surface(const std::string& path, const DomainOptions& domain);

/// JSON for a box: [x0, y0, x1, y1].
nlohmann::json box_json(const Box& b);

/// The numbers of a comma-separated list ("35,25"), or nothing when a field is not a number.
std::optional<std::vector<double>> comma_numbers(const std::string& text);

/// Applies --threads (set_thread_count).
void apply_threads(int threads);

/// The option --threads of a command, into `threads`.
void add_threads_option(CLI::App& cmd, int& threads);

/// The one velocity law given among options (name, given), in their order: InvalidInput with
/// `missing` when none is, or naming the first two when several are.
std::string one_velocity_law(const std::vector<std::pair<std::string, bool>>& options,
                             const std::string& missing);

/// The result of contour(), timed: its process CPU seconds and wall seconds go to summary's
/// "cpu_s" and "wall_s". When it throws NumericalFailure, summary.json in folder records status
/// "error" and the message (context followed by the failure's), the folder is committed and
/// NumericalFailure of that message is thrown.
template <class Contour>
auto timed_contour(nlohmann::json& summary, OutputFolder& folder, const std::string& context,
                   Contour contour) {
    const std::clock_t cpu_start = std::clock();
    const auto wall_start = std::chrono::steady_clock::now();
    std::optional<decltype(contour())> result;
    try {
        result = contour();
    } catch (const NumericalFailure& e) {
        const std::string message = context + e.what();
        summary["status"] = "error";
        summary["message"] = message;
        write_file_atomic(folder.path() / "summary.json", summary.dump(2) + "\n");
        folder.commit();
        throw NumericalFailure(message);
    }
    summary["cpu_s"] = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    summary["wall_s"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    return std::move(*result);
}

/// Prints summary.json's "error_estimate" in one line: the estimate, or why there is none.
void print_estimate(const nlohmann::json& estimate);

/// ", finest cell W at (x, y[, z])" from a run's summary.json (finest_cell), or nothing: for the
/// closing line of slc run.
std::string finest_cell_text(const nlohmann::json& summary);

/// Prints to stderr the notes of thin cells other than asked: the start's, r.thin_depth levels
/// where `asked` were asked (fewer where thin cells broke a sharp edge or point), and the steps'
/// that were taken again deeper (RunTotals::deeper_at); `what`: "curves" or "surface".
void note_deeper(std::string_view what, int asked, const RunTotals& r);

/// Prints to stderr the warning of a run with its guards off that broke what its law keeps
/// (RunTotals::broken), when it did.
void warn_broken(const RunTotals& r);

/// Whether a run's frames end with one more, where it stopped: when the last frame written is
/// not there (it stopped early: its components reached, vanished, unstable) and there is something
/// to show; an interrupted run leaves its frames to --resume. For curves and surfaces alike.
bool ends_frames_where_stopped(const RunTotals& r, bool empty, bool last_frame_there);

/// The rules by which slc run and slc contour choose the contour settings of a user's shape when
/// none are given, in words for their --help (with the library's numbers), so that the two
/// commands describe the same rules: K from the domain, eps from K, eta, and the thin depth.
namespace default_rule {
std::string depth();
std::string eps();
std::string eta();
std::string thin_depth();
}  // namespace default_rule

/// The note slc contour gives when the contour of a user's shape does not keep its topology: a
/// part thinner than the cells resolve (at the thin depth given) was torn or joined. Nothing when
/// it is kept.
std::optional<std::string> topology_note(const ShapeTopology& given, const ShapeTopology& contour,
                                         int dim, int thin_depth);

/// CLI11 checks with one-line messages naming the value: a positive finite number; a finite
/// number >= 0; an integer in [lo, hi]; a number in [0, 1).
CLI::Validator positive_number();
CLI::Validator nonnegative_number();
CLI::Validator integer_in(int lo, int hi);
/// The same for one of the library's ranges (setting_range).
inline CLI::Validator integer_in(IntRange r) { return integer_in(r.lo, r.hi); }
CLI::Validator fraction_below_one();

}  // namespace slc::cli
