// slc contour: contours the exact signed distance of an interface (paper §2, Tables 2 and 3) and
// reports cells, segments, mean segment length, error and cost, with a picture of the tree and
// the contour like the paper's Figs. 5–7.
#include "slc/contour/contour.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "commands/commands.hpp"
#include "commands/common.hpp"
#include "commands/memory_budget.hpp"
#include "commands/output_folder.hpp"
#include "commands/surface_contour.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/render.hpp"
#include "slc/io/summary.hpp"
#include "slc/io/surface_files.hpp"
#include "slc/tree/triangulation.hpp"

namespace slc::cli {
namespace {

/// --refine's value when --eps is given without it: until converged (each pass that changes
/// nothing, or finds no midpoint beyond eps, ends refinement first).
constexpr int converged_passes = 1000;

struct ContourCommandOptions {
    std::string initial;
    std::string function;
    std::optional<int> depth;  ///< unset: depth_for_domain, as slc run takes for a user's shape
    std::optional<double> eps;
    int refine = 0;
    std::optional<double> eta;
    std::optional<int> thin_depth;  ///< unset: default_thin_depth for a file, 0 for a function
    double rho = 0.1;
    DomainOptions domain;
    std::optional<int> tree_depth;
    std::string out;
    int threads = 0;
};

/// Largest |F| over the vertices and over the segment midpoints (paper Tables 2 and 3).
struct ContourError {
    double vertices = 0.0;
    double midpoints = 0.0;
};

ContourError measure_error(const DistanceTree& tree, const Interface& curves) {
    const std::vector<double> f = tree.signed_distances(vertices_and_midpoints(curves));
    ContourError e;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        e.vertices = std::max(e.vertices, std::abs(f[i]));
        e.midpoints = std::max(e.midpoints, std::abs(f[curves.size() + i]));
    }
    return e;
}

/// The tree's triangulation (unperturbed) and leaves, the input faintly, the contour and its
/// vertices on top.
void draw(const ContourResult& r, const Interface& input, const Box& domain,
          const std::string& title, const std::filesystem::path& dir) {
    std::vector<Box> cells;
    for (std::uint32_t c : r.tree.leaves()) cells.push_back(r.tree.box(c));
    const Triangulation mesh = triangulate(r.tree);
    Figure figure(domain, title);
    figure.add_triangles(mesh.vertices, mesh.triangles, Color{0.55, 0.68, 0.88, 1.0}, 0.3);
    figure.add_boxes(cells, Color{0.35, 0.35, 0.35, 0.8});
    figure.add_curves(input, "input", Color{0.6, 0.75, 0.95, 1.0}, 3.0);
    figure.add_curves(r.curves, "contour", palette_color(1), 1.2);
    figure.add_points(r.curves.points(), palette_color(1), 1.8);
    figure.save(dir / "final.svg");
    figure.save(dir / "final.png");
}

/// The contour's options: ε and η as given, or by the rule of a run of the curves, ℓ their
/// length scale.
ContourOptions library_options(const ContourCommandOptions& o, int depth, double length_scale) {
    const ContourTolerances tolerances =
        contour_tolerances(2, depth, o.refine, length_scale, o.eps, o.eta);
    ContourOptions options;
    options.depth = depth;
    options.refine_passes = o.refine;
    options.eps = tolerances.eps;
    options.eta = tolerances.eta;
    options.rho = o.rho;
    options.thin_depth = o.thin_depth.value_or(default_thin_depth(2));
    options.distance_slack = 0.0;  // G is the exact signed distance, 1-Lipschitz
    return options;
}

/// summary.json before the contour: the input and every parameter, resolved.
nlohmann::json summary_head(const ContourCommandOptions& o, const LoadedInterface& in,
                            const ContourOptions& options, int tree_depth) {
    return {{"command", "contour"},
            {"input", o.initial},
            {"time", in.time},
            {"domain", box_json(in.domain)},
            {"params",
             {{"K", options.depth},
              {"P", o.refine},
              {"eps", options.resolved_eps()},
              {"eta", options.resolved_eta()},
              {"rho", o.rho},
              {"thin_depth", options.thin_depth},
              {"gamma", options.gamma},
              {"L", tree_depth},
              {"threads", thread_count()}}}};
}

std::string picture_title(const ContourCommandOptions& o, const ContourOptions& options,
                          const ContourResult& r, double error) {
    if (o.refine == 0) {
        return fmt::format("Linear contour, K = {}: {} segments, error {:.2e}", options.depth,
                           r.stats.segments, error);
    }
    return fmt::format("Contour K = {}, eps = {:.0e}, {} passes: {} segments, error {:.2e}",
                       options.depth, options.resolved_eps(), r.stats.passes, r.stats.segments,
                       error);
}

/// final.json, the pictures, then summary.json (last, so that it marks a complete run); thin_note
/// says which thin depth was kept, when another than the one asked for.
void write_results(const ContourCommandOptions& o, const ContourOptions& options,
                   const LoadedInterface& in, const DistanceTree& tree, const ContourResult& r,
                   nlohmann::json summary, OutputFolder& folder,
                   const std::optional<std::string>& thin_note) {
    const std::filesystem::path dir = folder.path();
    const ContourError e = measure_error(tree, r.curves);
    const double error = std::max(e.vertices, e.midpoints);
    summary["status"] = "ok";
    summary.update(contour_stats_json(r.stats));
    summary["error"] = r.curves.empty() ? nlohmann::json(nullptr) : nlohmann::json(error);
    summary["error_vertices"] = e.vertices;
    summary["error_midpoints"] = e.midpoints;
    summary["area"] = area(r.curves);
    summary["length"] = length(r.curves);
    const std::optional<std::string> torn =
        topology_note(shape_topology(in.curves), shape_topology(r.curves), 2, options.thin_depth);
    summary["kept_topology"] = !torn;
    if (torn) summary["note"] = *torn;
    if (thin_note) summary["note"] = torn ? *torn + "; " + *thin_note : *thin_note;
    write_file_atomic(dir / "final.json", interface_json(r.curves, in.time));
    draw(r, in.curves, in.domain, picture_title(o, options, r, error), dir);
    write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    folder.commit();
    if (torn) fmt::print(stderr, "slc: note: {}\n", *torn);
    if (thin_note) fmt::print(stderr, "slc: note: {}\n", *thin_note);
    fmt::print(
        "{} cells, {} segments, error {:.3g}, {} G evaluations ({:.2f} per vertex), {:.3g} s; "
        "wrote {}\n",
        r.stats.cells, r.stats.segments, error, r.stats.g_evals, r.stats.g_evals_per_vertex,
        summary["cpu_s"].get<double>(), (std::filesystem::path(o.out) / "summary.json").string());
}

void run_contour(const ContourCommandOptions& o) {
    apply_threads(o.threads);
    const LoadedInterface in = load_interface(o.initial, o.domain);
    const int tree_depth = o.tree_depth.value_or(DistanceTree::default_depth(in.curves, in.domain));
    // K as slc run resolves it for a user's curves: 5, deeper for a domain wider than the default.
    const int depth = o.depth.value_or(
        depth_for_domain(2, in.domain.width(), default_domain(in.curves.curves()).width()));
    const ContourOptions options = library_options(o, depth, length_scale(in.curves));
    check_tree_memory(fmt::format("--tree-depth {}", tree_depth), tree_depth, length(in.curves),
                      in.domain.width(), distance_bytes_per_cell);
    check_tree_memory(fmt::format("--depth {}", depth), depth, length(in.curves), in.domain.width(),
                      contour_bytes_per_cell);
    nlohmann::json summary = summary_head(o, in, options, tree_depth);
    OutputFolder folder(o.out, false);

    const DistanceTree tree(in.curves, in.domain, {.depth = tree_depth, .triangulate = false});
    const auto exact = [&tree](std::span<const Vec2> x, std::span<double> v) {
        const std::vector<double> f = tree.signed_distances(x);
        std::copy(f.begin(), f.end(), v.begin());
    };
    // cpu_s and wall_s time the contour alone, evaluations of F included, at the thin depth that
    // keeps the curves' components and holes where the default does not (the linear contours
    // decide it, and the one kept is refined).
    ContourOptions kept = options;
    const ContourResult result =
        timed_contour(summary, folder, fmt::format("at t = {}: ", in.time), [&] {
            if (!o.thin_depth) {
                ContourOptions linear = options;
                linear.refine_passes = 0;
                auto [thin, r] = keeping_topology(
                    shape_topology(in.curves), options.thin_depth,
                    [&](int levels) {
                        linear.thin_depth = levels;
                        return contour(exact, in.domain, linear);
                    },
                    [](const ContourResult& c) { return shape_topology(c.curves); });
                kept.thin_depth = thin;
                if (options.refine_passes == 0) return std::move(r);
            }
            return contour(exact, in.domain, kept);
        });
    summary["params"]["thin_depth"] = kept.thin_depth;
    write_results(o, kept, in, tree, result, std::move(summary), folder,
                  thin_depth_note("curves", options.thin_depth, kept.thin_depth, "--thin-depth"));
}

}  // namespace

void add_contour_command(CLI::App& app) {
    const auto [cmd, o] = add_command<ContourCommandOptions>(
        app, "contour",
        "Contours the exact signed distance of an interface (paper Tables 2 and 3)");
    const auto require_source = add_initial_or_builtin(
        *cmd, o->initial,
        "Interface file (JSON), or a closed surface (.obj, .stl, .ply, .vdb) contoured in space",
        "--function", o->function,
        "Instead of --initial, a built-in implicit surface in [-1, 1]^3: sphere, torus, cassini");
    cmd->add_option("-K,--depth", o->depth,
                    fmt::format("Depth K of the contouring tree (default as slc run takes for a "
                                "shape of your own: {}; for --function, beyond [-1, 1]^3)",
                                default_rule::depth()))
        ->check(integer_in(0, 20));
    cmd->add_option("--eps", o->eps,
                    fmt::format("Tolerance eps of refinement on |G| at segment midpoints (for a "
                                "surface: edge midpoints and triangle centroids); default as slc "
                                "run takes it, with half-width 1 for --function: {}",
                                default_rule::eps()))
        ->check(positive_number());
    auto* refine =
        cmd->add_option("--refine", o->refine,
                        "Passes P of adaptive refinement (default 0, the linear contour, or with "
                        "--eps given 1000: until converged); refinement stops early when no "
                        "midpoint exceeds eps or a pass changes nothing, so a large P means 'until "
                        "converged'; a surface left beyond eps ends with status 'unconverged' and "
                        "exit status 3")
            ->check(integer_in(0, 1000000));
    cmd->add_option("--eta", o->eta,
                    fmt::format("Root-finding tolerance eta: |G| <= eta at every vertex "
                                "(default {})",
                                default_rule::eta()))
        ->check(positive_number());
    cmd->add_option("--thin-depth", o->thin_depth,
                    fmt::format("Levels beyond K for cells where the zero set's two sides, or a "
                                "sharp turn, lie within one cell (default {}; 0 for --function); "
                                "left unset, where the contour at the default loses the input's "
                                "components or holes, the shallower depths and then deeper ones "
                                "are tried and the first that keeps them is used (a note says "
                                "so)",
                                default_rule::thin_depth()))
        ->check(integer_in(setting_range::thin_depth));
    cmd->add_option("--rho", o->rho, "Pruning ratio rho in [0, 1) (default 0.1)")
        ->check(fraction_below_one());
    add_domain_options(*cmd, o->domain);
    cmd->add_option("-L,--tree-depth", o->tree_depth,
                    "Depth L of the distance tree that evaluates F (default: cells about one mean "
                    "segment, or four to eight mean edges of a surface, wide; it sets the speed, "
                    "not the error)")
        ->check(integer_in(0, 30));
    cmd->add_option("--out", o->out, "Output folder")->required();
    add_threads_option(*cmd, o->threads);
    cmd->footer(
        "Writes final.json, summary.json (cells, segments, mean segment length, error = max |F| "
        "over\nvertices and segment midpoints, cpu_s, g_evals, g_evals_per_vertex) and "
        "final.svg/.png (tree and\ncontour); for a surface (.obj, .stl, .ply, .vdb) or --function, "
        "final.obj, final.vtp, final.png\nand summary.json (triangles, error over vertices, edge "
        "midpoints and centroids).");
    cmd->callback([o, require_source, refine] {
        require_source();
        // A tolerance given asks for it to be met: refinement until converged.
        if (refine->count() == 0 && o->eps) o->refine = converged_passes;
        if (!o->function.empty() || is_surface_file(o->initial)) {
            apply_threads(o->threads);
            const int thin =
                o->thin_depth.value_or(o->function.empty() ? default_thin_depth(3) : 0);
            run_surface_contour({o->initial, o->function, o->depth, o->refine, o->eps, o->eta, thin,
                                 o->thin_depth.has_value(), o->domain, o->tree_depth, o->out});
            return;
        }
        run_contour(*o);
    });
}

}  // namespace slc::cli
