// slc render: draws interface files in one picture, with axes and a legend of the file names, or
// the frames of a run (slc run --frames) as an animated SVG.
#include "slc/io/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "commands/commands.hpp"
#include "commands/common.hpp"
#include "slc/core/error.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/animation.hpp"
#include "slc/io/interface_json.hpp"

namespace slc::cli {
namespace {

struct RenderOptions {
    std::vector<std::string> files;
    std::vector<std::string> frames;
    double seconds_per_frame = 0.25;
    int columns = 0;
    std::vector<double> times;
    bool by_run = false;
    std::string out;
    std::string title;
    DomainOptions view;
};

/// The view the options give, else the square around `bounds` (the curves') with a 10% margin.
Box view_of(const DomainOptions& given, Box bounds) {
    if (given.half_width || given.box) return resolve_domain(given, {});
    return Box::square(bounds.center(), 0.55 * std::max(bounds.width(), bounds.height()));
}

/// The frame files of a run folder, in order: DIR/frames/frame_*.json, or DIR/frame_*.json.
std::vector<std::filesystem::path> frame_files(const std::filesystem::path& dir) {
    namespace fs = std::filesystem;
    const fs::path folder = fs::is_directory(dir / "frames") ? dir / "frames" : dir;
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with("frame_") && entry.path().extension() == ".json")
            files.push_back(entry.path());
    }
    if (ec) throw InvalidInput(fmt::format("cannot read {}: {}", folder.string(), ec.message()));
    if (files.empty()) {
        throw InvalidInput(fmt::format(
            "no frames in {}: want frames/frame_NNNN.json, as slc run --frames n writes",
            dir.string()));
    }
    std::sort(files.begin(), files.end());
    return files;
}

void render_animation(const RenderOptions& o) {
    if (o.frames.size() != 1)
        throw InvalidInput(
            "an animation draws one run's frames: give --columns to set runs side by side");
    if (std::filesystem::path(o.out).extension() != ".svg")
        throw InvalidInput(
            fmt::format("--frames draws an animated SVG: --out must end in .svg, got {}", o.out));
    std::vector<AnimationFrame> frames;
    Box bounds = Box::empty();
    for (const auto& file : frame_files(o.frames[0])) {
        const InterfaceFile raw = read_interface_json(file);
        // A run's last frame is empty when everything vanished.
        Interface curves = raw.curves.empty() ? Interface{} : prepare_interface(raw.curves).curves;
        if (!curves.empty()) bounds = unite(bounds, bounding_box(curves.points()));
        frames.push_back({raw.time, std::move(curves)});
    }
    if (bounds.is_empty())
        throw InvalidInput(fmt::format("every frame in {} is empty", o.frames[0]));
    const AnimationOptions options{o.seconds_per_frame, o.title, true};
    write_file_atomic(o.out, animated_svg(frames, view_of(o.view, bounds), options));
}

/// A run folder without a trailing separator ("out/a/" is out/a).
std::filesystem::path run_folder(const std::string& dir) {
    const std::filesystem::path p(dir);
    return p.filename().empty() ? p.parent_path() : p;
}

/// A run folder's name for a panel: its summary.json's "run" (N/S/K/P/eps) when it has one,
/// else the folder's name.
std::string run_title(const std::string& dir) {
    const std::filesystem::path folder = run_folder(dir);
    std::ifstream in(folder / "summary.json");
    if (in) {
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        if (j.is_object() && j.contains("run") && j["run"].is_string())
            return j["run"].get<std::string>();
    }
    return folder.filename().string();
}

/// One panel of a grid: its title and its interfaces, each with a legend label (or none).
struct Panel {
    std::string title;
    std::vector<std::pair<std::string, Interface>> layers;
};

/// The frame of a run nearest each of `times`; every frame when none is given.
std::vector<std::filesystem::path> frames_at(const std::string& dir,
                                             const std::vector<double>& times) {
    const auto files = frame_files(dir);
    if (times.empty()) return files;
    std::vector<double> at;
    for (const auto& file : files) at.push_back(read_interface_json(file).time);
    std::vector<std::filesystem::path> out;
    for (double t : times) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < at.size(); ++i)
            if (std::abs(at[i] - t) < std::abs(at[best] - t)) best = i;
        out.push_back(files[best]);
    }
    return out;
}

/// Each file in a panel of its own; or a panel a time, holding each run's frame nearest it (the
/// runs overlaid, named in a legend when there are several), `columns` to a row.
void render_grid(const RenderOptions& o) {
    std::vector<Panel> panels;
    Box bounds = Box::empty();
    const auto read = [&bounds](const std::filesystem::path& file) {
        InterfaceFile raw = read_interface_json(file);
        Interface curves = raw.curves.empty() ? Interface{} : prepare_interface(raw.curves).curves;
        if (!curves.empty()) bounds = unite(bounds, bounding_box(curves.points()));
        return std::pair{raw.time, std::move(curves)};
    };
    if (o.frames.empty()) {
        for (const std::string& f : o.files)
            panels.push_back(
                {std::filesystem::path(f).filename().string(), {{"", read(f).second}}});
    } else if (o.by_run) {
        for (const std::string& dir : o.frames) {
            Panel panel{run_title(dir), {}};
            for (const auto& file : frames_at(dir, o.times))
                panel.layers.emplace_back("", read(file).second);
            panels.push_back(std::move(panel));
        }
    } else {
        // Without --times, the first run's frames set the panels; the others' nearest join them.
        std::vector<std::vector<std::filesystem::path>> runs{frames_at(o.frames[0], o.times)};
        std::vector<double> times = o.times;
        if (times.empty())
            for (const auto& file : runs[0]) times.push_back(read_interface_json(file).time);
        for (std::size_t r = 1; r < o.frames.size(); ++r)
            runs.push_back(frames_at(o.frames[r], times));
        for (std::size_t i = 0; i < times.size(); ++i) {
            Panel panel;
            for (std::size_t r = 0; r < runs.size(); ++r) {
                auto [t, curves] = read(runs[r][i]);
                if (r == 0) panel.title = fmt::format("t = {:.4g}", t);
                const std::string label =
                    runs.size() > 1 ? run_folder(o.frames[r]).filename().string() : "";
                panel.layers.emplace_back(label, std::move(curves));
            }
            panels.push_back(std::move(panel));
        }
    }
    if (panels.size() > 64)
        throw InvalidInput(
            fmt::format("{} panels are too many for one picture (at most 64): "
                        "choose frames with --times",
                        panels.size()));
    if (bounds.is_empty()) throw InvalidInput("every interface to draw is empty");
    const Box view = view_of(o.view, bounds);
    std::vector<Figure> figures;
    for (const Panel& panel : panels) {
        Figure& figure = figures.emplace_back(
            view, o.title.empty() ? panel.title : fmt::format("{}: {}", o.title, panel.title));
        // The runs' legend on the first panel only: the colours are the same in every one. A
        // run's frames (--by-run) in time's colours.
        const double last = std::max<double>(1.0, static_cast<double>(panel.layers.size()) - 1.0);
        for (std::size_t r = 0; r < panel.layers.size(); ++r)
            figure.add_curves(
                panel.layers[r].second, figures.size() == 1 ? panel.layers[r].first : "",
                o.by_run ? sequence_color(static_cast<double>(r) / last) : palette_color(r));
    }
    Figure::save_grid(figures, o.columns, o.out);
}

void run_render(const RenderOptions& o) {
    if (!o.times.empty() && (o.frames.empty() || o.columns == 0))
        throw InvalidInput("--times picks frames for panels: give it with --frames and --columns");
    if (o.by_run && (o.frames.empty() || o.columns == 0))
        throw InvalidInput("--by-run draws runs in panels: give it with --frames and --columns");
    if (o.columns > 0) {
        if (o.frames.empty() && o.files.empty())
            throw InvalidInput("give interface files to draw, or --frames DIR");
        render_grid(o);
        return;
    }
    if (!o.frames.empty()) {
        render_animation(o);
        return;
    }
    if (o.files.empty()) throw InvalidInput("give interface files to draw, or --frames DIR");
    std::vector<Interface> all;
    Box bounds = Box::empty();
    for (const std::string& file : o.files) {
        all.push_back(load_interface(file, DomainOptions{}).curves);
        bounds = unite(bounds, bounding_box(all.back().points()));
    }
    Figure figure(view_of(o.view, bounds), o.title);
    for (std::size_t i = 0; i < all.size(); ++i) {
        figure.add_curves(all[i], std::filesystem::path(o.files[i]).filename().string(),
                          palette_color(i));
    }
    figure.save(o.out);
}

}  // namespace

void add_render_command(CLI::App& app) {
    const auto [cmd, o] = add_command<RenderOptions>(
        app, "render", "Draws interface files, or the frames of a run, as SVG or PNG");
    auto* files = cmd->add_option("files", o->files,
                                  "Interface files of curves (JSON); a surface's "
                                  "pictures are drawn by slc run and slc contour (final.png)");
    cmd->add_option("--frames", o->frames,
                    "Instead of files: the frames of a run (DIR/frames/frame_*.json, from slc run "
                    "--out DIR --frames n) as an animated SVG, each frame in turn over a trail of "
                    "all of them; with --columns, panels of one or more runs (overlaid)")
        ->excludes(files);
    cmd->add_option("--seconds-per-frame", o->seconds_per_frame,
                    "With --frames: how long each frame shows (default 0.25)")
        ->check(positive_number());
    cmd->add_option("--columns", o->columns,
                    "Draw each file, or each frame of --frames, in a panel of its own (the same "
                    "view, titled by its file name or the frame's time), this many panels to a "
                    "row: a time sequence as SVG or PNG, at most 64 panels")
        ->check(CLI::Range(1, 64));
    cmd->add_option("--times", o->times,
                    "With --frames and --columns: the panels are the frames nearest these times "
                    "(comma-separated), in this order")
        ->delimiter(',');
    cmd->add_flag("--by-run", o->by_run,
                  "With --frames and --columns: a panel a run, its frames overlaid (all, or "
                  "those nearest --times), titled by the run's N/S/K/P/eps");
    cmd->add_option("--out", o->out,
                    "Picture to write: .svg or .png (.svg with --frames, unless --columns)")
        ->required();
    cmd->add_option("--title", o->title, "Title above the picture");
    add_domain_options(*cmd, o->view);
    cmd->footer(
        "The extension of --out chooses SVG or PNG. Files are overlaid, or in panels with "
        "--columns; a\nrun's frames make an animated SVG (--frames) or panels (--frames --columns, "
        "--times).");
    cmd->callback([o] { run_render(*o); });
}

}  // namespace slc::cli
