// Topology resolution in space (paper §2.1 with d = 3, DESIGN §8): the octree split by min|G|
// against γ·edge with γ doubled until it is 2:1 balanced (tree_sampler.hpp, written once with the
// plane), thin cells split beyond K where G bends, its tetrahedral mesh with G at the vertices,
// the boundary check, perturbation of vertices where |G| ≤ η, and the tetrahedra where G changes
// sign.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "perturb.hpp"
#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/point_text.hpp"
#include "surface_stages.hpp"
#include "tree_sampler.hpp"

namespace slc::contouring {
namespace {

using Evaluator = SpaceEvaluator;

std::string place(Vec3 p) { return point_text(p, 6); }

/// The tree sampler of space (TreeSampler<3>: every cell samples its eight corners and its
/// centre), and what the tetrahedra need of it.
class SurfaceSampler : public TreeSampler<3> {
public:
    /// γ splits cells down to level `limit` (K); the tree may go deeper (thin cells).
    SurfaceSampler(const Octree& tree, const Evaluator& g, std::optional<SpaceBoundsRef> bounds,
                   std::optional<double> distance_slack, double rounding, double eta, int limit)
        : TreeSampler<3>(tree, g, bounds, distance_slack, rounding, eta, limit) {}

    /// The sample at a grid point (Tetrahedralization::key), or nullptr.
    const Sample* at(std::uint64_t key) const {
        const std::uint32_t* id = index_.find(key);
        return id ? &samples_[*id] : nullptr;
    }
    /// The sample at mesh vertex q of leaf c, or nullptr: c's own corners and centre are read
    /// from c, and a centre of a face that no finer cell touches (sides: c's finer_sides()) is
    /// no sample; other points are looked up.
    const Sample* at_vertex(std::uint32_t c, const std::array<std::uint32_t, 3>& q,
                            std::uint32_t sides) const {
        const auto& cell = tree_.cell(c);
        const std::uint64_t half = grid_.units(cell.level) / 2;
        // Where q lies in c, in half edges along each axis (0, 1 or 2), when it is on that grid;
        // on how many of c's sides (0 or 2 along an axis), and the last of them.
        std::array<std::uint64_t, 3> place{};
        int on_sides = 0, side = 0;
        for (int i = 0; i < 3; ++i) {
            const std::uint64_t offset = q[i] - cell.coords[i] * 2 * half;
            if (offset % half != 0) return at(Tetrahedralization::key(q[0], q[1], q[2]));
            place[i] = offset / half;
            if (place[i] != 1) ++on_sides, side = 2 * i + static_cast<int>(place[i] / 2);
        }
        if (on_sides == 3) {  // corner j of c: bit i of j high along axis i
            return &samples_[cell_samples_[c]
                                          [place[0] / 2 + 2 * (place[1] / 2) + 4 * (place[2] / 2)]];
        }
        if (on_sides == 0) return &samples_[cell_samples_[c][cell_points - 1]];
        if (on_sides == 1 && (sides >> side & 1u) == 0) return nullptr;
        return at(Tetrahedralization::key(q[0], q[1], q[2]));
    }
    /// Whether the samples of leaf c give G's sign at x, its centre tried first (the nearest to
    /// the points asked of it, the centres of c's faces).
    bool signed_by_donors(Vec3 x, std::uint32_t c) const {
        const CellSamples& ids = cell_samples_[c];
        const std::array<std::uint32_t, cell_points> centre_first{
            ids[cell_points - 1], ids[0], ids[1], ids[2], ids[3], ids[4], ids[5], ids[6], ids[7]};
        return TreeSampler<3>::signed_by_donors(x, centre_first);
    }
    /// A stand-in for G at x from the samples of leaf c, when they give its sign.
    std::optional<Sample> stand_in(Vec3 x, std::uint32_t c) const {
        return from_donors(x, cell_samples_[c]);
    }
    /// True when leaf c's tetrahedra are certain to hold no zero of G's interpolant and no
    /// vertex within η of zero, so that the contour needs none of them: c lies off the root
    /// box's boundary; its samples have one sign and |G| > η (a stand-in always has); no finer
    /// cell touches its edges or faces (sides: its finer_sides()), so its tetrahedra's vertices
    /// are its corners, its centre and its face centres; and c's samples give each face centre
    /// a stand-in of their sign. Without a distance slack (no stand-ins from samples), never.
    bool clear_of_zero(std::uint32_t c, double eta, std::uint32_t sides) const {
        if (sides != 0 || min_abs(c) <= eta || changes_sign(c)) return false;
        const auto& cell = tree_.cell(c);
        const std::uint64_t u = grid_.units(cell.level);
        SampleGrid<3>::Coords lo;
        for (int i = 0; i < 3; ++i) {
            lo[i] = cell.coords[i] * u;
            if (lo[i] == 0 || lo[i] + u == grid_.extent()) return false;
        }
        // c's samples have one sign, so a stand-in from them has it too: each face centre
        // needs one sample whose bound gives the sign, the nearest (the centre) tried first.
        for (int d = 0; d < 6; ++d) {
            const int a = d / 2;
            SampleGrid<3>::Coords p = lo;
            p[a] += (d & 1) * u;
            p[(a + 1) % 3] += u / 2;
            p[(a + 2) % 3] += u / 2;
            if (!signed_by_donors(grid_.point(p), c)) return false;
        }
        return true;
    }
};

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

/// G at the given vertices of the mesh, in one batch, made exact; ids is emptied.
void evaluate_at(SurfaceTopology& topo, const Evaluator& g, std::vector<std::uint32_t>& ids) {
    std::vector<Vec3> points;
    for (const std::uint32_t v : ids) points.push_back(topo.mesh.vertices[v]);
    std::vector<double> got(points.size());
    g(points, got);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        topo.values[ids[i]] = got[i];
        topo.exact[ids[i]] = 1;
    }
    ids.clear();
}

/// G at the mesh's vertices: the tree's samples, stand-ins from a leaf's samples for the face
/// centres whose sign they give, and one batch for the other face centres.
void mesh_values(SurfaceTopology& topo, const SurfaceSampler& sampler, const Evaluator& g,
                 std::span<const std::uint32_t> sides) {
    const auto& mesh = topo.mesh;
    const std::size_t n = mesh.vertices.size();
    topo.values.assign(n, 0.0);
    topo.exact.assign(n, 0);
    // Each vertex's stand-in comes from the leaf whose tetrahedra use it first, on all threads.
    std::vector<std::uint8_t> guessed(n, 0);
    const std::vector<std::uint32_t> leaves = topo.tree.leaves();
    parallel_for(leaves.size(), [&](std::size_t i) {
        const std::uint32_t c = leaves[i];
        for (std::uint32_t v = mesh.vertex_offsets[c]; v < mesh.vertex_offsets[c + 1]; ++v) {
            const Sample* s = sampler.at_vertex(c, mesh.grid[v], sides[c]);
            const std::optional<Sample> guess =
                s ? std::optional(*s) : sampler.stand_in(mesh.vertices[v], c);
            if (!guess) continue;
            topo.values[v] = guess->value;
            topo.exact[v] = guess->is_exact() ? 1 : 0;
            guessed[v] = 1;
        }
    });
    std::vector<std::uint32_t> ids;
    for (std::uint32_t v = 0; v < n; ++v)
        if (!guessed[v]) ids.push_back(v);
    evaluate_at(topo, g, ids);
}

/// The zero set may not reach the domain's boundary: a boundary vertex within η of zero, or a
/// sign change along an edge on the boundary, is LeftDomain. (On all threads: parallel_for
/// throws the first failure in order, as one thread would.)
void check_boundary(const SurfaceTopology& topo, double eta) {
    const auto& mesh = topo.mesh;
    const auto& values = topo.values;
    const auto extent = static_cast<std::uint32_t>(std::uint64_t{2} << topo.tree.max_depth());
    parallel_for(mesh.vertices.size(), [&](std::size_t v) {
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
}

/// Moves inner vertices with |G| ≤ η off zero (§2.1), all in the same direction.
std::size_t perturb(SurfaceTopology& topo, const Evaluator& g, double eta) {
    return perturb_vertices<3>(topo.mesh.vertices, topo.values, g, eta,
                               topo.tree.edge(topo.tree.depth()),
                               [](std::size_t, int k) { return perturbation_direction(k); });
}

/// The tetrahedra where G changes sign, in order, their corners' signs counted on all threads.
std::vector<std::uint32_t> crossing_tetrahedra(const SurfaceTopology& topo) {
    const auto& tetrahedra = topo.mesh.tetrahedra;
    std::vector<std::uint8_t> changes(tetrahedra.size());
    parallel_for(tetrahedra.size(), [&](std::size_t k) {
        int positive = 0;
        for (const std::uint32_t v : tetrahedra[k]) positive += topo.values[v] > 0.0 ? 1 : 0;
        changes[k] = positive != 0 && positive != 4 ? 1 : 0;
    });
    std::vector<std::uint32_t> list;
    for (std::size_t k = 0; k < changes.size(); ++k)
        if (changes[k]) list.push_back(static_cast<std::uint32_t>(k));
    return list;
}

constexpr std::uint32_t none_index = std::numeric_limits<std::uint32_t>::max();

/// Tries of move_across at most: each makes the contour's topology again.
constexpr int max_moves_tried = 64;

/// The components and handles of the linear contour that the signs at the mesh's vertices make
/// over the crossing tetrahedra (marching tetrahedra: a triangle where one corner differs, two
/// where two do). A component's vertices are the edges that change sign, and as a closed
/// surface its edges are half again its triangles: its Euler characteristic is its vertices
/// less half its triangles.
ShapeTopology linear_topology(const SurfaceTopology& topo,
                              std::span<const std::uint32_t> crossing) {
    KeyMap<std::uint32_t> id;
    id.reserve(2 * crossing.size());
    std::vector<std::uint32_t> parent;
    auto vertex = [&](std::uint32_t a, std::uint32_t b) {
        const auto [v, added] =
            id.try_emplace(edge_key(a, b), static_cast<std::uint32_t>(parent.size()));
        if (added) parent.push_back(*v);
        return *v;
    };
    auto root = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    auto join = [&](std::uint32_t a, std::uint32_t b) { parent[root(a)] = root(b); };
    std::vector<std::uint32_t> triangle_of;  // one vertex of each triangle
    for (const std::uint32_t k : crossing) {
        const auto& t = topo.mesh.tetrahedra[k];
        std::array<std::uint32_t, 4> in{}, out{};
        int ins = 0, outs = 0;
        for (const std::uint32_t v : t) {
            if (topo.values[v] > 0.0)
                out[outs++] = v;
            else
                in[ins++] = v;
        }
        if (ins == 1 || outs == 1) {
            const std::uint32_t lone = ins == 1 ? in[0] : out[0];
            const auto& rest = ins == 1 ? out : in;
            const std::uint32_t a = vertex(lone, rest[0]), b = vertex(lone, rest[1]),
                                c = vertex(lone, rest[2]);
            join(a, b), join(a, c);
            triangle_of.push_back(a);
        } else {
            const std::uint32_t a = vertex(in[0], out[0]), b = vertex(in[0], out[1]),
                                c = vertex(in[1], out[1]), d = vertex(in[1], out[0]);
            join(a, b), join(a, c), join(a, d);
            triangle_of.push_back(a), triangle_of.push_back(a);
        }
    }
    std::vector<long long> chi(parent.size(), 0);  // twice each component's, at its root
    for (std::uint32_t v = 0; v < parent.size(); ++v) chi[root(v)] += 2;
    for (const std::uint32_t v : triangle_of) chi[root(v)] -= 1;
    ShapeTopology out;
    for (std::uint32_t v = 0; v < parent.size(); ++v) {
        if (root(v) != v) continue;
        ++out.components;
        out.holes += (4 - chi[v]) / 4;  // genus 1 − χ/2, χ = chi[v] / 2
    }
    return out;
}

/// How far a contour's topology is from the shape's: the components and handles it differs by.
long long topology_gap(const ShapeTopology& a, const ShapeTopology& b) {
    return std::llabs(static_cast<long long>(a.components) - static_cast<long long>(b.components)) +
           std::llabs(a.holes - b.holes);
}

/// Moves mesh vertices within a sixteenth of the finest cell h of the zero set across it, where
/// the linear contour's topology differs from `shape` and that brings it nearer (keep_topology
/// in contour_options.hpp): only vertices that are not simple, those whose side changes the
/// contour's topology (the vertices of their link on the negative side do not make one disc),
/// nearest the zero set first, each moved along G's gradient (by differences) to G = ∓h/200
/// where the tetrahedra about it keep their orientation. All or nothing: returns the vertices
/// moved once the contour has the shape's topology, else puts them back (a part thinner than
/// the cells, not a sharp edge) and returns 0.
std::size_t move_across(SurfaceTopology& topo, const Evaluator& g, double eta,
                        const ShapeTopology& shape) {
    std::vector<std::uint32_t>& crossing = topo.crossing;
    ShapeTopology now = linear_topology(topo, crossing);
    if (now == shape) return 0;
    const double h = topo.tree.edge(topo.tree.depth());
    // The candidates: exact values within h/16 at the crossing tetrahedra's corners.
    std::vector<std::uint32_t> candidates;
    {
        std::vector<std::uint8_t> seen(topo.values.size(), 0);
        for (const std::uint32_t k : crossing) {
            for (const std::uint32_t v : topo.mesh.tetrahedra[k]) {
                if (seen[v]) continue;
                seen[v] = 1;
                if (topo.exact[v] && std::abs(topo.values[v]) <= h / 16.0) candidates.push_back(v);
            }
        }
    }
    std::sort(candidates.begin(), candidates.end(), [&](std::uint32_t a, std::uint32_t b) {
        const double x = std::abs(topo.values[a]), y = std::abs(topo.values[b]);
        return x < y || (x == y && a < b);
    });
    if (candidates.empty()) return 0;
    // The tetrahedra about each candidate.
    std::vector<std::uint32_t> place(topo.values.size(), none_index);
    for (std::uint32_t i = 0; i < candidates.size(); ++i) place[candidates[i]] = i;
    std::vector<std::vector<std::uint32_t>> star(candidates.size());
    for (std::uint32_t k = 0; k < topo.mesh.tetrahedra.size(); ++k)
        for (const std::uint32_t v : topo.mesh.tetrahedra[k])
            if (place[v] != none_index) star[place[v]].push_back(k);
    // The triangles of candidate i's link: each tetrahedron about it less it, corners in order.
    auto link = [&](std::uint32_t i) {
        std::vector<std::array<std::uint32_t, 3>> faces;
        for (const std::uint32_t k : star[i]) {
            std::array<std::uint32_t, 3> f{};
            int n = 0;
            for (const std::uint32_t u : topo.mesh.tetrahedra[k])
                if (u != candidates[i]) f[n++] = u;
            std::sort(f.begin(), f.end());
            faces.push_back(f);
        }
        return faces;
    };
    // Whether v is simple: the corners of its link on the negative side make one disc (one
    // component, Euler characteristic 1).
    auto simple = [&](std::uint32_t i) {
        const std::vector<std::array<std::uint32_t, 3>> faces = link(i);
        std::vector<std::uint32_t> corners;
        for (const auto& f : faces) corners.insert(corners.end(), f.begin(), f.end());
        std::sort(corners.begin(), corners.end());
        corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
        auto negative = [&](std::uint32_t u) { return !(topo.values[u] > 0.0); };
        std::vector<std::uint32_t> up(corners.size());
        for (std::uint32_t j = 0; j < up.size(); ++j) up[j] = j;
        auto at = [&](std::uint32_t u) {
            return static_cast<std::uint32_t>(std::lower_bound(corners.begin(), corners.end(), u) -
                                              corners.begin());
        };
        auto top = [&](std::uint32_t j) {
            while (up[j] != j) j = up[j] = up[up[j]];
            return j;
        };
        std::vector<std::uint64_t> edges;
        long long chi = 0;
        for (const std::uint32_t u : corners) chi += negative(u) ? 1 : 0;
        for (const auto& f : faces) {
            if (negative(f[0]) && negative(f[1]) && negative(f[2])) ++chi;
            for (int a = 0; a < 3; ++a) {
                for (int b = a + 1; b < 3; ++b) {
                    if (!negative(f[a]) || !negative(f[b])) continue;
                    edges.push_back(edge_key(f[a], f[b]));
                    up[top(at(f[a]))] = top(at(f[b]));
                }
            }
        }
        std::sort(edges.begin(), edges.end());
        chi -= static_cast<long long>(std::unique(edges.begin(), edges.end()) - edges.begin());
        std::size_t parts = 0;
        for (std::uint32_t j = 0; j < corners.size(); ++j)
            if (negative(corners[j]) && top(j) == j) ++parts;
        return parts == 1 && chi == 1;
    };
    // Whether the tetrahedra about candidate i close round it (its link is a closed surface, each
    // edge in two of its triangles): a vertex beside a leaf left out of the mesh (clear of the
    // zero set) is not moved, since that leaf's tetrahedra would cross it.
    auto closed_round = [&](std::uint32_t i) {
        std::vector<std::uint64_t> edges;
        for (const auto& f : link(i)) {
            edges.push_back(edge_key(f[0], f[1]));
            edges.push_back(edge_key(f[1], f[2]));
            edges.push_back(edge_key(f[0], f[2]));
        }
        std::sort(edges.begin(), edges.end());
        for (std::size_t j = 0; j < edges.size(); j += 2)
            if (j + 1 >= edges.size() || edges[j] != edges[j + 1] ||
                (j + 2 < edges.size() && edges[j + 2] == edges[j]))
                return false;
        return !edges.empty();
    };
    // G's gradient at the candidates, by central differences, one batch.
    const double step = 1e-3 * h;
    std::vector<Vec3> points;
    for (const std::uint32_t v : candidates) {
        for (int a = 0; a < 3; ++a) {
            for (const double sign : {1.0, -1.0}) {
                Vec3 p = topo.mesh.vertices[v];
                p[a] += sign * step;
                points.push_back(p);
            }
        }
    }
    std::vector<double> values(points.size());
    g(points, values);
    std::vector<Vec3> target(candidates.size());
    std::vector<std::uint8_t> can(candidates.size(), 0);
    for (std::uint32_t i = 0; i < candidates.size(); ++i) {
        const Vec3 grad{(values[6 * i] - values[6 * i + 1]) / (2 * step),
                        (values[6 * i + 2] - values[6 * i + 3]) / (2 * step),
                        (values[6 * i + 4] - values[6 * i + 5]) / (2 * step)};
        const double n2 = norm2(grad);
        if (!(n2 > 0.25)) continue;  // G is a distance near its zero set: |∇G| near 1
        const double x = topo.values[candidates[i]];
        const double want = (x > 0.0 ? -1.0 : 1.0) * h / 200.0;
        target[i] = topo.mesh.vertices[candidates[i]] + ((want - x) / n2) * grad;
        if (distance(target[i], topo.mesh.vertices[candidates[i]]) > h / 10.0 || !closed_round(i))
            continue;
        can[i] = 1;
    }
    // Whether the tetrahedra about candidate i keep their orientation with it at its target (and
    // the vertices moved before it where they are now).
    auto keeps_orientation = [&](std::uint32_t i) {
        for (const std::uint32_t k : star[i]) {
            std::array<Vec3, 4> q;
            for (int j = 0; j < 4; ++j) {
                const std::uint32_t u = topo.mesh.tetrahedra[k][j];
                q[j] = u == candidates[i] ? target[i] : topo.mesh.vertices[u];
            }
            if (!(dot(q[1] - q[0], cross(q[2] - q[0], q[3] - q[0])) > 0.0)) return false;
        }
        return true;
    };
    std::vector<Vec3> at_target;
    for (std::uint32_t i = 0; i < candidates.size(); ++i)
        if (can[i]) at_target.push_back(target[i]);
    std::vector<double> there(at_target.size());
    g(at_target, there);
    struct Undo {
        std::uint32_t vertex;
        Vec3 point;
        double value;
    };
    std::vector<Undo> undo;
    std::size_t next = 0;
    int tried = 0;
    for (std::uint32_t i = 0; i < candidates.size() && !(now == shape) && tried < max_moves_tried;
         ++i) {
        if (!can[i]) continue;
        const double value = there[next++];
        const std::uint32_t v = candidates[i];
        if ((value > 0.0) == (topo.values[v] > 0.0) || !(std::abs(value) > eta) || simple(i) ||
            !keeps_orientation(i))
            continue;
        ++tried;
        const Vec3 was = topo.mesh.vertices[v];
        const double was_value = topo.values[v];
        topo.mesh.vertices[v] = target[i];
        topo.values[v] = value;
        crossing = crossing_tetrahedra(topo);
        const ShapeTopology after = linear_topology(topo, crossing);
        if (topology_gap(after, shape) < topology_gap(now, shape)) {
            now = after;
            undo.push_back({v, was, was_value});
        } else {
            topo.mesh.vertices[v] = was;
            topo.values[v] = was_value;
        }
    }
    // All or nothing: short of the shape (a wall thinner than the cells, not a sharp edge), the
    // contour is the signs' own.
    if (!(now == shape)) {
        for (auto it = undo.rbegin(); it != undo.rend(); ++it) {
            topo.mesh.vertices[it->vertex] = it->point;
            topo.values[it->vertex] = it->value;
        }
        undo.clear();
    }
    if (tried > 0) crossing = crossing_tetrahedra(topo);  // of the vertices as they are now
    return undo.size();
}

/// Stand-ins at the corners of the crossing tetrahedra give way to G, for the roots' brackets;
/// their signs are G's, so the tetrahedra stay the same.
void evaluate_crossed_stand_ins(SurfaceTopology& topo, const Evaluator& g) {
    std::vector<std::uint32_t> ids;
    for (const std::uint32_t k : topo.crossing) {
        for (const std::uint32_t v : topo.mesh.tetrahedra[k]) {
            if (!topo.exact[v]) {
                topo.exact[v] = 1;  // about to be
                ids.push_back(v);
            }
        }
    }
    evaluate_at(topo, g, ids);
}

}  // namespace

SurfaceTopology resolve_surface_topology(const SpaceEvaluator& g, const Box3& domain,
                                         const SurfaceContourOptions& options,
                                         std::optional<SpaceBoundsRef> bounds) {
    const double eta = options.resolved_eta();
    const int thin_depth =
        thin_levels<3>(domain, options.depth, options.thin_depth, max_tetrahedralized_depth);
    SurfaceTopology topo(Octree(domain, options.depth + thin_depth));
    // The slack and the bounds allow for rounding in G too: a few thousand ulps of the domain's
    // coordinates.
    const double rounding = 1e-12 * std::max(domain.largest_magnitude(), domain.width());
    SurfaceSampler sampler(topo.tree, g, bounds, options.distance_slack, rounding, eta,
                           options.depth);
    topo.gamma = build_tree(topo.tree, sampler, options.gamma);
    const ThinSplit thin = split_thin(topo.tree, sampler, topo.gamma);
    topo.thin_cells = thin.cells;
    topo.thin_budget_reached = thin.budget_reached;
    topo.settled = sampler.settled();
    topo.bound_evals = sampler.bound_evals();
    // Only the leaves the zero set may meet are tetrahedralized: far from the surface a tree
    // has many leaves (about four in five of a torus's at K = 7), none of whose tetrahedra the
    // contour needs. The crossing tetrahedra, their vertices and values are the same as over
    // every leaf.
    const std::vector<std::uint32_t> sides = finer_sides(topo.tree);
    std::vector<std::uint8_t> wanted(topo.tree.size(), 0);
    parallel_for(topo.tree.size(), [&](std::size_t c) {
        const auto cell = static_cast<std::uint32_t>(c);
        wanted[c] = topo.tree.is_leaf(cell) && !sampler.clear_of_zero(cell, eta, sides[c]) ? 1 : 0;
    });
    topo.mesh = tetrahedralize(topo.tree, wanted, sides);
    mesh_values(topo, sampler, g, sides);
    check_boundary(topo, eta);
    topo.perturbed = perturb(topo, g, eta);
    topo.crossing = crossing_tetrahedra(topo);
    if (options.keep_topology)
        topo.moved_across = move_across(topo, g, eta, *options.keep_topology);
    evaluate_crossed_stand_ins(topo, g);
    return topo;
}

}  // namespace slc::contouring
