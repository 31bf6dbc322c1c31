// slc tree: builds the distance tree of an interface, checks it against brute force, and draws
// the tree, the signed distance and the velocity extensions (the paper's Figs. 2 and 3).
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <random>

#include "commands/commands.hpp"
#include "commands/common.hpp"
#include "slc/distance/extension.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/render.hpp"
#include "slc/io/surface_files.hpp"
#include "slc/io/vtk.hpp"

namespace slc::cli {
namespace {

struct TreeOptions {
    std::string initial;
    std::string shape;
    DomainOptions domain;
    std::optional<int> depth;
    std::optional<double> slice;
    std::string out;
    int threads = 0;
};

/// Built-in shapes by name, in the domain [−1, 1]².
std::vector<std::vector<Vec2>> builtin_shape(const std::string& name) {
    if (name == "propeller") return {shapes::propeller(256)};
    if (name == "circle") return {shapes::circle({0, 0}, 0.6, 128)};
    if (name == "two-circles")
        return {shapes::circle({-0.35, 0}, 0.3, 96), shapes::circle({0.35, 0}, 0.3, 96)};
    throw InvalidInput(
        fmt::format("unknown shape '{}'; known: propeller, circle, two-circles", name));
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Centres of an n × n grid over box.
std::vector<Vec2> grid_points(const Box& box, int n) {
    std::vector<Vec2> xs;
    xs.reserve(static_cast<std::size_t>(n) * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            xs.push_back(
                {box.lo.x + (i + 0.5) * box.width() / n, box.lo.y + (j + 0.5) * box.height() / n});
    return xs;
}

/// The largest difference between tree and brute-force signed distances at random points.
nlohmann::json brute_force_check(const DistanceTree& tree, const Box& domain) {
    std::mt19937 rng(2001);
    std::uniform_real_distribution<double> ux(domain.lo.x, domain.hi.x),
        uy(domain.lo.y, domain.hi.y);
    std::vector<Vec2> xs(2000);
    for (Vec2& x : xs) x = {ux(rng), uy(rng)};
    const auto fast = tree.signed_distances(xs);
    double worst = 0.0;
    for (std::size_t i = 0; i < xs.size(); ++i)
        worst = std::max(
            worst, std::abs(fast[i] - closest_point_brute_force(tree.curves(), xs[i]).distance));
    return {{"points", xs.size()}, {"seed", 2001}, {"max_abs_difference", worst}};
}

void draw_pictures(const DistanceTree& tree, const Box& domain, const std::filesystem::path& dir) {
    const Interface& curves = tree.curves();
    const int n = 320;
    const std::vector<Vec2> xs = grid_points(domain, n);
    // The rotation velocity u = (−y, x) at the vertices, extended off Γ (paper Fig. 3 shows its
    // x-component).
    std::vector<double> ux(curves.size());
    for (std::size_t i = 0; i < curves.size(); ++i) ux[i] = -curves.point(i).y;
    const std::vector<std::pair<std::string, std::vector<double>>> fields = {
        {"distance", tree.signed_distances(xs)},
        {"extension", nearest_point_extension<double>(tree, ux, xs)},
        {"whitney", WhitneyExtension<double>(tree, ux)(xs)}};
    const std::map<std::string, std::string> titles = {
        {"distance", "Signed distance F"},
        {"extension", "Nearest-point extension W_x of u_x = -y"},
        {"whitney", "Whitney extension W_x of u_x = -y"}};
    std::vector<Box> cells;
    for (std::uint32_t c : tree.tree().leaves()) cells.push_back(tree.tree().box(c));
    const auto save = [&dir](const Figure& figure, const std::string& name) {
        figure.save(dir / (name + ".svg"));
        figure.save(dir / (name + ".png"));
    };
    std::vector<Figure> panels;  // the paper's Fig. 3: the tree, V_x on Γ, and W_x
    Figure figure(domain, fmt::format("Distance tree, depth {}, and its triangulation",
                                      tree.tree().max_depth()));
    figure.add_triangles(tree.triangulation().vertices, tree.triangulation().triangles,
                         Color{0.55, 0.65, 0.85, 1});
    figure.add_boxes(cells, Color{0, 0, 0, 1});
    figure.add_curves(curves, "interface", palette_color(1));
    save(figure, "tree");
    panels.push_back(figure);
    Figure velocity(domain, "Interfacial velocity V_x = -y on the interface");
    velocity.add_curve_values(curves, ux, "V_x");
    save(velocity, "velocity");
    panels.push_back(velocity);
    for (const auto& [name, values] : fields) {
        Figure field(domain, titles.at(name));
        field.add_field(ScalarGrid{domain, n, n, values}, name == "distance" ? "F" : "W_x",
                        name == "distance");
        field.add_boxes(cells, Color{0, 0, 0, 0.25});
        field.add_curves(curves, "interface", Color{0, 0, 0, 1});
        save(field, name);
        if (name == "extension") panels.push_back(field);
    }
    Figure::save_grid(panels, 3, dir / "panels.png");
}

/// The pieces of the surface's triangles in the plane z = z0, as two-point polylines in x, y.
std::vector<std::array<Vec2, 2>> cross_section(const Surface& s, double z0) {
    std::vector<std::array<Vec2, 2>> out;
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        std::vector<Vec2> ends;
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = tri[k], b = tri[(k + 1) % 3];
            // Half-open in z, so that a corner on the plane counts for one edge of each pair.
            if ((a.z <= z0) == (b.z <= z0)) continue;
            const double u = (z0 - a.z) / (b.z - a.z);
            ends.push_back({a.x + u * (b.x - a.x), a.y + u * (b.y - a.y)});
        }
        if (ends.size() == 2) out.push_back({ends[0], ends[1]});
    }
    return out;
}

/// slc tree on a surface (DESIGN §8): the octree, checked against brute force, drawn in the
/// slice z = const through it.
void run_surface_tree(const TreeOptions& o) {
    const LoadedSurface in = load_surface(o.initial, o.domain);
    const Box3& domain = in.domain;
    const double z0 = o.slice.value_or(domain.center().z);
    if (!(z0 >= domain.lo.z && z0 <= domain.hi.z)) {
        throw InvalidInput(fmt::format("--slice must lie in the domain's z range [{}, {}], got {}",
                                       domain.lo.z, domain.hi.z, z0));
    }
    const int depth = o.depth.value_or(SurfaceDistanceTree::default_depth(in.surface, domain));
    auto start = std::chrono::steady_clock::now();
    const SurfaceDistanceTree tree(in.surface, domain, {.depth = depth});
    const double build_s = seconds_since(start);

    // Brute-force check at random points of the domain.
    std::mt19937 rng(2001);
    std::uniform_real_distribution<double> ux(domain.lo.x, domain.hi.x),
        uy(domain.lo.y, domain.hi.y), uz(domain.lo.z, domain.hi.z);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 x{ux(rng), uy(rng), uz(rng)};
        worst = std::max(
            worst, std::abs(tree.closest_point(x).distance -
                            closest_point_brute_force(in.surface, tree.normals(), x).distance));
    }
    // The slice: leaves cut by the plane, the signed distance on it, the surface's section.
    const Box view{{domain.lo.x, domain.lo.y}, {domain.hi.x, domain.hi.y}};
    std::vector<Box> cells;
    for (std::uint32_t c : tree.tree().leaves()) {
        const Box3 b = tree.tree().box(c);
        if (b.lo.z <= z0 && z0 < b.hi.z) cells.push_back({{b.lo.x, b.lo.y}, {b.hi.x, b.hi.y}});
    }
    const int n = 320;
    std::vector<Vec3> xs;
    for (const Vec2 p : grid_points(view, n)) xs.push_back({p.x, p.y, z0});
    const auto section = cross_section(in.surface, z0);
    const std::filesystem::path dir(o.out);
    for (const bool field : {false, true}) {
        Figure figure(view, field ? fmt::format("Signed distance F in the slice z = {:g}", z0)
                                  : fmt::format("Octree, depth {}, in the slice z = {:g}",
                                                tree.tree().max_depth(), z0));
        if (field) figure.add_field(ScalarGrid{view, n, n, tree.signed_distances(xs)}, "F", true);
        figure.add_boxes(cells, Color{0, 0, 0, field ? 0.25 : 1.0});
        for (const auto& piece : section) figure.add_polyline(piece, "", palette_color(1));
        const std::string name = field ? "distance" : "tree";
        figure.save(dir / (name + ".svg"));
        figure.save(dir / (name + ".png"));
    }
    const Surface& s = in.surface;
    const nlohmann::json summary = {
        {"command", "tree"},
        {"status", "ok"},
        {"input", o.initial},
        {"domain", {domain.lo.x, domain.lo.y, domain.lo.z, domain.hi.x, domain.hi.y, domain.hi.z}},
        {"tree_depth", depth},
        {"slice_z", z0},
        {"triangles", s.size()},
        {"components", component_count(s)},
        {"genus", genus(s)},
        {"area", area(s)},
        {"volume", volume(s)},
        {"cells", tree.tree().size()},
        {"leaves", tree.tree().leaves().size()},
        {"build_s", build_s},
        {"brute_force_check", {{"points", 2000}, {"seed", 2001}, {"max_abs_difference", worst}}}};
    write_file_atomic(dir / "surface.vtp", vtp_text(s, 0.0));
    write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    fmt::print("{} cells, {} triangles, built in {:.3g} s; wrote {}\n", tree.tree().size(),
               s.size(), build_s, (dir / "summary.json").string());
}

void run_tree(const TreeOptions& o) {
    apply_threads(o.threads);
    if (!o.initial.empty() && is_surface_file(o.initial)) {
        run_surface_tree(o);
        return;
    }
    Interface curves;
    Box domain;
    if (!o.initial.empty()) {
        LoadedInterface in = load_interface(o.initial, o.domain);
        curves = std::move(in.curves);
        domain = in.domain;
    } else {
        const auto raw = builtin_shape(o.shape);
        domain = o.domain.half_width || o.domain.box ? resolve_domain(o.domain, raw)
                                                     : Box::centered_square(1.0);
        curves = prepare_interface(raw, domain).curves;
    }
    const int depth = o.depth.value_or(6);
    const std::filesystem::path dir(o.out);

    auto start = std::chrono::steady_clock::now();
    const DistanceTree tree(curves, domain, {.depth = depth, .triangulate = true});
    const double build_s = seconds_since(start);

    nlohmann::json summary = {{"command", "tree"},
                              {"status", "ok"},
                              {"input", o.initial.empty() ? o.shape : o.initial},
                              {"domain", box_json(domain)},
                              {"tree_depth", depth},
                              {"curves", curves.curve_count()},
                              {"segments", curves.size()},
                              {"area", area(curves)},
                              {"length", length(curves)},
                              {"cells", tree.tree().size()},
                              {"leaves", tree.tree().leaves().size()},
                              {"triangles", tree.triangulation().triangles.size()},
                              {"triangulation_vertices", tree.triangulation().vertices.size()},
                              {"build_s", build_s},
                              {"brute_force_check", brute_force_check(tree, domain)}};
    write_file_atomic(dir / "interface.json", interface_json(curves, 0.0));
    draw_pictures(tree, domain, dir);
    write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    fmt::print("{} cells, {} segments, built in {:.3g} s; wrote {}\n", tree.tree().size(),
               curves.size(), build_s, (dir / "summary.json").string());
}

}  // namespace

void add_tree_command(CLI::App& app) {
    const auto [cmd, o] = add_command<TreeOptions>(
        app, "tree",
        "Builds the distance tree of an interface, checks it against brute force and draws it");
    const auto require_source = add_initial_or_builtin(
        *cmd, o->initial,
        "Interface file (JSON), or a closed surface (.obj, .stl, .ply, .vdb): the octree is drawn "
        "in "
        "a slice z = const",
        "--shape", o->shape, "A built-in shape in [-1, 1]^2: propeller, circle, two-circles");
    add_domain_options(*cmd, o->domain);
    cmd->add_option("-L,--tree-depth", o->depth,
                    "Depth L of the distance tree (default 6; for a surface, cells about one mean "
                    "edge wide)")
        ->check(integer_in(0, 16));
    cmd->add_option("--slice", o->slice,
                    "For a surface: the height z of the slice drawn (default: the domain's "
                    "middle)");
    cmd->add_option("--out", o->out,
                    "Output folder: summary.json, interface.json, "
                    "tree/velocity/distance/extension/whitney .svg and .png, panels.png")
        ->required();
    add_threads_option(*cmd, o->threads);
    cmd->footer(
        "For curves, the pictures: the tree, the x-component of u = (-y, x) on the curves, the\n"
        "signed distance, and u_x's nearest-point and Whitney extensions; panels.png sets the\n"
        "tree, u_x and its nearest-point extension side by side, as the paper's Fig. 3.");
    cmd->callback([o, require_source] {
        require_source();
        run_tree(*o);
    });
}

}  // namespace slc::cli
