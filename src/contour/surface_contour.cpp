// contour_surface(): topology resolution in space (paper §2.1 with d = 3) — the octree split by
// min|G| against γ·edge with γ doubled until it is 2:1 balanced (tree_sampler.hpp, written once
// with the plane), thin cells split beyond K where G bends, its tetrahedral mesh, G at the
// mesh vertices, perturbation of vertices where |G| ≤ η, the boundary check — and marching
// tetrahedra with roots on the tetrahedra's edges.
#include "slc/contour/surface_contour.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/geometry/triangle3.hpp"
#include "slc/tree/orthtree.hpp"
#include "slc/tree/tetrahedralization.hpp"
#include "surface_stages.hpp"
#include "tree_sampler.hpp"

namespace slc {
namespace {

/// Perturbation: the first displacement is this fraction of the finest cell edge, doubled at each
/// attempt; after max_perturbations attempts it is 3.2% of that edge, well below the smallest
/// altitude of the mesh's tetrahedra (an eighth of the finest edge), so the mesh stays valid.
constexpr double first_perturbation = 1e-3;
constexpr int max_perturbations = 6;
/// A cell's G bends (SurfaceSampler::bends) when a body diagonal's centre is nearer zero than its
/// ends' mean by this fraction of the half-diagonal.
constexpr double thin_dip = 0.25;

std::string place(Vec3 p) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", p.x, p.y, p.z); }

void validate(const SurfaceContourOptions& o, const Box3& domain) {
    auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
    if (o.depth < 0 || o.depth > max_tetrahedralized_depth) {
        throw InvalidInput(fmt::format("contour depth K must be between 0 and {}, got {}",
                                       max_tetrahedralized_depth, o.depth));
    }
    if (o.eta && !positive(*o.eta))
        throw InvalidInput(fmt::format("eta must be positive, got {}", *o.eta));
    if (!positive(o.gamma))
        throw InvalidInput(fmt::format("gamma must be positive, got {}", o.gamma));
    if (o.thin_depth < 0) {
        throw InvalidInput(
            fmt::format("thin cells' extra depth must be >= 0, got {}", o.thin_depth));
    }
    if (o.refine_passes < 0 && o.refine_passes != SurfaceContourOptions::until_converged) {
        throw InvalidInput(
            fmt::format("refinement passes P must be >= 0, got {}", o.refine_passes));
    }
    if (o.distance_slack && !(*o.distance_slack >= 0.0 && std::isfinite(*o.distance_slack))) {
        throw InvalidInput(
            fmt::format("distance slack must be >= 0 and finite, got {}", *o.distance_slack));
    }
    if (o.eps && (!positive(*o.eps) || *o.eps < o.resolved_eta())) {
        throw InvalidInput(
            fmt::format("eps must be at least eta = {}, got {}", o.resolved_eta(), *o.eps));
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

/// What a cell's samples say of G bending within it (SurfaceSampler::bends).
enum class Bend { no, yes, unsure };

using contouring::Sample;

/// The tree sampler of space (TreeSampler<3>: every cell samples its eight corners and its
/// centre), and what thin cells and the tetrahedra need of it.
class SurfaceSampler : public contouring::TreeSampler<3> {
public:
    /// γ splits cells down to level `limit` (K); the tree may go deeper (thin cells).
    SurfaceSampler(const Octree& tree, const Evaluator& g, std::optional<double> distance_slack,
                   double rounding, double eta, int limit)
        : TreeSampler<3>(tree, g, std::nullopt, distance_slack, rounding, eta, limit) {}

    /// Whether G bends within cell c: along a body diagonal, the ends and the centre of one sign
    /// and the centre nearer zero than the ends' mean by more than thin_dip of the
    /// half-diagonal. A distance is linear along a segment on one side of a plane and bends by
    /// about h²/(2R) near a sheet of radius R: a dip this large means the sheet turns within the
    /// cell or its other side is there too. Only cells the zero set may meet are tested (the
    /// centre's |G| at most the half-diagonal). From the samples' bounds: unsure when stand-ins
    /// leave it open, and then the stand-ins that would settle it are appended to `wanted`.
    Bend bends(std::uint32_t c, std::vector<std::uint32_t>& wanted) const {
        const CellSamples& ids = cell_samples_[c];
        const Sample& m = samples_[ids[8]];
        const double half_diagonal = 0.5 * std::sqrt(3.0) * tree_.edge(tree_.cell(c).level);
        if (std::abs(m.value) > half_diagonal) return Bend::no;
        if (m.upper > half_diagonal) {
            wanted.push_back(ids[8]);
            return Bend::unsure;
        }
        const double threshold = thin_dip * half_diagonal;
        bool unsure = false;
        for (int k = 0; k < 4; ++k) {
            const Sample& a = samples_[ids[k]];
            const Sample& b = samples_[ids[7 - k]];
            if ((a.value > 0.0) != (m.value > 0.0) || (b.value > 0.0) != (m.value > 0.0)) continue;
            // |G| ≥ |value| and ≤ upper at each point, with the value's sign.
            const double least = 0.5 * (std::abs(a.value) + std::abs(b.value)) - m.upper;
            const double most = 0.5 * (a.upper + b.upper) - std::abs(m.value);
            if (least > threshold) return Bend::yes;
            if (!(most > threshold)) continue;
            unsure = true;
            for (const std::uint32_t id : {ids[k], ids[7 - k], ids[8]})
                if (!samples_[id].is_exact()) wanted.push_back(id);
        }
        return unsure ? Bend::unsure : Bend::no;
    }

    /// Makes G exact at the given points (from bends), in one batch, and updates the least |G|
    /// of the given cells.
    void make_exact(std::vector<std::uint32_t> ids, std::span<const std::uint32_t> cells) {
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        for (std::uint32_t id : ids) samples_[id] = contouring::pending;
        evaluate(ids);
        for (std::uint32_t c : cells) update_min(c);
    }
    /// Tree points with a stand-in rather than G.
    std::size_t settled() const {
        return static_cast<std::size_t>(std::count_if(
            samples_.begin(), samples_.end(), [](const Sample& s) { return !s.is_exact(); }));
    }
    /// The sample at a grid point (Tetrahedralization::key), or nullptr.
    const Sample* at(std::uint64_t key) const {
        const std::uint32_t* id = index_.find(key);
        return id ? &samples_[*id] : nullptr;
    }
    /// A stand-in for G at x from the samples of leaf c, when they give its sign.
    std::optional<Sample> stand_in(Vec3 x, std::uint32_t c) const {
        return from_donors(x, donors_of(cell_samples_[c]));
    }
};

/// Splits the leaves at level `limit` near the zero set (min|G| below γ times their edge) where G
/// bends within them (SurfaceSampler::bends), and their children where it still does, down to the
/// tree's deepest level; then balances the tree again, sampling the cells balancing makes.
/// Returns the cells split.
std::size_t split_thin(Octree& tree, SurfaceSampler& sampler, double gamma, int limit) {
    std::vector<std::uint32_t> frontier;
    for (std::uint32_t c : tree.leaves())
        if (tree.cell(c).level == limit && gamma * tree.edge(limit) > sampler.min_abs(c))
            frontier.push_back(c);
    std::size_t split = 0;
    while (!frontier.empty() && tree.cell(frontier.front()).level < tree.max_depth()) {
        // Stand-ins that leave a cell unsure are evaluated, a batch a round, until none does;
        // the cells that bend split in the frontier's order.
        std::vector<std::uint32_t> bent, unsure = frontier;
        while (!unsure.empty()) {
            std::vector<std::uint32_t> wanted, still;
            for (std::uint32_t c : unsure) {
                const Bend b = sampler.bends(c, wanted);
                if (b == Bend::yes) bent.push_back(c);
                if (b == Bend::unsure) still.push_back(c);
            }
            sampler.make_exact(std::move(wanted), still);
            unsure = std::move(still);
        }
        std::sort(bent.begin(), bent.end());
        std::vector<std::uint32_t> next;
        for (std::uint32_t c : bent) {
            const std::uint32_t first = tree.split(c);
            for (std::uint32_t k = 0; k < 8; ++k) next.push_back(first + k);
            ++split;
        }
        sampler.sample(next);
        frontier.clear();
        for (std::uint32_t c : next)
            if (gamma * tree.edge(tree.cell(c).level) > sampler.min_abs(c)) frontier.push_back(c);
    }
    if (split > 0 && !tree.is_balanced()) {
        const auto before = static_cast<std::uint32_t>(tree.size());
        tree.balance();
        std::vector<std::uint32_t> made(tree.size() - before);
        std::iota(made.begin(), made.end(), before);
        sampler.sample(made);
    }
    return split;
}

/// The direction of attempt k, the same for every vertex: golden-ratio sequences on the sphere.
/// One direction for all makes the perturbed values those of G shifted as a whole, so vertices
/// on a face or a sharp edge of the zero set all move to the same side of it; directions drawn
/// vertex by vertex could leave one on the other side from all its neighbours, a speck of zero
/// set around it.
Vec3 perturbation_direction(int k) {
    const double phi = 0.6180339887498949, silver = 0.4142135623730950;
    const double plastic = 0.7548776662466927, bronze = 0.3027756377319946;
    auto frac = [](double x) { return x - std::floor(x); };
    const double z = 2.0 * frac(phi + k * silver) - 1.0;
    const double angle = 2.0 * std::numbers::pi * frac(plastic + k * bronze);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(angle), r * std::sin(angle), z};
}

/// True when grid point p lies on the root box's boundary (at 0 or the grid's extent).
bool on_boundary(const std::array<std::uint32_t, 3>& p, std::uint32_t extent) {
    for (std::uint32_t x : p)
        if (x == 0 || x == extent) return true;
    return false;
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

}  // namespace

SurfaceContour contour_surface(SpaceFunctionRef g, const Box3& domain,
                               const SurfaceContourOptions& options) {
    validate(options, domain);
    const double eta = options.resolved_eta();
    SurfaceContour out;
    SurfaceContourStats& stats = out.stats;
    const Evaluator tree_g(g, stats.g_evals_tree);
    const int thin_depth = std::min(options.thin_depth, max_tetrahedralized_depth - options.depth);
    Octree tree(domain, options.depth + thin_depth);
    // The slack allows for rounding in G too: a few thousand ulps of the domain's coordinates.
    const double rounding = 1e-12 * std::max(domain.largest_magnitude(), domain.width());
    SurfaceSampler sampler(tree, tree_g, options.distance_slack, rounding, eta, options.depth);
    stats.gamma = contouring::build_tree(tree, sampler, options.gamma);
    stats.thin_cells = split_thin(tree, sampler, stats.gamma, options.depth);
    stats.cells = tree.size();
    stats.leaves = tree.leaves().size();
    stats.settled = sampler.settled();

    // G at the mesh's vertices: the tree's samples, stand-ins from a leaf's samples for the face
    // centres whose sign they give, and one batch for the other face centres.
    Tetrahedralization mesh = tetrahedralize(tree);
    stats.tetrahedra = mesh.tetrahedra.size();
    const std::size_t n = mesh.vertices.size();
    std::vector<double> values(n);
    std::vector<std::uint8_t> exact(n, 0);
    // G at the given vertices, in one batch.
    auto evaluate_at = [&](std::vector<std::uint32_t>& ids) {
        std::vector<Vec3> points;
        for (const std::uint32_t v : ids) points.push_back(mesh.vertices[v]);
        std::vector<double> got(points.size());
        tree_g(points, got);
        for (std::size_t i = 0; i < ids.size(); ++i) {
            values[ids[i]] = got[i];
            exact[ids[i]] = 1;
        }
        ids.clear();
    };
    {
        // Each vertex's stand-in comes from the leaf whose tetrahedra use it first, on all
        // threads.
        std::vector<std::uint8_t> guessed(n, 0);
        const std::vector<std::uint32_t> leaves = tree.leaves();
        parallel_for(leaves.size(), [&](std::size_t i) {
            const std::uint32_t c = leaves[i];
            for (std::uint32_t v = mesh.vertex_offsets[c]; v < mesh.vertex_offsets[c + 1]; ++v) {
                const auto& q = mesh.grid[v];
                const Sample* s = sampler.at(Tetrahedralization::key(q[0], q[1], q[2]));
                const std::optional<Sample> guess =
                    s ? std::optional(*s) : sampler.stand_in(mesh.vertices[v], c);
                if (!guess) continue;
                values[v] = guess->value;
                exact[v] = guess->is_exact() ? 1 : 0;
                guessed[v] = 1;
            }
        });
        std::vector<std::uint32_t> ids;
        for (std::uint32_t v = 0; v < n; ++v)
            if (!guessed[v]) ids.push_back(v);
        evaluate_at(ids);
    }

    // The zero set may not reach the domain's boundary: a boundary vertex within η of zero, or
    // a sign change along an edge on the boundary, is LeftDomain.
    // (On all threads: parallel_for throws the first failure in order, as one thread would.)
    const auto extent = static_cast<std::uint32_t>(std::uint64_t{2} << tree.max_depth());
    parallel_for(n, [&](std::size_t v) {
        if (on_boundary(mesh.grid[v], extent) && std::abs(values[v]) <= eta) {
            throw LeftDomain(
                fmt::format("the contour reaches the domain boundary near {}; enlarge the domain "
                            "(--domain, --box)",
                            place(mesh.vertices[v])));
        }
    });
    parallel_for(mesh.tetrahedra.size(), [&](std::size_t k) {
        const auto& t = mesh.tetrahedra[k];
        for (int i = 0; i < 4; ++i) {
            for (int j = i + 1; j < 4; ++j) {
                const auto& p = mesh.grid[t[i]];
                const auto& q = mesh.grid[t[j]];
                bool same_face = false;
                for (int a = 0; a < 3; ++a)
                    same_face |= p[a] == q[a] && (p[a] == 0 || p[a] == extent);
                if (same_face && (values[t[i]] > 0.0) != (values[t[j]] > 0.0)) {
                    throw LeftDomain(
                        fmt::format("the contour crosses the domain boundary near {}; enlarge the "
                                    "domain (--domain, --box)",
                                    place(0.5 * (mesh.vertices[t[i]] + mesh.vertices[t[j]]))));
                }
            }
        }
    });

    // Inner vertices with |G| ≤ η move off zero (§2.1), all of one attempt in one batch.
    {
        const double h = tree.edge(tree.depth());
        std::vector<std::uint32_t> todo;
        for (std::uint32_t v = 0; v < n; ++v)
            if (std::abs(values[v]) <= eta) todo.push_back(v);
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
                    eta, place(original[slot.front()]), max_perturbations,
                    first_perturbation * std::ldexp(h, max_perturbations - 1)));
            }
            std::vector<Vec3> points;
            for (std::size_t i = 0; i < todo.size(); ++i) {
                const double step = first_perturbation * std::ldexp(h, k);
                points.push_back(original[slot[i]] + step * perturbation_direction(k));
            }
            std::vector<double> got(points.size());
            tree_g(points, got);
            std::vector<std::uint32_t> left;
            std::vector<std::size_t> left_slot;
            for (std::size_t i = 0; i < todo.size(); ++i) {
                mesh.vertices[todo[i]] = points[i];
                values[todo[i]] = got[i];
                if (std::abs(got[i]) <= eta) {
                    left.push_back(todo[i]);
                    left_slot.push_back(slot[i]);
                }
            }
            todo = std::move(left);
            slot = std::move(left_slot);
        }
    }

    // The tetrahedra where G changes sign, in order, their corners' signs counted on all threads.
    const std::vector<std::uint32_t> crossing = [&] {
        std::vector<std::uint8_t> changes(mesh.tetrahedra.size());
        parallel_for(mesh.tetrahedra.size(), [&](std::size_t k) {
            int positive = 0;
            for (const std::uint32_t v : mesh.tetrahedra[k]) positive += values[v] > 0.0 ? 1 : 0;
            changes[k] = positive != 0 && positive != 4 ? 1 : 0;
        });
        std::vector<std::uint32_t> list;
        for (std::size_t k = 0; k < changes.size(); ++k)
            if (changes[k]) list.push_back(static_cast<std::uint32_t>(k));
        return list;
    }();
    // Stand-ins at the corners of those tetrahedra give way to G, for the roots' brackets; their
    // signs are G's, so the tetrahedra stay the same.
    {
        std::vector<std::uint32_t> ids;
        for (const std::uint32_t k : crossing) {
            const auto& t = mesh.tetrahedra[k];
            for (const std::uint32_t v : t) {
                if (!exact[v]) {
                    exact[v] = 1;  // about to be
                    ids.push_back(v);
                }
            }
        }
        evaluate_at(ids);
    }

    // Marching tetrahedra: a surface vertex on every edge where G changes sign, found once
    // for all the tetrahedra around the edge (fewer edges than tetrahedra: each is shared).
    KeyMap<std::uint32_t> on_edge(crossing.size());
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
    for (const std::uint32_t tet : crossing) {
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
            brackets, RootOptions{.eta = eta, .method = options.root_method});
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
    // Beside a convex corner, where thin cells are finer than their neighbours, a mesh vertex
    // just inside the corner can have no neighbour inside: the linear zero set closes a speck
    // around it, apart from the rest of the corner. A component less than a finest cell across
    // is below what the mesh resolves: dropped (only where cells went beyond K).
    if (stats.thin_cells > 0) stats.specks = drop_specks(out.surface, tree.edge(tree.depth()));
    if (options.refine_passes != 0 && !out.surface.triangles.empty()) {
        const Evaluator refine_g(g, stats.g_evals_refine);
        const contouring::SurfaceRefinement r = contouring::refine_surface(
            out.surface, refine_g, options.resolved_eps(),
            RootOptions{.eta = eta, .method = options.root_method}, options.refine_passes,
            options.max_refine_passes, options.max_vertices);
        stats.passes = r.passes;
        stats.splits = r.splits;
        stats.rejected = r.rejected;
        stats.collapses = r.collapses;
        stats.flips = r.flips;
        stats.converged = r.converged != 0;
        stats.residual = r.residual;
    }
    stats.triangles = out.surface.triangles.size();
    stats.vertices = out.surface.vertices.size();
    stats.g_evals = stats.g_evals_tree + stats.g_evals_roots + stats.g_evals_refine;
    stats.g_evals_per_vertex = stats.vertices == 0 ? 0.0
                                                   : static_cast<double>(stats.g_evals) /
                                                         static_cast<double>(stats.vertices);
    return out;
}

double SurfaceContourOptions::resolved_eta() const {
    if (eta) return *eta;
    return refine_passes == 0 ? default_eta : std::max(default_eta, resolved_eps() / 100.0);
}

double SurfaceContourOptions::resolved_eps() const { return eps.value_or(std::pow(10.0, -depth)); }

}  // namespace slc
