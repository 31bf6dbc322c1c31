// Topology resolution (paper §2.1) in the plane: the K-level tree split by min|G|/γ with γ doubled
// until the tree is 2:1 balanced (tree_sampler.hpp, written once with space), G on its
// triangulation, perturbation of vertices where |G| ≤ η, the boundary check, and marching
// triangles into closed polygons with G > 0 on their right.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "perturb.hpp"
#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/point_text.hpp"
#include "stages.hpp"
#include "tree_sampler.hpp"

namespace slc::contouring {
namespace {

/// The tree sampler of the plane (TreeSampler<2>, with the caller's bounds on G), and what the
/// triangulation needs of it: the centres of the finest leaves and the vertices' values.
class CurveSampler : public TreeSampler<2> {
public:
    CurveSampler(BatchFunctionRef g, std::optional<BatchBoundsRef> bounds, const Quadtree& tree,
                 const ContourOptions& options, double rounding)
        : TreeSampler<2>(tree, g, bounds, options.distance_slack, rounding, options.resolved_eta(),
                         options.depth) {
        enter_centres_as_corners(options.bends_through_centres);
    }

    /// Centres of the leaves at the depth limit, in one batch. A leaf whose corners share one sign
    /// with |G| > γ h/√2 holds no zero if |∇G| ≤ γ (every point is within h/√2 of a corner), and
    /// such a leaf has no finer neighbour, so all its triangles keep that sign: its centre gets a
    /// stand-in value with that sign instead of an evaluation. So does a centre whose sign the
    /// corners' values or the bounds make certain.
    void complete_centres(double gamma) {
        const int depth = tree_.max_depth();
        const double clearance = gamma * tree_.edge(depth) / std::numbers::sqrt2;
        std::vector<std::uint32_t> finest;
        for (std::uint32_t c : tree_.leaves())
            if (tree_.cell(c).level == depth) finest.push_back(c);
        // Each centre is new and its own cell's only: numbered in cell order, worked out on all
        // threads.
        const std::size_t first = samples_.size();
        samples_.resize(first + finest.size(), pending);
        points_.resize(first + finest.size());
        parallel_for(finest.size(), [&](std::size_t i) {
            const std::uint32_t c = finest[i];
            const auto id = static_cast<std::uint32_t>(first + i);
            CellSamples& ids = cell_samples_[c];
            ids[4] = id;
            points_[id] = grid_.point(sample_keys(c, true).at[4]);
            double lo = infinity, hi = -infinity;
            for (int j = 0; j < 4; ++j) {
                lo = std::min(lo, samples_[ids[j]].value);
                hi = std::max(hi, samples_[ids[j]].value);
            }
            if (lo > clearance || hi < -clearance) {
                samples_[id] = Sample{lo > 0.0 ? lo : hi, infinity, Source::parents};
            } else if (const auto stand_in = from_donors(points_[id], std::span(ids).first(4))) {
                samples_[id] = *stand_in;
            }
        });
        std::vector<std::uint32_t> open;
        for (std::size_t i = 0; i < finest.size(); ++i) {
            const auto id = static_cast<std::uint32_t>(first + i);
            if (std::isnan(samples_[id].value)) open.push_back(id);
        }
        evaluate(apply_bounds(open));
    }

    /// The tree's triangulation (triangulate()'s, to the vertex numbers), with G or its stand-in
    /// at every vertex, the vertices found in the table of samples: every corner and centre of a
    /// cell is a sample point, and the midpoint of a leaf's edge is one exactly where the
    /// neighbour across is finer (it is then a corner of that neighbour's children, and no
    /// other cell's corner or centre). on_boundary: per vertex, whether it is on the root box.
    void triangulate(Topology& topo, std::vector<std::uint8_t>& on_boundary) {
        const std::uint64_t n = grid_.extent();
        topo.values.reserve(samples_.size());
        topo.mesh.vertices.reserve(samples_.size());
        topo.stand_in.reserve(samples_.size());
        on_boundary.reserve(samples_.size());
        auto number = [&](Sample& s, std::uint64_t gx, std::uint64_t gy) {
            if (s.vertex == no_vertex) {
                s.vertex = static_cast<std::uint32_t>(topo.mesh.vertices.size());
                topo.mesh.vertices.push_back(grid_.point({gx, gy}));
                topo.values.push_back(s.value);
                topo.stand_in.push_back(s.source != Source::g);
                on_boundary.push_back(gx == 0 || gy == 0 || gx == n || gy == n);
            }
            return s.vertex;
        };
        fan_leaves(
            tree_,
            [&](std::size_t c, int corner, std::uint64_t gx, std::uint64_t gy) {
                return number(samples_[cell_samples_[c][corner]], gx, gy);
            },
            [&](std::size_t c, int, std::uint64_t gx, std::uint64_t gy) {
                // No cell is finer than the depth limit, and the midpoint of such a leaf's edge
                // is on no coarser cell's corners or centre: no lookup is needed there.
                if (tree_.cell(c).level == tree_.max_depth()) return no_vertex;
                const std::uint32_t* id = index_.find(SampleGrid<2>::key({gx, gy}));
                return id == nullptr ? no_vertex : number(samples_[*id], gx, gy);
            },
            topo.mesh);
    }
};

std::string place(Vec2 p) { return point_text(p, 6); }

/// The zero set of the interpolant stays inside the domain iff G has one strict sign at every
/// boundary vertex: a boundary edge with a sign change or a zero would carry a contour vertex.
void check_boundary(const Topology& topo, std::span<const std::uint8_t> on_boundary, double eta) {
    const auto& mesh = topo.mesh;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (on_boundary[v] && std::abs(topo.values[v]) <= eta) {
            throw NumericalFailure(
                fmt::format("the contour reaches the domain boundary at {} (|G| <= eta there); "
                            "enlarge the domain (--domain, --box)",
                            place(mesh.vertices[v])));
        }
    }
    for (const auto& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = t[k], b = t[(k + 1) % 3];
            const double ga = topo.values[a], gb = topo.values[b];
            if (on_boundary[a] && on_boundary[b] && (ga > 0.0) != (gb > 0.0)) {
                const Vec2 p =
                    mesh.vertices[a] + ga / (ga - gb) * (mesh.vertices[b] - mesh.vertices[a]);
                throw LeftDomain(
                    fmt::format("the contour crosses the domain boundary near {}; enlarge the "
                                "domain (--domain, --box)",
                                place(p)));
            }
        }
    }
}

/// A deterministic direction for attempt k at vertex v (golden-ratio sequences: well spread,
/// independent of evaluation order and thread count).
Vec2 perturbation_direction(std::size_t v, int k) {
    const double phi = 0.6180339887498949, silver = 0.4142135623730950;
    const double turns = static_cast<double>(v + 1) * phi + static_cast<double>(k) * silver;
    const double angle = 2.0 * std::numbers::pi * (turns - std::floor(turns));
    return {std::cos(angle), std::sin(angle)};
}

/// Moves interior vertices with |G| ≤ η (§2.1) until none is left, each in its own direction.
std::size_t perturb(Topology& topo, BatchFunctionRef g, double eta) {
    return perturb_vertices<2>(topo.mesh.vertices, topo.values, g, eta,
                               topo.tree.edge(topo.tree.depth()), perturbation_direction);
}

/// Stand-ins at vertices of triangles where G changes sign get their exact values: root finding
/// starts from them. Their signs were certain, so no triangle should change state; should a bound
/// have been wrong (G's bound holds only to rounding, and a law may break it), the triangles the
/// new values cross are evaluated in turn, and values within η perturbed, until no crossed
/// triangle holds a stand-in. One batch per round, almost always one round. Returns the vertices
/// perturbed.
std::size_t evaluate_crossed_stand_ins(Topology& topo, BatchFunctionRef g, double eta) {
    const auto& mesh = topo.mesh;
    std::size_t perturbed = 0;
    for (;;) {
        std::vector<std::uint32_t> ids;
        for (const auto& t : mesh.triangles) {
            const bool positive = topo.values[t[0]] > 0.0;
            if ((topo.values[t[1]] > 0.0) == positive && (topo.values[t[2]] > 0.0) == positive)
                continue;
            for (std::uint32_t v : t) {
                if (topo.stand_in[v]) {
                    topo.stand_in[v] = 0;
                    ids.push_back(v);
                }
            }
        }
        if (ids.empty()) return perturbed;
        std::vector<Vec2> points;
        for (std::uint32_t v : ids) points.push_back(mesh.vertices[v]);
        std::vector<double> values(points.size());
        g(points, values);
        for (std::size_t i = 0; i < ids.size(); ++i) topo.values[ids[i]] = values[i];
        perturbed += perturb(topo, g, eta);
    }
}

}  // namespace

Topology resolve_topology(BatchFunctionRef g, const Box& domain, const ContourOptions& options,
                          std::optional<BatchBoundsRef> bounds) {
    const int thin_depth =
        thin_levels<2>(domain, options.depth, options.thin_depth, Quadtree::max_supported_depth);
    Topology topo{Quadtree(domain, options.depth + thin_depth), {}, {}, {}, {}};
    topo.gamma = options.gamma;
    // Both bounds allow for rounding in G and in the bound: a few thousand ulps of the
    // coordinates.
    const double rounding = 1e-12 * std::max(domain.largest_magnitude(), domain.width());
    CurveSampler sampler(g, bounds, topo.tree, options, rounding);
    topo.gamma = build_tree(topo.tree, sampler, options.gamma);
    const ThinSplit thin = split_thin(topo.tree, sampler, topo.gamma);
    topo.thin_cells = thin.cells;
    topo.thin_budget_reached = thin.budget_reached;
    sampler.complete_centres(topo.gamma);
    topo.bound_evals = sampler.bound_evals();
    std::vector<std::uint8_t> on_boundary;
    sampler.triangulate(topo, on_boundary);
    check_boundary(topo, on_boundary, options.resolved_eta());
    topo.perturbed = perturb(topo, g, options.resolved_eta());
    topo.perturbed += evaluate_crossed_stand_ins(topo, g, options.resolved_eta());
    topo.settled = static_cast<std::size_t>(
        std::count(topo.stand_in.begin(), topo.stand_in.end(), std::uint8_t{1}));
    return topo;
}

LinearContour march(Topology& topo) {
    const auto& mesh = topo.mesh;
    LinearContour out;
    KeyMap<std::uint32_t> on_edge;  // edge (lo, hi) -> contour vertex
    auto vertex_on = [&](std::uint32_t a, std::uint32_t b) {
        if (a > b) std::swap(a, b);
        const auto [vertex, fresh] = on_edge.try_emplace(
            (std::uint64_t{a} << 32) | b, static_cast<std::uint32_t>(out.brackets.size()));
        if (fresh) {
            out.brackets.push_back(
                {mesh.vertices[a], mesh.vertices[b], topo.values[a], topo.values[b]});
            out.next.push_back(std::numeric_limits<std::uint32_t>::max());
            out.triangle.push_back(0);
        }
        return *vertex;
    };
    topo.crossed.assign(mesh.triangles.size(), 0);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        std::array<bool, 3> positive{};
        for (int k = 0; k < 3; ++k) positive[k] = topo.values[tri[k]] > 0.0;
        if (positive[0] == positive[1] && positive[1] == positive[2]) continue;
        topo.crossed[t] = 1;
        SLC_ASSERT(!topo.stand_in[tri[0]] && !topo.stand_in[tri[1]] && !topo.stand_in[tri[2]],
                   "a leaf centre left unevaluated lies in triangles of one sign only");
        // Walking the counterclockwise boundary, the segment starts on the edge where G turns
        // from negative to positive and ends where it turns back: then G > 0 lies on its right.
        std::uint32_t start = 0, end = 0;
        for (int k = 0; k < 3; ++k) {
            const int j = (k + 1) % 3;
            if (!positive[k] && positive[j]) start = vertex_on(tri[k], tri[j]);
            if (positive[k] && !positive[j]) end = vertex_on(tri[k], tri[j]);
        }
        SLC_ASSERT(
            out.next[start] == std::numeric_limits<std::uint32_t>::max(),
            "a contour vertex starts one segment: its edge has two triangles of opposite walk");
        out.next[start] = end;
        out.triangle[start] = static_cast<std::uint32_t>(t);
    }
    for (std::uint32_t s : out.next) {
        SLC_ASSERT(s != std::numeric_limits<std::uint32_t>::max(),
                   "every contour vertex starts a segment: no dead ends off the boundary");
    }
    return out;
}

}  // namespace slc::contouring
