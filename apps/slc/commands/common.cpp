// Shared command-line pieces: interface loading, domain resolution, defaults.
#include "commands/common.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/surface_files.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc::cli {

namespace {

/// text wrapped at spaces to lines of at most `width` characters (a longer word stands alone):
/// each line of the text keeps its indentation, and the continuation lines of an indented line (an
/// item of a list) take two spaces more.
std::string wrapped(const std::string& text, std::size_t width) {
    std::string out;
    std::istringstream lines(text);
    std::string line;
    for (bool first = true; std::getline(lines, line); first = false) {
        if (!first) out += '\n';
        const std::size_t indent = line.find_first_not_of(' ');
        if (indent == std::string::npos) continue;
        std::istringstream words(line.substr(indent));
        std::string word, current(indent, ' ');
        bool empty = true;
        while (words >> word) {
            if (!empty && current.size() + 1 + word.size() > width) {
                out += current + '\n';
                current = std::string(indent == 0 ? 0 : indent + 2, ' ') + word;
            } else {
                current += (empty ? "" : " ") + word;
            }
            empty = false;
        }
        out += current;
    }
    return out;
}

class WrappingFormatter : public CLI::Formatter {
public:
    std::string make_option_desc(const CLI::Option* option) const override {
        return wrapped(CLI::Formatter::make_option_desc(option), help_width - get_column_width());
    }
    std::string make_description(const CLI::App* app) const override {
        const std::string text = CLI::Formatter::make_description(app);
        const bool ends_line = !text.empty() && text.back() == '\n';
        return wrapped(text, help_width) + (ends_line ? "\n" : "");
    }
    std::string make_subcommand(const CLI::App* sub) const override {
        std::stringstream out;
        CLI::detail::format_help(out, sub->get_display_name(),
                                 wrapped(sub->get_description(), help_width - get_column_width()),
                                 get_column_width());
        return out.str();
    }
};

}  // namespace

std::shared_ptr<CLI::Formatter> help_formatter() { return std::make_shared<WrappingFormatter>(); }

void add_domain_options(CLI::App& cmd, DomainOptions& options, std::string_view more) {
    auto* domain =
        cmd.add_option("--domain", options.half_width,
                       "Half-width b of the square domain [-b, b]^2, or cube [-b, b]^3 for a "
                       "surface (default: the square or cube around the bounding box, 1.5 "
                       "times its largest half-side)" +
                           std::string(more));
    auto* box = cmd.add_option(
        "--box", options.box,
        "The domain as x0,y0,x1,y1 (x0,y0,z0,x1,y1,z1 for a surface); a rectangle (box) is taken "
        "as the square (cube) around it, sharing its centre");
    domain->excludes(box);
}

std::function<void()> add_initial_or_builtin(CLI::App& cmd, std::string& initial,
                                             const std::string& initial_help,
                                             const std::string& builtin, std::string& name,
                                             const std::string& builtin_help) {
    auto* file = cmd.add_option("--initial", initial, initial_help);
    auto* shape = cmd.add_option(builtin, name, builtin_help);
    file->excludes(shape);
    return [file, shape, builtin] {
        if (file->count() == 0 && shape->count() == 0)
            throw InvalidInput(fmt::format("give --initial FILE or {} NAME", builtin));
    };
}

namespace {

/// The numbers of a comma-separated list, or nothing if one is not a number.
std::optional<std::vector<double>> numbers(const std::string& text) {
    std::vector<double> v;
    std::stringstream in(text);
    std::string field;
    while (std::getline(in, field, ',')) {
        try {
            std::size_t used = 0;
            v.push_back(std::stod(field, &used));
            if (used != field.size()) return std::nullopt;
        } catch (const std::exception&) {
            return std::nullopt;
        }
    }
    return v;
}

Box parse_box(const std::string& text) {
    const auto v = numbers(text);
    if (!v || v->size() != 4)
        throw InvalidInput(fmt::format("--box must be four numbers x0,y0,x1,y1, got '{}'", text));
    const Box b{{(*v)[0], (*v)[1]}, {(*v)[2], (*v)[3]}};
    if (!is_finite(b.lo) || !is_finite(b.hi) || !(b.width() > 0) || !(b.height() > 0)) {
        throw InvalidInput(
            fmt::format("--box must have x0 < x1 and y0 < y1, all finite, got '{}'", text));
    }
    if (b.largest_magnitude() > tolerance::max_coordinate) {
        throw InvalidInput(fmt::format("--box corners must lie within ±{:g}, got '{}'",
                                       tolerance::max_coordinate, text));
    }
    // The trees need a square: a rectangle becomes the square around it with the same centre.
    if (std::abs(b.width() - b.height()) > 1e-12 * std::max(b.width(), b.height()))
        return Box::square(b.center(), 0.5 * std::max(b.width(), b.height()));
    return {b.lo, {b.hi.x, b.lo.y + b.width()}};
}

/// The half-width b of --domain, checked: positive and up to the largest coordinate.
double domain_half_width(double b) {
    if (!(b > 0.0) || !(b <= tolerance::max_coordinate)) {
        throw InvalidInput(fmt::format("--domain must be a positive half-width up to {:g}, got {}",
                                       tolerance::max_coordinate, b));
    }
    return b;
}

Box3 parse_box3(const std::string& text) {
    const auto v = numbers(text);
    if (!v || v->size() != 6) {
        throw InvalidInput(fmt::format(
            "--box must be six numbers x0,y0,z0,x1,y1,z1 for a surface, got '{}'", text));
    }
    return cube_around_corners(*v, "--box");
}

}  // namespace

std::optional<std::vector<double>> comma_numbers(const std::string& text) { return numbers(text); }

Box3 resolve_domain3(const DomainOptions& options, const Box3& bounds) {
    if (options.half_width) return Box3::centered_cube(domain_half_width(*options.half_width));
    if (options.box) return parse_box3(*options.box);
    return default_domain(bounds);
}

LoadedSurface load_surface(const std::string& path, const DomainOptions& domain) {
    Surface raw = read_surface(path);
    try {
        PreparedSurface prepared = prepare_surface(std::move(raw));
        for (const std::string& note : prepared.notes)
            fmt::print(stderr, "slc: {}: {}\n", path, note);
        const Box3 bounds = bounding_box(prepared.surface);
        const Box3 box = resolve_domain3(domain, bounds);
        if (!box.contains(bounds)) {
            const auto& vs = prepared.surface.vertices;
            std::size_t v = 0;
            while (v < vs.size() && box.contains(vs[v])) ++v;
            throw InvalidInput(fmt::format(
                "vertex {} ({}, {}, {}) lies outside the domain [{}, {}]x[{}, {}]x[{}, {}]", v,
                vs[v].x, vs[v].y, vs[v].z, box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z,
                box.hi.z));
        }
        return {std::move(prepared.surface), box};
    } catch (const InvalidInput& e) {
        if (domain.half_width || domain.box) {
            // The options' own problems name the option, not the file.
            const std::string what = e.what();
            if (what.starts_with("--")) throw;
        }
        throw InvalidInput(fmt::format("{}: {}", path, e.what()));
    }
}

Box resolve_domain(const DomainOptions& options, const std::vector<std::vector<Vec2>>& raw) {
    if (options.half_width) return Box::centered_square(domain_half_width(*options.half_width));
    if (options.box) return parse_box(*options.box);
    return default_domain(raw);
}

LoadedInterface load_interface(const std::string& path, const DomainOptions& domain) {
    InterfaceFile file = read_interface_json(path);
    // A domain given by --domain or --box is the options' own problem; the rest, which comes from
    // the curves, names the file, as the reader's problems do.
    const std::optional<Box> given =
        domain.half_width || domain.box ? std::optional(resolve_domain(domain, {})) : std::nullopt;
    try {
        const Box box = given ? *given : resolve_domain(domain, file.curves);
        PreparedInterface prepared = prepare_interface(file.curves, box);
        for (const std::string& note : prepared.notes)
            fmt::print(stderr, "slc: {}: {}\n", path, note);
        return {std::move(prepared.curves), file.time, box};
    } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("{}: {}", path, e.what()));
    }
}

nlohmann::json box_json(const Box& b) { return {b.lo.x, b.lo.y, b.hi.x, b.hi.y}; }

void apply_threads(int threads) { set_thread_count(threads); }

void add_threads_option(CLI::App& cmd, int& threads) {
    cmd.add_option("--threads", threads,
                   "Worker threads: 0, the default, takes OMP_NUM_THREADS when it is set, else "
                   "every core this process may use; a larger count runs on those cores; "
                   "results do not depend on it")
        ->check(integer_in(0, 1024));
}

namespace {

/// The whole of text as a number, or nothing.
std::optional<double> number(const std::string& text) {
    try {
        std::size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size()) return v;
    } catch (const std::exception&) {
    }
    return std::nullopt;
}

}  // namespace

namespace default_rule {

std::string depth() {
    return fmt::format(
        "{}, a level deeper for each doubling of --domain or --box beyond the default domain",
        default_depth);
}

std::string eps() {
    return fmt::format(
        "the shape's half-width times 10^-K for curves (not below {:g}) and {:g} 4^({}-K) for "
        "surfaces; at least two ulps of the domain's largest coordinate",
        min_curve_eps, eps_for_depth(3, default_depth, 1.0), default_depth);
}

std::string eta() {
    return fmt::format(
        "{:g} times the shape's half-width; for curves lowered to eps/10 when eps is below it, for "
        "a refined surface raised to eps/100; at least two ulps of the domain's largest "
        "coordinate, below which doubles cannot place a root",
        ContourOptions::default_eta);
}

std::string thin_depth() {
    return fmt::format("{} for curves, {} for a surface", default_thin_depth(2),
                       default_thin_depth(3));
}

}  // namespace default_rule

CLI::Validator positive_number() {
    return CLI::Validator(
        [](std::string& text) {
            const auto v = number(text);
            if (v && *v > 0.0 && std::isfinite(*v)) return std::string();
            return fmt::format("must be a positive finite number, got '{}'", text);
        },
        "POSITIVE");
}

CLI::Validator nonnegative_number() {
    return CLI::Validator(
        [](std::string& text) {
            const auto v = number(text);
            if (v && *v >= 0.0 && std::isfinite(*v)) return std::string();
            return fmt::format("must be a finite number >= 0, got '{}'", text);
        },
        "NONNEGATIVE");
}

CLI::Validator integer_in(int lo, int hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) {
            const auto v = number(text);
            if (v && *v >= lo && *v <= hi && *v == std::floor(*v)) return std::string();
            return fmt::format("must be an integer from {} to {}, got '{}'", lo, hi, text);
        },
        fmt::format("in [{}, {}]", lo, hi));
}

CLI::Validator fraction_below_one() {
    return CLI::Validator(
        [](std::string& text) {
            const auto v = number(text);
            if (v && *v >= 0.0 && *v < 1.0) return std::string();
            return fmt::format("must be a number in [0, 1), got '{}'", text);
        },
        "in [0, 1)");
}

std::string one_velocity_law(const std::vector<std::pair<std::string, bool>>& options,
                             const std::string& missing) {
    std::vector<std::string> given, all;
    for (const auto& [name, is_given] : options) {
        all.push_back(name);
        if (is_given) given.push_back(name);
    }
    if (given.empty()) throw InvalidInput(missing);
    if (given.size() > 1) {
        const std::string last = all.back();
        all.pop_back();
        throw InvalidInput(fmt::format("give one velocity law of {} and {}, got {} and {}",
                                       fmt::join(all, ", "), last, given[0], given[1]));
    }
    return given[0];
}

std::string finest_cell_text(const nlohmann::json& summary) {
    if (!summary.contains("finest_cell")) return {};
    const nlohmann::json& f = summary["finest_cell"];
    std::string at;
    for (const auto& x : f["at"])
        at += fmt::format("{}{:.4g}", at.empty() ? "" : ", ", x.get<double>());
    return fmt::format(", finest cell {:.3g} at ({})", f["width"].get<double>(), at);
}

void warn_broken(const RunTotals& r) {
    if (!r.broken.empty()) fmt::print(stderr, "slc: warning: --no-guards: {}\n", r.broken);
}

bool ends_frames_where_stopped(const RunTotals& r, bool empty, bool last_frame_there) {
    return !last_frame_there && !empty && r.status != RunStatus::interrupted;
}

void note_deeper(std::string_view what, int asked, const RunTotals& r) {
    if (r.thin_depth >= 0) {
        if (const auto kept = thin_depth_note(what, asked, r.thin_depth, "--thin-depth"))
            fmt::print(stderr, "slc: note: {} (summary.json: thin_depth)\n", *kept);
    }
    if (!std::isnan(r.deeper_at)) {
        fmt::print(
            stderr,
            "slc: note: {}: a part thinner than the contours resolved, kept by deeper thin "
            "cells, up to {} levels deep, in {} of the run's steps (summary.json: thin_deeper)\n",
            r.deeper_why, r.deepest_thin_depth, r.deeper_steps);
    }
    if (!std::isnan(r.shallower_at)) {
        fmt::print(stderr,
                   "slc: note: {}: deeper thin cells made holes or handles that neither the "
                   "step's start nor shallower cells had (as where parts meet), and {} {} kept "
                   "the shallower cells that made none, down to {} (summary.json: "
                   "thin_shallower)\n",
                   r.shallower_why, r.shallower_substeps,
                   r.shallower_substeps == 1 ? "sub-step" : "sub-steps",
                   r.shallowest_thin_depth == 1
                       ? std::string("1 level")
                       : fmt::format("{} levels", r.shallowest_thin_depth));
    }
}

void print_estimate(const nlohmann::json& estimate) {
    if (estimate["estimate"].is_null()) {
        fmt::print("{}\n", estimate["note"].get<std::string>());
    } else {
        fmt::print("error estimate: {:.3g} (the distance to the run {} at half resolution)\n",
                   estimate["estimate"].get<double>(), estimate["coarse"].get<std::string>());
    }
}

std::optional<std::string> topology_note(const ShapeTopology& given, const ShapeTopology& contour,
                                         int dim, int thin_depth) {
    return lost_topology_note(given, contour, dim,
                              fmt::format("raise --thin-depth (now {}) or -K", thin_depth));
}

}  // namespace slc::cli
