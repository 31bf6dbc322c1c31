// contour_surface() (paper §2 with d = 3, DESIGN §8) in stages, as contour() in the plane: the
// topology on the tetrahedralized octree (surface_topology.cpp), marching tetrahedra with roots
// on the tetrahedra's edges, specks dropped, and adaptive refinement (surface_refinement.cpp).
#include "slc/contour/surface_contour.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "options_check.hpp"
#include "rounding.hpp"
#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/geometry/triangle3.hpp"
#include "slc/tree/tetrahedralization.hpp"
#include "surface_stages.hpp"
#include "tree_sampler.hpp"

namespace slc {
namespace {

using contouring::SpaceEvaluator;
using contouring::SurfaceTopology;

/// Throws InvalidInput naming the first option out of range, or a domain that is not a cube.
void validate(const SurfaceContourOptions& o, const Box3& domain) {
    contouring::check_options(o, max_tetrahedralized_depth);
    const double w = domain.width();
    if (!(w > 0.0) || !std::isfinite(w) || !is_finite(domain.lo) || !domain.is_cube()) {
        throw InvalidInput(fmt::format(
            "the contour domain must be a cube of positive size, got [{}, {}] x [{}, {}] x [{}, "
            "{}]",
            domain.lo.x, domain.hi.x, domain.lo.y, domain.hi.y, domain.lo.z, domain.hi.z));
    }
}

/// Drops the closed components of s smaller than `size` across (the largest extent of their
/// box), and the vertices only they used. Returns the components dropped.
std::size_t drop_specks(Surface& s, double size) {
    if (s.triangles.empty()) return 0;
    const std::vector<std::uint32_t> label = component_labels(s);
    const std::size_t count = *std::max_element(label.begin(), label.end()) + 1;
    std::vector<Box3> boxes(count, Box3::empty());
    for (std::size_t t = 0; t < s.size(); ++t)
        boxes[label[t]] = unite(boxes[label[t]], bounding_box(s.triangle(t)));
    std::vector<std::uint8_t> speck(count, 0);
    std::size_t dropped = 0;
    for (std::size_t c = 0; c < count; ++c) {
        const Vec3 extent = boxes[c].hi - boxes[c].lo;
        speck[c] = std::max({extent.x, extent.y, extent.z}) < size ? 1 : 0;
        dropped += speck[c];
    }
    if (dropped == 0) return 0;
    std::vector<TriangleIndices> kept;
    for (std::size_t t = 0; t < s.size(); ++t)
        if (!speck[label[t]]) kept.push_back(s.triangles[t]);
    s.triangles = std::move(kept);
    drop_unused_vertices(s);
    return dropped;
}

/// The even permutations of a positively oriented tetrahedron that start with each vertex:
/// the other three in an order that keeps the orientation.
constexpr int others[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

/// The zero set of the piecewise-linear interpolant on the tetrahedra: a vertex on every edge
/// where G changes sign, and in each crossing tetrahedron a triangle, or a quadrilateral to split
/// once its vertices are known; both face G > 0.
struct LinearSurface {
    /// Per surface vertex: its edge, from its end lower in the grid's order (x, then y, then
    /// z), so that a root does not depend on how the mesh numbers its vertices.
    std::vector<Bracket3> brackets;
    std::vector<TriangleIndices> triangles;
    std::vector<std::array<std::uint32_t, 4>> quads;  ///< around their boundary, facing G > 0
};

/// Marching tetrahedra over the crossing tetrahedra, in order: each edge's vertex found once for
/// all the tetrahedra around it (fewer edges than tetrahedra: each is shared).
LinearSurface march(const SurfaceTopology& topo) {
    const auto& mesh = topo.mesh;
    const auto& values = topo.values;
    LinearSurface out;
    KeyMap<std::uint32_t> on_edge(topo.crossing.size());
    auto vertex_on = [&](std::uint32_t a, std::uint32_t b) {
        if (a > b) std::swap(a, b);
        const auto [vertex, fresh] = on_edge.try_emplace(
            (std::uint64_t{a} << 32) | b, static_cast<std::uint32_t>(out.brackets.size()));
        if (fresh) {
            if (mesh.grid[b] < mesh.grid[a]) std::swap(a, b);
            out.brackets.push_back({mesh.vertices[a], mesh.vertices[b], values[a], values[b]});
        }
        return *vertex;
    };
    for (const std::uint32_t tet : topo.crossing) {
        const auto& t = mesh.tetrahedra[tet];
        int positive = 0;
        for (std::uint32_t v : t) positive += values[v] > 0.0 ? 1 : 0;
        if (positive == 0 || positive == 4) continue;  // (signs kept: see above)
        if (positive == 1 || positive == 3) {
            // The vertex of the lone sign, i, and the others (j, k, l) in the orientation's
            // order: the triangle on edges ij, ik, il faces away from i.
            int i = 0;
            while ((values[t[i]] > 0.0) != (positive == 1)) ++i;
            const auto* o = others[i];
            const std::uint32_t a = vertex_on(t[i], t[o[0]]), b = vertex_on(t[i], t[o[1]]),
                                c = vertex_on(t[i], t[o[2]]);
            if (positive == 1)
                out.triangles.push_back({a, c, b});  // towards the positive vertex i
            else
                out.triangles.push_back({a, b, c});
            continue;
        }
        // Two of each sign: (p0, p1, n0, n1) an even permutation of the tetrahedron; the
        // quadrilateral on edges p0n0, p1n0, p1n1, p0n1 then faces the positive side.
        int p[2], m[2], np = 0, nm = 0;
        for (int k = 0; k < 4; ++k) (values[t[k]] > 0.0 ? p[np++] : m[nm++]) = k;
        // Parity of (p0, p1, m0, m1) as a permutation of (0, 1, 2, 3).
        const int order[4] = {p[0], p[1], m[0], m[1]};
        int inversions = 0;
        for (int x = 0; x < 4; ++x)
            for (int y = x + 1; y < 4; ++y) inversions += order[x] > order[y] ? 1 : 0;
        if (inversions % 2 == 1) std::swap(m[0], m[1]);
        out.quads.push_back({vertex_on(t[p[0]], t[m[0]]), vertex_on(t[p[1]], t[m[0]]),
                             vertex_on(t[p[1]], t[m[1]]), vertex_on(t[p[0]], t[m[1]])});
    }
    return out;
}

/// The roots of G on the brackets' edges, the surface's vertices; counts their evaluations and
/// the roots that did not converge in stats.
std::vector<Vec3> roots_on_edges(SpaceFunctionRef g, std::span<const Bracket3> brackets,
                                 const RootOptions& options, SurfaceContourStats& stats) {
    std::size_t evaluations = 0;
    const SpaceEvaluator counted(g, evaluations);
    const std::vector<Root3> roots = find_roots(
        [&](std::span<const Vec3> points, std::span<double> got) { counted(points, got); },
        brackets, options);
    stats.g_evals_roots = evaluations;
    std::vector<Vec3> vertices;
    vertices.reserve(roots.size());
    for (const Root3& r : roots) {
        vertices.push_back(r.point);
        if (!r.converged) ++stats.unconverged_roots;
    }
    return vertices;
}

/// Appends to triangles the quadrilaterals, each split along its shorter diagonal.
void split_quads(std::span<const std::array<std::uint32_t, 4>> quads, std::span<const Vec3> x,
                 std::vector<TriangleIndices>& triangles) {
    for (const auto& q : quads) {
        if (distance(x[q[0]], x[q[2]]) <= distance(x[q[1]], x[q[3]])) {
            triangles.push_back({q[0], q[1], q[2]});
            triangles.push_back({q[0], q[2], q[3]});
        } else {
            triangles.push_back({q[1], q[2], q[3]});
            triangles.push_back({q[1], q[3], q[0]});
        }
    }
}

/// Adaptive refinement of s (§2.2), its figures in stats.
void refine(Surface& s, SpaceFunctionRef g, const SurfaceContourOptions& options,
            SurfaceContourStats& stats) {
    const SpaceEvaluator counted(g, stats.g_evals_refine);
    const RootOptions roots{.eta = options.resolved_eta(), .method = options.root_method};
    auto refined = [&](Surface& surface, bool creases) {
        return contouring::refine_surface(surface, counted, options.resolved_eps(), roots,
                                          options.refine_passes, options.max_refine_passes,
                                          options.max_vertices, creases);
    };
    std::optional<Surface> linear;
    if (options.creases) linear = s;
    contouring::SurfaceRefinement r = refined(s, options.creases);
    // Where following creases left a part beyond ε (slivers about a vertex where several creases
    // meet), plain refinement from the linear contour, if it comes nearer.
    if (linear && r.converged == 0) {
        const contouring::SurfaceRefinement plain = refined(*linear, false);
        if (plain.converged != 0 || plain.residual < r.residual) s = std::move(*linear), r = plain;
    }
    stats.passes = r.passes;
    stats.splits = r.splits;
    stats.rejected = r.rejected;
    stats.collapses = r.collapses;
    stats.flips = r.flips;
    stats.converged = r.converged != 0;
    stats.residual = r.residual;
}

/// contour_surface() with or without bounds on G.
SurfaceContour contour_surface_with(SpaceFunctionRef g, const Box3& domain,
                                    const SurfaceContourOptions& given,
                                    std::optional<SpaceBoundsRef> bounds) {
    validate(given, domain);
    const SurfaceContourOptions options = contouring::within_rounding(given, domain);
    SurfaceContour out;
    SurfaceContourStats& stats = out.stats;
    const SurfaceTopology topo = contouring::resolve_surface_topology(
        SpaceEvaluator(g, stats.g_evals_tree), domain, options, bounds);
    stats.gamma = topo.gamma;
    stats.thin_cells = topo.thin_cells;
    stats.thin_budget_reached = topo.thin_budget_reached;
    stats.finest_cell = topo.tree.edge(topo.tree.depth());
    stats.finest_at = contouring::deepest_place(topo.tree);
    stats.cells = topo.tree.size();
    stats.leaves = topo.tree.leaves().size();
    stats.settled = topo.settled;
    stats.bound_evals = topo.bound_evals;
    stats.tetrahedra = topo.mesh.tetrahedra.size();
    stats.perturbed = topo.perturbed;
    stats.moved_across = topo.moved_across;

    LinearSurface linear = march(topo);
    const RootOptions roots{.eta = options.resolved_eta(), .method = options.root_method};
    out.surface.vertices = roots_on_edges(g, linear.brackets, roots, stats);
    split_quads(linear.quads, out.surface.vertices, linear.triangles);
    out.surface.triangles = std::move(linear.triangles);
    // Beside a convex corner, where thin cells are finer than their neighbours, a mesh vertex
    // just inside the corner can have no neighbour inside: the linear zero set closes a speck
    // around it, apart from the rest of the corner. A component less than a finest cell across
    // is below what the mesh resolves: dropped (only where cells went beyond K).
    if (stats.thin_cells > 0)
        stats.specks = drop_specks(out.surface, topo.tree.edge(topo.tree.depth()));
    if (options.refine_passes != 0 && !out.surface.triangles.empty())
        refine(out.surface, g, options, stats);
    stats.triangles = out.surface.triangles.size();
    stats.vertices = out.surface.vertices.size();
    stats.g_evals = stats.g_evals_tree + stats.g_evals_roots + stats.g_evals_refine;
    stats.g_evals_per_vertex = stats.vertices == 0 ? 0.0
                                                   : static_cast<double>(stats.g_evals) /
                                                         static_cast<double>(stats.vertices);
    return out;
}

}  // namespace

SurfaceContour contour_surface(SpaceFunctionRef g, const Box3& domain,
                               const SurfaceContourOptions& options) {
    return contour_surface_with(g, domain, options, std::nullopt);
}

SurfaceContour contour_surface(SpaceFunctionRef g, const Box3& domain,
                               const SurfaceContourOptions& options, SpaceBoundsRef bounds) {
    return contour_surface_with(g, domain, options, bounds);
}

}  // namespace slc
