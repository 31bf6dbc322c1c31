// slc distance: signed distance and nearest point of Γ for each point of a CSV file.
#include <fmt/format.h>

#include "commands/commands.hpp"
#include "commands/common.hpp"
#include "commands/memory_budget.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/io/points_csv.hpp"
#include "slc/io/surface_files.hpp"

namespace slc::cli {
namespace {

struct DistanceOptions {
    std::string initial;
    std::string points;
    DomainOptions domain;
    std::optional<int> depth;
    int threads = 0;
};

/// The 3D form (DESIGN §8): a surface file, x,y,z points.
void run_surface_distance(const DistanceOptions& o) {
    const LoadedSurface in = load_surface(o.initial, o.domain);
    const std::vector<Vec3> xs = read_points3_csv(o.points);
    const int depth = o.depth.value_or(SurfaceDistanceTree::default_depth(in.surface, in.domain));
    const SurfaceDistanceTree tree(in.surface, in.domain, {.depth = depth});
    const std::vector<SurfacePoint> answers = tree.closest_points(xs);
    std::string out = "x,y,z,distance,nearest_x,nearest_y,nearest_z\n";
    for (std::size_t i = 0; i < xs.size(); ++i) {
        const SurfacePoint& p = answers[i];
        out += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", xs[i].x,
                           xs[i].y, xs[i].z, p.distance, p.point.x, p.point.y, p.point.z);
    }
    fmt::print("{}", out);
}

void run_distance(const DistanceOptions& o) {
    apply_threads(o.threads);
    if (is_surface_file(o.initial)) {
        run_surface_distance(o);
        return;
    }
    const LoadedInterface in = load_interface(o.initial, o.domain);
    const std::vector<Vec2> xs = read_points_csv(o.points);
    const int depth = o.depth.value_or(DistanceTree::default_depth(in.curves, in.domain));
    check_tree_memory(fmt::format("--tree-depth {}", depth), depth, length(in.curves),
                      in.domain.width(), distance_bytes_per_cell);
    const DistanceTree tree(in.curves, in.domain, {.depth = depth, .triangulate = false});
    const std::vector<ClosestPoint> answers = tree.closest_points(xs);
    std::string out = "x,y,distance,nearest_x,nearest_y\n";
    for (std::size_t i = 0; i < xs.size(); ++i) {
        const ClosestPoint& p = answers[i];
        out += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", xs[i].x, xs[i].y,
                           p.distance, p.point.x, p.point.y);
    }
    fmt::print("{}", out);
}

}  // namespace

void add_distance_command(CLI::App& app) {
    const auto [cmd, o] =
        add_command<DistanceOptions>(app, "distance",
                                     "Signed distance (negative inside) and nearest point of an "
                                     "interface at the points of a CSV file");
    cmd->add_option("--initial", o->initial,
                    "Interface file (JSON), or a closed surface (.obj, .stl, .ply, .vdb): 3D")
        ->required();
    cmd->add_option("--points", o->points,
                    "Query points, one x,y (x,y,z for a surface) per line (optional header)")
        ->required();
    add_domain_options(*cmd, o->domain);
    cmd->add_option("-L,--tree-depth", o->depth,
                    "Depth L of the distance tree (default: cells about one mean segment wide)")
        ->check(integer_in(0, 30));
    add_threads_option(*cmd, o->threads);
    cmd->footer(
        "Reads x,y lines and prints x,y,distance,nearest_x,nearest_y with 17 significant digits; "
        "for a\nsurface (.obj, .stl, .ply, .vdb), x,y,z lines and "
        "x,y,z,distance,nearest_x,nearest_y,nearest_z.");
    cmd->callback([o] { run_distance(*o); });
}

}  // namespace slc::cli
