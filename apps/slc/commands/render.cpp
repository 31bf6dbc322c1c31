// slc render: draws interface files in one picture, with axes and a legend of the file names, or
// the frames of a run (slc run --frames) as an animated SVG.
#include "slc/io/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

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
    std::string frames;
    double seconds_per_frame = 0.25;
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
    if (std::filesystem::path(o.out).extension() != ".svg")
        throw InvalidInput(
            fmt::format("--frames draws an animated SVG: --out must end in .svg, got {}", o.out));
    std::vector<AnimationFrame> frames;
    Box bounds = Box::empty();
    for (const auto& file : frame_files(o.frames)) {
        const InterfaceFile raw = read_interface_json(file);
        // A run's last frame is empty when everything vanished.
        Interface curves = raw.curves.empty() ? Interface{} : prepare_interface(raw.curves).curves;
        if (!curves.empty()) bounds = unite(bounds, bounding_box(curves.points()));
        frames.push_back({raw.time, std::move(curves)});
    }
    if (bounds.is_empty()) throw InvalidInput(fmt::format("every frame in {} is empty", o.frames));
    const AnimationOptions options{o.seconds_per_frame, o.title, true};
    write_file_atomic(o.out, animated_svg(frames, view_of(o.view, bounds), options));
}

void run_render(const RenderOptions& o) {
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
        app, "render",
        "Draws interface files as SVG or PNG (by the extension of --out), or the frames of a run "
        "as an animated SVG (--frames)");
    auto* files = cmd->add_option("files", o->files,
                                  "Interface files of curves (JSON); a surface's "
                                  "pictures are drawn by slc run and slc contour (final.png)");
    cmd->add_option("--frames", o->frames,
                    "Instead of files: the frames of a run (DIR/frames/frame_*.json, from slc run "
                    "--out DIR --frames n) as an animated SVG, each frame in turn over a trail of "
                    "all of them")
        ->excludes(files);
    cmd->add_option("--seconds-per-frame", o->seconds_per_frame,
                    "With --frames: how long each frame shows (default 0.25)")
        ->check(positive_number());
    cmd->add_option("--out", o->out, "Picture to write: .svg or .png (.svg with --frames)")
        ->required();
    cmd->add_option("--title", o->title, "Title above the picture");
    add_domain_options(*cmd, o->view);
    cmd->callback([o] { run_render(*o); });
}

}  // namespace slc::cli
