// slc contour on a surface: topology resolution in space (contour_surface) of the exact signed
// distance of a surface file or of a built-in implicit surface, its error against the exact
// distance, and the files.
#include "commands/surface_contour.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <optional>

#include "commands/memory_budget.hpp"
#include "commands/output_folder.hpp"
#include "slc/contour/implicit_surfaces.hpp"
#include "slc/contour/surface_contour.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/point_text.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/geometry/triangle3.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/summary.hpp"
#include "slc/io/surface_files.hpp"
#include "slc/io/surface_picture.hpp"
#include "slc/io/vtk.hpp"

namespace slc::cli {
namespace {

/// Largest |F| over the vertices, the edge midpoints and the centroids of the triangles, and
/// where the largest of all is.
struct SurfaceError {
    double vertices = 0.0;
    double midpoints = 0.0;
    double centroids = 0.0;
    Vec3 worst{};  ///< a point where |F| is largest
};

SurfaceError measure_error(const Surface& s, const std::function<double(Vec3)>& exact) {
    std::vector<double> v(s.vertices.size()), m(3 * s.size()), c(s.size());
    parallel_for(
        s.vertices.size(), [&](std::size_t i) { v[i] = std::abs(exact(s.vertices[i])); },
        expensive_grain);
    auto midpoint = [&](std::size_t i) {
        const Triangle3 tri = s.triangle(i / 3);
        const int k = static_cast<int>(i % 3);
        return 0.5 * (tri[k] + tri[(k + 1) % 3]);
    };
    auto centroid = [&](std::size_t t) {
        const Triangle3 tri = s.triangle(t);
        return (tri.a + tri.b + tri.c) / 3.0;
    };
    parallel_for(
        s.size(),
        [&](std::size_t t) {
            for (std::size_t k = 0; k < 3; ++k) m[3 * t + k] = std::abs(exact(midpoint(3 * t + k)));
            c[t] = std::abs(exact(centroid(t)));
        },
        expensive_grain);
    auto largest = [](const std::vector<double>& x) {
        return x.empty() ? x.end() : std::max_element(x.begin(), x.end());
    };
    SurfaceError e;
    double most = -1.0;
    if (const auto i = largest(v); i != v.end()) {
        e.vertices = *i, most = *i;
        e.worst = s.vertices[static_cast<std::size_t>(i - v.begin())];
    }
    if (const auto i = largest(m); i != m.end()) {
        e.midpoints = *i;
        if (*i > most) most = *i, e.worst = midpoint(static_cast<std::size_t>(i - m.begin()));
    }
    if (const auto i = largest(c); i != c.end()) {
        e.centroids = *i;
        if (*i > most) e.worst = centroid(static_cast<std::size_t>(i - c.begin()));
    }
    return e;
}

/// " by a sharp edge of the input" or " by a sharp corner of the input" when one (its triangles
/// turning by more than 30°) of the triangle nearest x lies within four times x's distance of
/// it: refinement does not follow such edges off the octree's axes, and the contour chamfers
/// them. Empty elsewhere.
std::string sharp_feature_near(const Surface& surface, const SurfaceDistanceTree& tree, Vec3 x) {
    const SurfacePoint p = tree.closest_point(x);
    const double reach = 4.0 * std::abs(p.distance);
    const TriangleIndices& t = surface.triangles[p.triangle];
    const Vec3 n = unit_normal(surface.triangle(p.triangle));
    // Whether a triangle with corner a (and b, when b is given) turns from t by more than 30°.
    auto sharp = [&](std::uint32_t a, std::optional<std::uint32_t> b) {
        for (std::uint32_t u = 0; u < surface.size(); ++u) {
            const TriangleIndices& o = surface.triangles[u];
            auto has = [&](std::uint32_t v) { return o[0] == v || o[1] == v || o[2] == v; };
            if (has(a) && (!b || has(*b)) &&
                dot(n, unit_normal(surface.triangle(u))) < std::cos(std::numbers::pi / 6.0))
                return true;
        }
        return false;
    };
    for (int k = 0; k < 3; ++k)
        if (distance(x, surface.vertices[t[k]]) <= reach && sharp(t[k], std::nullopt))
            return " by a sharp corner of the input";
    for (int k = 0; k < 3; ++k) {
        const Vec3 a = surface.vertices[t[k]], b = surface.vertices[t[(k + 1) % 3]];
        const double along = std::clamp(dot(x - a, b - a) / norm2(b - a), 0.0, 1.0);
        if (distance(x, a + along * (b - a)) <= reach && sharp(t[k], t[(k + 1) % 3]))
            return " by a sharp edge of the input";
    }
    return "";
}

/// The contoured function, its exact distance where known, the domain and a name for it.
struct Source {
    std::string name;
    Box3 domain;
    std::optional<Surface> surface;  ///< the input surface, for --initial
    std::function<double(Vec3)> g;
    std::function<double(Vec3)> exact;
    bool lipschitz = false;  ///< g is a signed distance
};

}  // namespace

void run_surface_contour(const SurfaceContourRequest& r) {
    Source source;
    std::optional<SurfaceDistanceTree> tree;
    if (!r.function.empty()) {
        const ImplicitSurface f = implicit_surface(r.function);
        source.name = r.function;
        source.domain = r.domain.half_width || r.domain.box
                            ? resolve_domain3(r.domain, Box3::centered_cube(1.0 / 1.5))
                            : Box3::centered_cube(1.0);
        source.g = f.g;
        source.exact = f.distance;
        source.lipschitz = f.g_is_distance;
    } else {
        LoadedSurface in = load_surface(r.initial, r.domain);
        source.name = r.initial;
        source.domain = in.domain;
        source.surface = std::move(in.surface);
        source.lipschitz = true;
    }
    const double width = source.domain.width();
    // K as slc run resolves it for a user's surface: 5, deeper for a domain wider than the
    // default (the cube around the surface, or [-1, 1]^3 around a built-in function).
    const double default_width = source.surface
                                     ? default_domain(bounding_box(*source.surface)).width()
                                     : Box3::centered_cube(1.0).width();
    const int depth = r.depth.value_or(depth_for_domain(3, width, default_width));
    // The octree hugs the surface: about area / h² cells at the finest level. A function's area
    // is not known before it is contoured; six faces of the domain bound any reasonable one.
    const double surface_area = source.surface ? area(*source.surface) : 6.0 * width * width;
    check_octree_memory(fmt::format("--depth {}", depth), depth, surface_area, width,
                        surface_contour_bytes_per_cell);
    nlohmann::json summary = {{"command", "contour"},
                              {r.function.empty() ? "input" : "function", source.name},
                              {"domain",
                               {source.domain.lo.x, source.domain.lo.y, source.domain.lo.z,
                                source.domain.hi.x, source.domain.hi.y, source.domain.hi.z}},
                              {"params",
                               {{"K", depth},
                                {"P", r.refine},
                                {"thin_depth", r.thin_depth},
                                {"threads", thread_count()}}}};
    OutputFolder folder(r.out, false);
    if (source.surface) {
        const int tree_depth = r.tree_depth.value_or(
            SurfaceDistanceTree::default_depth(*source.surface, source.domain));
        summary["params"]["L"] = tree_depth;
        tree.emplace(*source.surface, source.domain,
                     SurfaceDistanceTree::Options{.depth = tree_depth});
        source.g = [&tree](Vec3 x) { return tree->closest_point(x).distance; };
        source.exact = source.g;
    }
    const auto g = pointwise<Vec3>([&](Vec3 x) { return source.g(x); }, expensive_grain);
    // A signed distance is 1-Lipschitz: points far from its surface need no value.
    // ε and η as given, or by the rule of a run of the surface.
    const ContourTolerances tolerances = contour_tolerances(
        3, depth, r.refine, source.surface ? length_scale(*source.surface) : 1.0, r.eps, r.eta);
    const SurfaceContourOptions options{
        .depth = depth,
        .refine_passes = r.refine,
        .eps = tolerances.eps,
        .eta = tolerances.eta,
        .thin_depth = r.thin_depth,
        // A mesh's facets meet at creases, which refinement follows.
        .creases = source.surface.has_value(),
        .distance_slack = source.lipschitz ? std::optional(0.0) : std::nullopt,
        // A mesh's topology is known: the contour keeps it beside its sharp edges and points.
        .keep_topology =
            source.surface ? std::optional(shape_topology(*source.surface)) : std::nullopt};
    summary["params"]["eps"] = options.resolved_eps();
    summary["params"]["eta"] = options.resolved_eta();
    summary["params"]["creases"] = options.creases;
    // cpu_s and wall_s time the contour alone, evaluations of G included: of a surface file, at
    // the thin depth that keeps its components and handles, where the default does not (the
    // linear contours decide it, and the one kept is refined).
    int thin_kept = r.thin_depth;
    const SurfaceContour result = timed_contour(summary, folder, "", [&] {
        SurfaceContourOptions o = options;
        if (source.surface && !r.thin_depth_given) {
            o.refine_passes = 0;
            auto [thin, c] = keeping_topology(
                shape_topology(*source.surface), r.thin_depth,
                [&](int levels) {
                    o.thin_depth = levels;
                    return contour_surface(g, source.domain, o);
                },
                [](const SurfaceContour& linear) { return shape_topology(linear.surface); });
            thin_kept = thin;
            if (options.refine_passes == 0) return std::move(c);
            o = options;
            o.thin_depth = thin_kept;
        }
        return contour_surface(g, source.domain, o);
    });
    summary["params"]["thin_depth"] = thin_kept;
    const std::optional<std::string> thin_note =
        thin_depth_note("surface", r.thin_depth, thin_kept, "--thin-depth");
    const Surface& s = result.surface;
    const SurfaceContourStats& st = result.stats;
    summary["status"] = "ok";
    summary["params"]["gamma"] = st.gamma;
    summary.update(contour_stats_json(st));
    const ShapeTopology got = shape_topology(s);
    summary.update({{"components", got.components},
                    {"genus", got.holes},
                    {"area", area(s)},
                    {"volume", volume(s)}});
    // A surface of the user's: whether the contour kept its components and handles.
    std::optional<std::string> torn;
    if (source.surface) {
        torn = topology_note(shape_topology(*source.surface), got, 3, thin_kept);
        summary["kept_topology"] = !torn;
        if (torn) summary["note"] = *torn;
        if (thin_note) summary["note"] = torn ? *torn + "; " + *thin_note : *thin_note;
    }
    // Whether refinement met ε, when refinement was asked for.
    if (r.refine != 0) summary["converged"] = st.converged;
    std::optional<double> error;
    Vec3 worst{};
    if (source.exact && !s.triangles.empty()) {
        const SurfaceError e = measure_error(s, source.exact);
        error = std::max({e.vertices, e.midpoints, e.centroids});
        worst = e.worst;
        summary["error"] = *error;
        summary["error_vertices"] = e.vertices;
        summary["error_midpoints"] = e.midpoints;
        summary["error_centroids"] = e.centroids;
    } else {
        summary["error"] = nullptr;
    }
    const std::filesystem::path dir = folder.path();
    write_file_atomic(dir / "final.obj", obj_text(s));
    write_file_atomic(dir / "final.vtp", vtp_text(s, 0.0));
    if (!s.triangles.empty()) {
        std::string title =
            r.refine == 0 ? fmt::format("Linear contour, K = {}: {} triangles", depth, st.triangles)
                          : fmt::format("Contour K = {}, eps = {:.0e}, {} passes: {} triangles",
                                        depth, options.resolved_eps(), st.passes, st.triangles);
        if (error) title += fmt::format(", error {:.2e}", *error);
        // A surface of the user's is drawn with the up axis its shape suggests (a y-up scan
        // stands up); a built-in function's with z up.
        const UpAxis up = source.surface ? up_axis(bounding_box(*source.surface)) : UpAxis::z;
        save_surface_picture(s, dir / "final.png", {.title = title, .up = up});
        save_surface_views(std::span<const Surface>(&s, 1), dir / "views.png",
                           {.width = 500, .height = 500, .title = title, .up = up});
    }
    // A refinement that stops with midpoints or centroids beyond ε (its splits refused, or P
    // spent) says so: the files are written, and the status and the exit status tell.
    const bool unconverged = r.refine != 0 && !s.triangles.empty() && !st.converged;
    if (unconverged) summary["status"] = "unconverged";
    write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
    folder.commit();
    if (torn) fmt::print(stderr, "slc: note: {}\n", *torn);
    if (thin_note) fmt::print(stderr, "slc: note: {}\n", *thin_note);
    if (unconverged) {
        // Where the contour is farthest, and whether a sharp edge or corner of the input is
        // there: refinement that cannot cut the contour there (corners closer together than the
        // cells) leaves it chamfered, and a larger K narrows the chamfer.
        const std::string sharp = error && source.surface
                                      ? sharp_feature_near(*source.surface, *tree, worst)
                                      : std::string();
        throw NumericalFailure(fmt::format(
            "refinement stopped after {} passes with |G| above eps = {:g}{} at a midpoint or "
            "centroid{}{}; raise -K or --eps{} (results written to {})",
            st.passes, options.resolved_eps(),
            error ? fmt::format(" (largest {:.3g})", *error) : std::string(),
            error ? " near " + point_text(worst, 6) : std::string(),
            sharp.empty() ? std::string() : sharp + ", which the contours chamfer",
            st.passes >= r.refine ? " or --refine" : "", r.out));
    }
    fmt::print(
        "{} cells, {} triangles, error {}, {} G evaluations ({:.2f} per vertex), {:.3g} s; "
        "wrote {}\n",
        st.cells, st.triangles, error ? fmt::format("{:.3g}", *error) : "n/a", st.g_evals,
        st.g_evals_per_vertex, summary["cpu_s"].get<double>(),
        (std::filesystem::path(r.out) / "summary.json").string());
}

}  // namespace slc::cli
