// contour_surface(): topology resolution in space (paper §2.1 with d = 3) — the octree split by
// min|G| against γ·edge with γ doubled until it is 2:1 balanced, its tetrahedral mesh, G at the
// mesh vertices, perturbation of vertices where |G| ≤ η, the boundary check — and marching
// tetrahedra with roots on the tetrahedra's edges.
#include "slc/contour/surface_contour.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"
#include "slc/tree/octree.hpp"
#include "slc/tree/tetrahedralization.hpp"
#include "surface_stages.hpp"

namespace slc {
namespace {

/// After this many doublings of γ (a factor of about 10^7) the tree is balanced by brute force.
constexpr int max_gamma_doublings = 24;
/// Perturbation: the first displacement is this fraction of the finest cell edge, doubled at each
/// attempt; after max_perturbations attempts it is 3.2% of that edge, well below the smallest
/// altitude of the mesh's tetrahedra (an eighth of the finest edge), so the mesh stays valid.
constexpr double first_perturbation = 1e-3;
constexpr int max_perturbations = 6;

std::string place(Vec3 p) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", p.x, p.y, p.z); }

void validate(const SurfaceContourOptions& o, const Box3& domain) {
    auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
    if (o.depth < 0 || o.depth > max_tetrahedralized_depth) {
        throw InvalidInput(fmt::format("contour depth K must be between 0 and {}, got {}",
                                       max_tetrahedralized_depth, o.depth));
    }
    if (!positive(o.eta)) throw InvalidInput(fmt::format("eta must be positive, got {}", o.eta));
    if (!positive(o.gamma))
        throw InvalidInput(fmt::format("gamma must be positive, got {}", o.gamma));
    if (o.refine_passes < 0 && o.refine_passes != SurfaceContourOptions::until_converged) {
        throw InvalidInput(
            fmt::format("refinement passes P must be >= 0, got {}", o.refine_passes));
    }
    if (o.eps && (!positive(*o.eps) || *o.eps < o.eta)) {
        throw InvalidInput(fmt::format("eps must be at least eta = {}, got {}", o.eta, *o.eps));
    }
    const double w = domain.width();
    if (!(w > 0.0) || !std::isfinite(w) || !is_finite(domain.lo) || !domain.is_cube()) {
        throw InvalidInput(fmt::format(
            "the contour domain must be a cube of positive size, got [{}, {}] x [{}, {}] x [{}, "
            "{}]",
            domain.lo.x, domain.hi.x, domain.lo.y, domain.hi.y, domain.lo.z, domain.hi.z));
    }
}

using Evaluator = contouring::SpaceEvaluator;

/// G at the grid points of the tree's cells (corners and centres, on the grid of half the finest
/// edge), each evaluated once, and the least |G| at each cell's nine points.
class TreeSampler {
public:
    TreeSampler(const Octree& tree, const Evaluator& g)
        : tree_(tree),
          g_(g),
          shift_(tree.max_depth() + 1),
          step_(tree.edge(0) / static_cast<double>(std::uint64_t{1} << shift_)) {}

    /// Evaluates the new points of the given cells in one batch and records their least |G|.
    void sample(std::span<const std::uint32_t> cells) {
        min_abs_.resize(tree_.size(), 0.0);
        std::vector<Vec3> points;
        std::vector<std::uint32_t> ids;
        for (std::uint32_t c : cells) {
            for_points(c, [&](std::uint64_t key, Vec3 p) {
                const auto [id, fresh] =
                    index_.try_emplace(key, static_cast<std::uint32_t>(values_.size()));
                if (fresh) {
                    values_.push_back(0.0);
                    points.push_back(p);
                    ids.push_back(*id);
                }
            });
        }
        std::vector<double> values(points.size());
        g_(points, values);
        for (std::size_t i = 0; i < ids.size(); ++i) values_[ids[i]] = values[i];
        for (std::uint32_t c : cells) {
            double least = std::numeric_limits<double>::infinity();
            for_points(c, [&](std::uint64_t key, Vec3) {
                least = std::min(least, std::abs(values_[index_.at(key)]));
            });
            min_abs_[c] = least;
        }
    }

    double min_abs(std::uint32_t c) const { return min_abs_[c]; }
    /// G at a grid point already sampled, or nullptr.
    const double* value(std::uint64_t key) const {
        const std::uint32_t* id = index_.find(key);
        return id ? &values_[*id] : nullptr;
    }

private:
    /// f(key, point) for the eight corners and the centre of cell c.
    template <class F>
    void for_points(std::uint32_t c, F f) const {
        const auto& cell = tree_.cell(c);
        const std::uint64_t u = std::uint64_t{1} << (shift_ - cell.level);
        const std::uint64_t x = cell.ix * u, y = cell.iy * u, z = cell.iz * u;
        auto at = [&](std::uint64_t gx, std::uint64_t gy, std::uint64_t gz) {
            const Vec3 lo = tree_.root_box().lo;
            f(Tetrahedralization::key(gx, gy, gz),
              Vec3{lo.x + static_cast<double>(gx) * step_, lo.y + static_cast<double>(gy) * step_,
                   lo.z + static_cast<double>(gz) * step_});
        };
        for (std::uint64_t k = 0; k < 8; ++k)
            at(x + (k & 1) * u, y + (k >> 1 & 1) * u, z + (k >> 2) * u);
        at(x + u / 2, y + u / 2, z + u / 2);
    }

    const Octree& tree_;
    const Evaluator& g_;
    int shift_;
    double step_;
    KeyMap<std::uint32_t> index_;
    std::vector<double> values_;
    std::vector<double> min_abs_;
};

/// Splits, level by level from the frontier, every cell whose edge exceeds min|G|/γ.
void split_while_coarse(Octree& tree, TreeSampler& sampler, std::vector<std::uint32_t> frontier,
                        double gamma) {
    while (!frontier.empty()) {
        sampler.sample(frontier);
        std::vector<std::uint32_t> next;
        for (std::uint32_t c : frontier) {
            const int level = tree.cell(c).level;
            if (level < tree.max_depth() && gamma * tree.edge(level) > sampler.min_abs(c)) {
                const std::uint32_t first = tree.split(c);
                for (std::uint32_t k = 0; k < 8; ++k) next.push_back(first + k);
            }
        }
        frontier = std::move(next);
    }
}

/// Builds the tree, doubling γ until it is balanced; the split criterion is monotone in γ, so
/// each doubling offers the leaves to it again. Returns γ.
double build_tree(Octree& tree, TreeSampler& sampler, double gamma) {
    split_while_coarse(tree, sampler, {0}, gamma);
    for (int doubling = 0; !tree.is_balanced(); ++doubling) {
        if (doubling == max_gamma_doublings) {
            tree.balance();
            break;
        }
        gamma *= 2.0;
        std::vector<std::uint32_t> leaves;
        for (std::uint32_t c : tree.leaves())
            if (tree.cell(c).level < tree.max_depth()) leaves.push_back(c);
        // Leaves are sampled already: test them, then sample and test their children.
        std::vector<std::uint32_t> next;
        for (std::uint32_t c : leaves) {
            if (gamma * tree.edge(tree.cell(c).level) > sampler.min_abs(c)) {
                const std::uint32_t first = tree.split(c);
                for (std::uint32_t k = 0; k < 8; ++k) next.push_back(first + k);
            }
        }
        split_while_coarse(tree, sampler, std::move(next), gamma);
    }
    return gamma;
}

/// A deterministic direction for attempt k at vertex v: golden-ratio sequences on the sphere.
Vec3 perturbation_direction(std::size_t v, int k) {
    const double phi = 0.6180339887498949, silver = 0.4142135623730950;
    const double plastic = 0.7548776662466927, bronze = 0.3027756377319946;
    auto frac = [](double x) { return x - std::floor(x); };
    const double z = 2.0 * frac(static_cast<double>(v + 1) * phi + k * silver) - 1.0;
    const double angle =
        2.0 * std::numbers::pi * frac(static_cast<double>(v + 1) * plastic + k * bronze);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(angle), r * std::sin(angle), z};
}

/// True when grid point p lies on the root box's boundary (at 0 or the grid's extent).
bool on_boundary(const std::array<std::uint32_t, 3>& p, std::uint32_t extent) {
    for (std::uint32_t x : p)
        if (x == 0 || x == extent) return true;
    return false;
}

/// The even permutations of a positively oriented tetrahedron that start with each vertex:
/// the other three in an order that keeps the orientation.
constexpr int others[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

}  // namespace

SurfaceContour contour_surface(SpaceFunctionRef g, const Box3& domain,
                               const SurfaceContourOptions& options) {
    validate(options, domain);
    SurfaceContour out;
    SurfaceContourStats& stats = out.stats;
    const Evaluator tree_g(g, stats.g_evals_tree);
    Octree tree(domain, options.depth);
    TreeSampler sampler(tree, tree_g);
    stats.gamma = build_tree(tree, sampler, options.gamma);
    stats.cells = tree.size();
    stats.leaves = tree.leaves().size();

    // G at the mesh's vertices: the tree's samples, and one batch for the face centres.
    Tetrahedralization mesh = tetrahedralize(tree);
    stats.tetrahedra = mesh.tetrahedra.size();
    const std::size_t n = mesh.vertices.size();
    std::vector<double> values(n);
    {
        std::vector<Vec3> points;
        std::vector<std::uint32_t> ids;
        for (std::uint32_t v = 0; v < n; ++v) {
            const auto& q = mesh.grid[v];
            if (const double* known = sampler.value(Tetrahedralization::key(q[0], q[1], q[2]))) {
                values[v] = *known;
            } else {
                points.push_back(mesh.vertices[v]);
                ids.push_back(v);
            }
        }
        std::vector<double> got(points.size());
        tree_g(points, got);
        for (std::size_t i = 0; i < ids.size(); ++i) values[ids[i]] = got[i];
    }

    // The zero set may not reach the domain's boundary: a boundary vertex within η of zero, or
    // a sign change along an edge on the boundary, is LeftDomain.
    const auto extent = static_cast<std::uint32_t>(std::uint64_t{2} << tree.max_depth());
    for (std::uint32_t v = 0; v < n; ++v) {
        if (on_boundary(mesh.grid[v], extent) && std::abs(values[v]) <= options.eta) {
            throw LeftDomain(
                fmt::format("the contour reaches the domain boundary near {}; enlarge the domain",
                            place(mesh.vertices[v])));
        }
    }
    for (const auto& t : mesh.tetrahedra) {
        for (int i = 0; i < 4; ++i) {
            for (int j = i + 1; j < 4; ++j) {
                const auto& p = mesh.grid[t[i]];
                const auto& q = mesh.grid[t[j]];
                bool same_face = false;
                for (int a = 0; a < 3; ++a)
                    same_face |= p[a] == q[a] && (p[a] == 0 || p[a] == extent);
                if (same_face && (values[t[i]] > 0.0) != (values[t[j]] > 0.0)) {
                    throw LeftDomain(fmt::format(
                        "the contour crosses the domain boundary near {}; enlarge the domain",
                        place(0.5 * (mesh.vertices[t[i]] + mesh.vertices[t[j]]))));
                }
            }
        }
    }

    // Inner vertices with |G| ≤ η move off zero (§2.1), all of one attempt in one batch.
    {
        const double h = tree.edge(tree.depth());
        std::vector<std::uint32_t> todo;
        for (std::uint32_t v = 0; v < n; ++v)
            if (std::abs(values[v]) <= options.eta) todo.push_back(v);
        stats.perturbed = todo.size();
        const std::vector<Vec3> original = [&] {
            std::vector<Vec3> o;
            for (std::uint32_t v : todo) o.push_back(mesh.vertices[v]);
            return o;
        }();
        std::vector<std::size_t> slot(todo.size());
        for (std::size_t i = 0; i < todo.size(); ++i) slot[i] = i;
        for (int k = 0; !todo.empty(); ++k) {
            if (k == max_perturbations) {
                throw NumericalFailure(fmt::format(
                    "G vanishes (|G| <= eta = {}) at and around {} after {} perturbations up to "
                    "{:.3g}: G and its gradient seem to vanish together, so the contour is "
                    "ill-posed there",
                    options.eta, place(original[slot.front()]), max_perturbations,
                    first_perturbation * std::ldexp(h, max_perturbations - 1)));
            }
            std::vector<Vec3> points;
            for (std::size_t i = 0; i < todo.size(); ++i) {
                const double step = first_perturbation * std::ldexp(h, k);
                points.push_back(original[slot[i]] + step * perturbation_direction(todo[i], k));
            }
            std::vector<double> got(points.size());
            tree_g(points, got);
            std::vector<std::uint32_t> left;
            std::vector<std::size_t> left_slot;
            for (std::size_t i = 0; i < todo.size(); ++i) {
                mesh.vertices[todo[i]] = points[i];
                values[todo[i]] = got[i];
                if (std::abs(got[i]) <= options.eta) {
                    left.push_back(todo[i]);
                    left_slot.push_back(slot[i]);
                }
            }
            todo = std::move(left);
            slot = std::move(left_slot);
        }
    }

    // Marching tetrahedra: a surface vertex on every edge where G changes sign, found once
    // for all the tetrahedra around the edge.
    KeyMap<std::uint32_t> on_edge;
    std::vector<Bracket3> brackets;
    auto vertex_on = [&](std::uint32_t a, std::uint32_t b) {
        if (a > b) std::swap(a, b);
        const auto [vertex, fresh] = on_edge.try_emplace(
            (std::uint64_t{a} << 32) | b, static_cast<std::uint32_t>(brackets.size()));
        if (fresh) brackets.push_back({mesh.vertices[a], mesh.vertices[b], values[a], values[b]});
        return *vertex;
    };
    // Triangles, and quadrilaterals to split once their vertices are known; both face G > 0.
    std::vector<TriangleIndices> triangles;
    std::vector<std::array<std::uint32_t, 4>> quads;
    for (const auto& t : mesh.tetrahedra) {
        int positive = 0;
        for (std::uint32_t v : t) positive += values[v] > 0.0 ? 1 : 0;
        if (positive == 0 || positive == 4) continue;
        if (positive == 1 || positive == 3) {
            // The vertex of the lone sign, i, and the others (j, k, l) in the orientation's
            // order: the triangle on edges ij, ik, il faces away from i.
            int i = 0;
            while ((values[t[i]] > 0.0) != (positive == 1)) ++i;
            const auto* o = others[i];
            const std::uint32_t a = vertex_on(t[i], t[o[0]]), b = vertex_on(t[i], t[o[1]]),
                                c = vertex_on(t[i], t[o[2]]);
            if (positive == 1)
                triangles.push_back({a, c, b});  // towards the positive vertex i
            else
                triangles.push_back({a, b, c});
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
        quads.push_back({vertex_on(t[p[0]], t[m[0]]), vertex_on(t[p[1]], t[m[0]]),
                         vertex_on(t[p[1]], t[m[1]]), vertex_on(t[p[0]], t[m[1]])});
    }
    {
        std::size_t root_evals = 0;
        const Evaluator root_g(g, root_evals);
        const std::vector<Root3> roots = find_roots(
            [&](std::span<const Vec3> points, std::span<double> got) { root_g(points, got); },
            brackets, RootOptions{.eta = options.eta, .method = options.root_method});
        stats.g_evals_roots = root_evals;
        out.surface.vertices.reserve(roots.size());
        for (const Root3& r : roots) {
            out.surface.vertices.push_back(r.point);
            if (!r.converged) ++stats.unconverged_roots;
        }
    }
    const auto& x = out.surface.vertices;
    for (const auto& q : quads) {
        // The shorter diagonal.
        if (distance(x[q[0]], x[q[2]]) <= distance(x[q[1]], x[q[3]])) {
            triangles.push_back({q[0], q[1], q[2]});
            triangles.push_back({q[0], q[2], q[3]});
        } else {
            triangles.push_back({q[1], q[2], q[3]});
            triangles.push_back({q[1], q[3], q[0]});
        }
    }
    out.surface.triangles = std::move(triangles);
    if (options.refine_passes != 0 && !out.surface.triangles.empty()) {
        const Evaluator refine_g(g, stats.g_evals_refine);
        const contouring::SurfaceRefinement r = contouring::refine_surface(
            out.surface, refine_g, options.resolved_eps(),
            RootOptions{.eta = options.eta, .method = options.root_method}, options.refine_passes,
            options.max_refine_passes, options.max_vertices);
        stats.passes = r.passes;
        stats.splits = r.splits;
        stats.rejected = r.rejected;
        stats.collapses = r.collapses;
        stats.flips = r.flips;
        stats.converged = r.converged != 0;
    }
    stats.triangles = out.surface.triangles.size();
    stats.vertices = out.surface.vertices.size();
    stats.g_evals = stats.g_evals_tree + stats.g_evals_roots + stats.g_evals_refine;
    stats.g_evals_per_vertex = stats.vertices == 0 ? 0.0
                                                   : static_cast<double>(stats.g_evals) /
                                                         static_cast<double>(stats.vertices);
    return out;
}

double SurfaceContourOptions::resolved_eps() const { return eps.value_or(std::pow(10.0, -depth)); }

}  // namespace slc
