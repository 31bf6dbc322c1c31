// slc render: draws interface files in one picture, with axes and a legend of the file names.
#include "slc/io/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "commands/commands.hpp"
#include "commands/common.hpp"

namespace slc::cli {
namespace {

struct RenderOptions {
    std::vector<std::string> files;
    std::string out;
    std::string title;
    DomainOptions view;
};

/// The square around all curves with a 10% margin.
Box view_around(const std::vector<Interface>& all) {
    Box b = Box::empty();
    for (const Interface& curves : all) b = unite(b, bounding_box(curves.points()));
    return Box::square(b.center(), 0.55 * std::max(b.width(), b.height()));
}

void run_render(const RenderOptions& o) {
    std::vector<Interface> all;
    for (const std::string& file : o.files)
        all.push_back(load_interface(file, DomainOptions{}).curves);
    const bool explicit_view = o.view.half_width || o.view.box;
    const Box view = explicit_view ? resolve_domain(o.view, {}) : view_around(all);
    Figure figure(view, o.title);
    for (std::size_t i = 0; i < all.size(); ++i) {
        figure.add_curves(all[i], std::filesystem::path(o.files[i]).filename().string(),
                          palette_color(i));
    }
    figure.save(o.out);
}

}  // namespace

void add_render_command(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    auto* cmd = app.add_subcommand(
        "render", "Draws interface files as SVG or PNG (by the extension of --out)");
    cmd->add_option("files", o->files, "Interface files (JSON)")->required();
    cmd->add_option("--out", o->out, "Picture to write: .svg or .png")->required();
    cmd->add_option("--title", o->title, "Title above the picture");
    add_domain_options(*cmd, o->view);
    cmd->callback([o] { run_render(*o); });
}

}  // namespace slc::cli
