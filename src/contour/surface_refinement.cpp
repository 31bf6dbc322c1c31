// Adaptive refinement of a contoured surface (paper §2.2 in space): edges split where G at their
// midpoint (or at a triangle's centroid) exceeds ε, the new vertex the root of G along the normal,
// with safeguards that keep the surface closed, manifold, oriented and free of crossings.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/stop.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "surface_stages.hpp"

namespace slc::contouring {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t{a} << 32) | b;
}

Edges::Edges(const Surface& s) {
    const HalfEdgeBuckets buckets = half_edges_by_lower_vertex(s);
    const std::size_t vertices = s.vertices.size();
    // The edges of a closed surface pair its half-edges, so vertex v numbers
    // (start[v + 1] − start[v]) / 2 edges, from first_of[v].
    first_of.assign(vertices + 1, 0);
    for (std::size_t v = 0; v < vertices; ++v) {
        const std::uint32_t halves = buckets.start[v + 1] - buckets.start[v];
        SLC_ASSERT(halves % 2 == 0, "every edge of a closed surface has two triangles");
        first_of[v + 1] = first_of[v] + halves / 2;
    }
    of_triangle.resize(s.size());
    ends.resize(first_of[vertices]);
    triangles.resize(first_of[vertices]);
    // Each vertex's edges in order of their other end, on all threads: the same numbering
    // as one thread gives.
    parallel_for(vertices, [&](std::size_t v) {
        const auto first = buckets.halves.begin() + buckets.start[v],
                   last = buckets.halves.begin() + buckets.start[v + 1];
        std::uint32_t e = first_of[v];
        for (auto it = first; it != last; it += 2, ++e) {
            SLC_ASSERT(it->first == (it + 1)->first,
                       "every edge of a closed surface has two triangles");
            const std::uint32_t h = it->second, k = (it + 1)->second;
            ends[e] = {static_cast<std::uint32_t>(v), it->first};
            triangles[e] = {h / 3, k / 3};
            of_triangle[h / 3][h % 3] = e;
            of_triangle[k / 3][k % 3] = e;
        }
    });
}

std::optional<std::uint32_t> Edges::find(std::uint32_t a, std::uint32_t b) const {
    if (a > b) std::swap(a, b);
    const auto begin = ends.begin() + first_of[a], end = ends.begin() + first_of[a + 1];
    const auto at =
        std::lower_bound(begin, end, b, [](const auto& ab, std::uint32_t x) { return ab[1] < x; });
    if (at == end || (*at)[1] != b) return std::nullopt;
    return static_cast<std::uint32_t>(at - ends.begin());
}

Vec3 area_normal(const Surface& s, const TriangleIndices& t) {
    const Vec3 a = s.vertices[t[0]];
    return cross(s.vertices[t[1]] - a, s.vertices[t[2]] - a);
}

// The triangles that replace t = (v0, v1, v2) when the edges flagged in `split` (bit k: edge
// from corner k to corner k + 1) get the vertices w[k], oriented as t.
void split_children(const Surface& s, const TriangleIndices& t, unsigned split,
                    const std::array<std::uint32_t, 3>& w, std::vector<TriangleIndices>& out,
                    bool other_diagonal) {
    const int count = std::popcount(split);
    if (count == 0) {
        out.push_back(t);
        return;
    }
    if (count == 3) {
        out.push_back({t[0], w[0], w[2]});
        out.push_back({w[0], t[1], w[1]});
        out.push_back({w[2], w[1], t[2]});
        out.push_back({w[0], w[1], w[2]});
        return;
    }
    if (count == 1) {
        const int k = std::countr_zero(split);
        out.push_back({t[k], w[k], t[(k + 2) % 3]});
        out.push_back({w[k], t[(k + 1) % 3], t[(k + 2) % 3]});
        return;
    }
    // Two: edges k and k + 1 split, edge k + 2 whole. The corner at k + 1 is cut off, and the
    // quadrilateral left is split along its shorter diagonal (or the other).
    const int k = (split & 1u) == 0 ? 1 : ((split & 2u) == 0 ? 2 : 0);
    const std::uint32_t a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
    const std::uint32_t p = w[k], q = w[(k + 1) % 3];
    out.push_back({p, b, q});
    const auto& x = s.vertices;
    if ((distance(x[a], x[q]) <= distance(x[p], x[c])) != other_diagonal) {
        out.push_back({a, p, q});
        out.push_back({a, q, c});
    } else {
        out.push_back({a, p, c});
        out.push_back({p, q, c});
    }
}

namespace {

/// A child triangle may turn at most this far from its parent (cos 60°).
constexpr double min_normal_cosine = 0.5;
/// Brackets reach this far along the normal, in edge lengths: ½, 1, then 2.
constexpr double bracket_reach[] = {0.5, 1.0, 2.0};

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
/// The first index of a triangle a collapse removed, until improve() drops it.
constexpr std::uint32_t dead = std::numeric_limits<std::uint32_t>::max();

/// The vertices opposite edge e in its two triangles, as one key.
std::uint64_t opposite_key(const Surface& s, const Edges& edges, std::uint32_t e) {
    auto opposite = [&](std::uint32_t t) {
        for (const std::uint32_t v : s.triangles[t])
            if (v != edges.ends[e][0] && v != edges.ends[e][1]) return v;
        return std::uint32_t{0};
    };
    const auto [t0, t1] = edges.triangles[e];
    return edge_key(opposite(t0), opposite(t1));
}

/// The normal of the surface around triangle t: the area-weighted normals of t and of its three
/// neighbours summed. A needle or a cap has a normal of no meaning; its neighbours give one.
Vec3 normal_around(const Surface& s, const Edges& edges, std::uint32_t t) {
    Vec3 n = area_normal(s, s.triangles[t]);
    for (const std::uint32_t e : edges.of_triangle[t]) {
        const auto [t0, t1] = edges.triangles[e];
        n += area_normal(s, s.triangles[t0 == t ? t1 : t0]);
    }
    return n;
}

/// True when triangle `now` has area and turns less than the angle of `cosine` from n.
bool along(const Surface& s, Vec3 n, const TriangleIndices& now, double cosine) {
    const Vec3 m = area_normal(s, now);
    const double mm = norm(m), nn = norm(n);
    if (!(mm > 0.0)) return false;
    // Area normals are squares of lengths, their products fourth powers: beyond 2^±900 (a
    // surface below 1e−68 or above 1e68) the unit normals' product, which neither underflows
    // nor overflows.
    const double scale = nn * mm;
    if (scale >= 0x1p-900 && scale <= 0x1p900) return dot(n, m) > cosine * scale;
    return dot(n / nn, m / mm) > cosine;
}

/// Following creases, a child may also turn this far from its parent itself (cos 30°), or,
/// when the parent is split where a crease crosses it, this far (cos 84°).
constexpr double min_parent_cosine = 0.866;
constexpr double min_crease_cosine = 0.1;

/// True when every child of triangle t keeps area and turns less than 60° from the surface
/// `around` t. Following creases (`creases`), also when it turns less than 30° from t itself: a
/// flat triangle beside a fold, whose neighbours turn the surface around it, is split in its
/// plane. When t is split where a crease crosses it (`crease`), its children lie on the
/// crease's two sides, which turn from the surface around t as far as the crease folds (90° at
/// a box's edge); t's own plane cuts across the fold, within 90° of either side, and a child
/// may turn up to 84° from it.
bool children_sound(const Surface& s, const TriangleIndices& t, Vec3 around, bool creases,
                    bool crease, std::span<const TriangleIndices> kids) {
    const Vec3 n = area_normal(s, t);
    const double parent_cosine = crease ? min_crease_cosine : min_parent_cosine;
    for (const TriangleIndices& kid : kids)
        if (!along(s, around, kid, min_normal_cosine) &&
            !(creases && along(s, n, kid, parent_cosine)))
            return false;
    return true;
}

/// An improving move may turn a triangle at most this far (cos 30°).
constexpr double improve_normal_cosine = 0.8660254037844386;
/// An edge shorter than this fraction of the shortest other edge of its two triangles is a
/// needle's and is collapsed.
constexpr double needle_ratio = 0.25;
/// A triangle whose edges are all shorter than this fraction of the shortest other edge of a
/// neighbour's is tiny beside it: a cluster of roots near one point of the mesh.
constexpr double cluster_ratio = 1.0 / 32.0;
/// Rounds of collapses and flips before each pass.
constexpr int improve_rounds = 8;
/// Times refinement collapses the needles about parts beyond ε whose splits were all refused.
constexpr int max_recoveries = 8;

/// The angle at corner k of triangle t.
double corner_angle(const Surface& s, const TriangleIndices& t, int k) {
    const Vec3 a = s.vertices[t[k]];
    const Vec3 u = s.vertices[t[(k + 1) % 3]] - a, v = s.vertices[t[(k + 2) % 3]] - a;
    return std::atan2(norm(cross(u, v)), dot(u, v));
}

/// One round of needle collapses: an edge much shorter than the other edges of its two
/// triangles is collapsed onto its first vertex (both ends lie on the zero set), when the
/// surface's topology allows it (the link condition: the two ends share exactly the two opposite
/// vertices as neighbours) and no triangle around the removed vertex turns more than 30°. Each
/// triangle takes part in one move a round; with `near` not empty, only edges both of whose
/// ends it marks. Dead triangles are marked by a first index of `dead`. Returns the collapses.
std::size_t collapse_needles(Surface& s, std::vector<std::uint8_t>& changed,
                             std::span<const std::uint8_t> near) {
    const Edges edges(s);
    // Triangles around each vertex, in order: its corners' triangles.
    VertexCorners around = vertex_corners(s);
    for (std::uint32_t& c : around.corners) c /= 3;
    auto ring = [&](std::uint32_t v) {
        return std::span<const std::uint32_t>(around.corners.data() + around.start[v],
                                              around.start[v + 1] - around.start[v]);
    };
    // Which edges are needles, on all threads: the test reads only the vertices and the edge
    // table of the round's start, which the collapses below leave as they are.
    std::vector<std::uint8_t> needle(edges.size(), 0);
    parallel_for(edges.size(), [&](std::size_t e) {
        const double length = distance(s.vertices[edges.ends[e][0]], s.vertices[edges.ends[e][1]]);
        // The shortest other edge and the longest edge of each of the two triangles.
        std::array<double, 2> shortest_other{}, longest{};
        for (int i = 0; i < 2; ++i) {
            shortest_other[i] = std::numeric_limits<double>::infinity();
            longest[i] = length;
            for (const std::uint32_t f : edges.of_triangle[edges.triangles[e][i]]) {
                if (f == e) continue;
                const double l =
                    distance(s.vertices[edges.ends[f][0]], s.vertices[edges.ends[f][1]]);
                shortest_other[i] = std::min(shortest_other[i], l);
                longest[i] = std::max(longest[i], l);
            }
        }
        // A needle's edge is much shorter than the other edges of both its triangles; or of one,
        // when the other triangle is tiny beside it (three roots near one point of the mesh,
        // between needles). An edge across a rounded edge of the surface, short beside the
        // long edges along it, is kept.
        needle[e] = length < needle_ratio * std::min(shortest_other[0], shortest_other[1]) ||
                            longest[1] < cluster_ratio * shortest_other[0] ||
                            longest[0] < cluster_ratio * shortest_other[1]
                        ? 1
                        : 0;
    });
    std::vector<std::uint8_t> touched(s.size(), 0);
    std::size_t collapses = 0;
    std::vector<std::uint32_t> neighbours_a, neighbours_b;
    for (std::uint32_t e = 0; e < edges.size(); ++e) {
        if (!needle[e]) continue;
        const auto [t0, t1] = edges.triangles[e];
        const std::uint32_t a = edges.ends[e][0], b = edges.ends[e][1];
        if (!near.empty() && !(near[a] && near[b])) continue;
        bool free = true;
        for (const std::uint32_t t : ring(a)) free &= !touched[t];
        for (const std::uint32_t t : ring(b)) free &= !touched[t];
        if (!free || ring(a).size() <= 3 || ring(b).size() <= 3) continue;
        // The link condition.
        auto neighbours = [&](std::uint32_t v, std::vector<std::uint32_t>& out) {
            out.clear();
            for (const std::uint32_t t : ring(v))
                for (const std::uint32_t w : s.triangles[t])
                    if (w != v) out.push_back(w);
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
        };
        neighbours(a, neighbours_a);
        neighbours(b, neighbours_b);
        std::size_t common = 0;
        for (const std::uint32_t w : neighbours_a)
            common += std::binary_search(neighbours_b.begin(), neighbours_b.end(), w) ? 1 : 0;
        if (common != 2) continue;
        // The triangles around b but t0 and t1 take a instead: none may turn far.
        bool sound = true;
        for (const std::uint32_t t : ring(b)) {
            if (t == t0 || t == t1) continue;
            TriangleIndices moved = s.triangles[t];
            for (std::uint32_t& v : moved)
                if (v == b) v = a;
            sound &= along(s, normal_around(s, edges, t), moved, improve_normal_cosine);
        }
        if (!sound) continue;
        for (const std::uint32_t t : ring(b)) {
            if (t == t0 || t == t1) continue;
            for (std::uint32_t& v : s.triangles[t])
                if (v == b) v = a;
            changed[t] = 1;
        }
        s.triangles[t0][0] = dead;
        s.triangles[t1][0] = dead;
        for (const std::uint32_t t : ring(a)) touched[t] = 1;
        for (const std::uint32_t t : ring(b)) touched[t] = 1;
        ++collapses;
    }
    return collapses;
}

/// The vertices that an edge tiny beside its neighbourhood joins: roots of the linear contour
/// near one point of the mesh, whose triangles have no shape worth keeping. An edge is tiny when
/// it is shorter than cluster_ratio times the longest edge at either of its ends.
/// Each cluster with ≥ 2 vertices is collapsed as a whole onto its vertex nearest its mean (a
/// root of G, so every vertex stays on the zero set), when what is left around that vertex is
/// one closed fan (the surface stays a manifold of the same Euler characteristic), no vertex
/// moves a quarter of the way from that vertex to its nearest neighbour outside, and no
/// triangle kept turns more than 30° from the surface around it. Each triangle takes part in
/// one collapse a round; with `near` not empty, only clusters all of whose vertices it marks.
/// Collapsed triangles are marked by a first index of `dead`. Returns the vertices removed.
std::size_t collapse_clusters(Surface& s, std::vector<std::uint8_t>& changed,
                              std::span<const std::uint8_t> near) {
    const Edges edges(s);
    const std::size_t vertices = s.vertices.size();
    std::vector<double> length(edges.size()), longest(vertices, 0.0);
    parallel_for(edges.size(), [&](std::size_t e) {
        length[e] = distance(s.vertices[edges.ends[e][0]], s.vertices[edges.ends[e][1]]);
    });
    for (std::size_t e = 0; e < edges.size(); ++e) {
        const auto [a, b] = edges.ends[e];
        longest[a] = std::max(longest[a], length[e]);
        longest[b] = std::max(longest[b], length[e]);
    }
    // The clusters: components of the tiny edges (union–find, the root the lowest vertex).
    std::vector<std::uint32_t> root(vertices);
    for (std::uint32_t v = 0; v < vertices; ++v) root[v] = v;
    auto find = [&](std::uint32_t v) {
        while (root[v] != v) v = root[v] = root[root[v]];
        return v;
    };
    bool any = false;
    for (std::size_t e = 0; e < edges.size(); ++e) {
        const auto [a, b] = edges.ends[e];
        if (!(length[e] < cluster_ratio * std::max(longest[a], longest[b]))) continue;
        const std::uint32_t ra = find(a), rb = find(b);
        if (ra != rb) root[std::max(ra, rb)] = std::min(ra, rb);
        any = true;
    }
    if (!any) return 0;
    std::vector<std::uint32_t> members, start(vertices + 1, 0);
    for (std::uint32_t v = 0; v < vertices; ++v) ++start[find(v) + 1];
    for (std::size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
    members.resize(vertices);
    {
        std::vector<std::uint32_t> at(start.begin(), start.end() - 1);
        for (std::uint32_t v = 0; v < vertices; ++v) members[at[find(v)]++] = v;
    }
    VertexCorners around = vertex_corners(s);
    for (std::uint32_t& c : around.corners) c /= 3;
    std::vector<std::uint8_t> touched(s.size(), 0), in_cluster(vertices, 0);
    std::vector<std::uint32_t> ring;
    std::vector<TriangleIndices> moved;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> fan;  // (x, y) of each kept (r, x, y)
    std::size_t removed = 0;
    for (std::uint32_t c = 0; c < vertices; ++c) {
        const std::span<const std::uint32_t> cluster(members.data() + start[c],
                                                     start[c + 1] - start[c]);
        if (cluster.size() < 2) continue;
        if (!near.empty() &&
            std::any_of(cluster.begin(), cluster.end(), [&](std::uint32_t v) { return !near[v]; }))
            continue;
        // The triangles around the cluster, once each.
        ring.clear();
        for (const std::uint32_t v : cluster)
            for (std::uint32_t k = around.start[v]; k < around.start[v + 1]; ++k)
                ring.push_back(around.corners[k]);
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
        if (std::any_of(ring.begin(), ring.end(), [&](std::uint32_t t) { return touched[t]; }))
            continue;
        // The vertex kept: the one nearest the cluster's mean.
        Vec3 mean{};
        for (const std::uint32_t v : cluster) mean += s.vertices[v];
        mean = (1.0 / static_cast<double>(cluster.size())) * mean;
        std::uint32_t r = cluster[0];
        for (const std::uint32_t v : cluster)
            if (distance(s.vertices[v], mean) < distance(s.vertices[r], mean)) r = v;
        for (const std::uint32_t v : cluster) in_cluster[v] = 1;
        // The triangles kept (one corner in the cluster), moved onto r, as fans (x, y) of r.
        moved.clear();
        fan.clear();
        std::size_t old_edges = 0, dropped = 0;
        for (const std::uint32_t t : ring) {
            const TriangleIndices& tri = s.triangles[t];
            int inside = 0, k = 0;
            for (int i = 0; i < 3; ++i)
                if (in_cluster[tri[i]]) ++inside, k = i;
            // Each edge counted once: at its triangle on the left, going from a to b.
            for (int i = 0; i < 3; ++i) {
                const std::uint32_t a = tri[i], b = tri[(i + 1) % 3];
                if ((in_cluster[a] || in_cluster[b]) && a < b) ++old_edges;
            }
            if (inside >= 2) {
                ++dropped;
                moved.push_back({dead, 0, 0});
                continue;
            }
            TriangleIndices m = tri;
            m[k] = r;
            moved.push_back(m);
            fan.push_back({tri[(k + 1) % 3], tri[(k + 2) % 3]});
        }
        for (const std::uint32_t v : cluster) in_cluster[v] = 0;
        // One closed fan: every outer vertex once first and once second, in one cycle of ≥ 3.
        std::sort(fan.begin(), fan.end());
        bool sound = fan.size() >= 3 &&
                     std::adjacent_find(fan.begin(), fan.end(), [](const auto& p, const auto& q) {
                         return p.first == q.first;
                     }) == fan.end();
        if (sound) {
            auto next = [&](std::uint32_t x) {
                const auto it =
                    std::lower_bound(fan.begin(), fan.end(), std::pair{x, std::uint32_t{0}});
                return it != fan.end() && it->first == x ? it->second : dead;
            };
            std::uint32_t x = fan[0].first;
            std::size_t steps = 0;
            do {
                x = next(x);
                ++steps;
            } while (x != dead && x != fan[0].first && steps <= fan.size());
            sound = x == fan[0].first && steps == fan.size();
        }
        // The Euler characteristic kept: V − E + F changes by −(|C| − 1) + (E_old − E_new) −
        // dropped, with E_old − E_new = old edges at the cluster − the fan's edges.
        sound &= old_edges == cluster.size() - 1 + dropped + fan.size();
        // Small beside what is kept: no vertex moves by a quarter of the distance from the
        // vertex kept to its nearest neighbour outside the cluster, and no triangle kept turns
        // far.
        if (sound) {
            double reach = 0.0, nearest = std::numeric_limits<double>::infinity();
            for (const std::uint32_t v : cluster)
                reach = std::max(reach, distance(s.vertices[v], s.vertices[r]));
            for (const auto& [x, y] : fan)
                nearest = std::min(nearest, distance(s.vertices[x], s.vertices[r]));
            sound = reach < needle_ratio * nearest;
            for (std::size_t i = 0; i < ring.size() && sound; ++i)
                if (moved[i][0] != dead)
                    sound =
                        along(s, normal_around(s, edges, ring[i]), moved[i], improve_normal_cosine);
        }
        if (!sound) continue;
        for (std::size_t i = 0; i < ring.size(); ++i) {
            s.triangles[ring[i]] = moved[i];
            changed[ring[i]] = 1;
            touched[ring[i]] = 1;
        }
        removed += cluster.size() - 1;
    }
    return removed;
}

/// Whether the angle at corner k of t and the angle at corner l of u sum beyond π(1 + 10⁻⁶), as
/// corner_angle() gives them. The sine of the excess δ = α + β − π, −(sin α cos β + cos α sin β),
/// settles it without atan2 where it is clearly away from zero: beyond 10⁻⁵, δ is that far from
/// 0 (and from π·10⁻⁶) while the rounding of either is about 10⁻¹⁵. The angles decide the rest
/// (δ near 0, or both triangles degenerate).
bool angles_beyond_pi(const Surface& s, const TriangleIndices& t, int k, const TriangleIndices& u,
                      int l) {
    // (√(x·x) rather than std::hypot: a few ulps more rounding, far below the margin of 1e-5.)
    auto sin_cos = [&](const TriangleIndices& tri, int c) {
        const Vec3 a = s.vertices[tri[c]];
        const Vec3 p = s.vertices[tri[(c + 1) % 3]] - a, q = s.vertices[tri[(c + 2) % 3]] - a;
        const Vec3 pq = cross(p, q);
        const double lengths = std::sqrt(dot(p, p) * dot(q, q));  // 0 for a repeated vertex: NaN
        return std::pair{std::sqrt(dot(pq, pq)) / lengths, dot(p, q) / lengths};
    };
    const auto [sin_a, cos_a] = sin_cos(t, k);
    const auto [sin_b, cos_b] = sin_cos(u, l);
    const double sin_excess = -(sin_a * cos_b + cos_a * sin_b);
    if (sin_excess > 1e-5) return true;
    if (sin_excess < -1e-5) return false;
    return corner_angle(s, t, k) + corner_angle(s, u, l) > std::numbers::pi * (1.0 + 1e-6);
}

/// A flip: the places of its two triangles and what they held before.
struct Flip {
    std::uint32_t t0, t1;
    TriangleIndices before0, before1;
};

/// One round of edge flips: edge (a, b) between triangles (a, b, c) and (b, a, d) becomes
/// (c, d) when the angles at c and d sum beyond π (the Delaunay rule, on the surface), the edge
/// (c, d) is new, neither new triangle turns more than 30° from the surface around the two, and
/// (following creases, `planes` given) it does not fold the contour across a crease by more than
/// eps (folds_beyond). Each triangle takes part in one flip a round. Returns the flips made.
std::vector<Flip> flip_edges(Surface& s, std::vector<std::uint8_t>& changed,
                             const CreasePlanes* planes, double eps) {
    const Edges edges(s);
    KeyMap<std::uint8_t> added;  // the edges this round's flips made
    // The edge (a, b) of triangles t0 = (a, b, c) and t1 = (b, a, d), with i and j the places of
    // a in t0 and of d in t1.
    struct Quad {
        std::uint32_t a, b, c, d;
        int i, j;
    };
    auto quad = [&](std::uint32_t e) {
        const auto [t0, t1] = edges.triangles[e];
        const TriangleIndices& p = s.triangles[t0];
        const TriangleIndices& q = s.triangles[t1];
        int i = 0;
        while (!(p[i] == edges.ends[e][0] || p[i] == edges.ends[e][1]) ||
               !(p[(i + 1) % 3] == edges.ends[e][0] || p[(i + 1) % 3] == edges.ends[e][1]))
            ++i;
        const std::uint32_t a = p[i], b = p[(i + 1) % 3];
        int j = 0;
        while (q[j] == a || q[j] == b) ++j;
        return Quad{a, b, p[(i + 2) % 3], q[j], i, j};
    };
    // Which edges break the Delaunay rule, on all threads, from the round's start: a flip
    // changes only its two triangles, which take part in no other flip this round, so the
    // triangles of every edge still tested below are the round's start's.
    std::vector<std::uint8_t> breaks(edges.size(), 0);
    parallel_for(edges.size(), [&](std::size_t e) {
        const Quad f = quad(static_cast<std::uint32_t>(e));
        const auto [t0, t1] = edges.triangles[e];
        breaks[e] =
            f.c != f.d && angles_beyond_pi(s, s.triangles[t0], (f.i + 2) % 3, s.triangles[t1], f.j)
                ? 1
                : 0;
    });
    std::vector<std::uint8_t> touched(s.size(), 0);
    std::vector<Flip> flips;
    for (std::uint32_t e = 0; e < edges.size(); ++e) {
        const auto [t0, t1] = edges.triangles[e];
        if (!breaks[e] || touched[t0] || touched[t1]) continue;
        const Quad f = quad(e);
        if (edges.contains(f.c, f.d) || added.contains(edge_key(f.c, f.d))) continue;
        const TriangleIndices u{f.c, f.a, f.d}, v{f.d, f.b, f.c};
        if (planes != nullptr &&
            folds_beyond(s, *planes, s.triangles[t0], s.triangles[t1], u, v, eps))
            continue;
        const Vec3 n = normal_around(s, edges, t0) + normal_around(s, edges, t1);
        if (!along(s, n, u, improve_normal_cosine) || !along(s, n, v, improve_normal_cosine))
            continue;
        flips.push_back({t0, t1, s.triangles[t0], s.triangles[t1]});
        s.triangles[t0] = u;
        s.triangles[t1] = v;
        added.assign(edge_key(f.c, f.d), 1);
        touched[t0] = touched[t1] = 1;
        changed[t0] = changed[t1] = 1;
    }
    return flips;
}

/// Collapses needles and flips edges, in rounds, until a round changes nothing. Triangles that
/// changed lose their cached centroid value and are marked dirty (their crossings unchecked);
/// collapsed ones are removed (vertices stay, unused). Where a round's changes make triangles
/// meet (a flip or collapse across a thin gap, decided by exact predicates among the changed
/// triangles), the flips of the triangles that meet are undone, until none meet; where a collapse
/// is among them, the whole round is undone and improvement ends for this pass. Following
/// creases (`planes`), no flip folds the contour across a crease by more than eps.
void improve(Surface& s, std::vector<double>& centroid_value, std::vector<std::uint8_t>& dirty,
             bool collapse, const CreasePlanes* planes, double eps, SurfaceRefinement& result,
             std::span<const std::uint8_t> near = {}) {
    for (int round = 0; round < improve_rounds; ++round) {
        const std::vector<TriangleIndices> triangles_before = s.triangles;
        const std::vector<double> centroids_before = centroid_value;
        const std::vector<std::uint8_t> dirty_before = dirty;
        std::vector<std::uint8_t> changed(s.size(), 0);
        auto drop_dead = [&] {
            std::size_t kept = 0;
            for (std::size_t t = 0; t < s.size(); ++t) {
                if (s.triangles[t][0] == dead) continue;
                s.triangles[kept] = s.triangles[t];
                centroid_value[kept] = changed[t] ? nan : centroid_value[t];
                dirty[kept] = dirty[t] | changed[t];
                changed[kept] = changed[t];
                ++kept;
            }
            s.triangles.resize(kept);
            centroid_value.resize(kept);
            dirty.resize(kept);
            changed.resize(kept);
        };
        std::size_t collapses = 0;
        if (collapse) {
            if (const std::size_t merged = collapse_clusters(s, changed, near); merged > 0) {
                collapses += merged;
                drop_dead();
            }
            if (const std::size_t needles = collapse_needles(s, changed, near); needles > 0) {
                collapses += needles;
                drop_dead();
            }
        }
        const std::vector<Flip> flipped = flip_edges(s, changed, planes, eps);
        std::size_t flips = flipped.size();
        bool meets = false;
        if (collapses + flips > 0) {
            // The flip of each triangle, by its place; a flip undone leaves its two triangles
            // as they were, still marked changed (checked again, their centroids forgotten).
            constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
            std::vector<std::uint32_t> flip_of(flipped.empty() ? 0 : s.size(), none);
            for (std::uint32_t i = 0; i < flipped.size(); ++i)
                flip_of[flipped[i].t0] = flip_of[flipped[i].t1] = i;
            for (;;) {
                const std::vector<TriangleContact> contacts = find_self_intersections(s, changed);
                if (contacts.empty()) break;
                bool undone = false;
                for (const TriangleContact& c : contacts) {
                    for (const std::uint32_t t : {c.first, c.second}) {
                        const std::uint32_t i = flip_of.empty() ? none : flip_of[t];
                        if (i == none) continue;
                        const Flip& f = flipped[i];
                        s.triangles[f.t0] = f.before0;
                        s.triangles[f.t1] = f.before1;
                        flip_of[f.t0] = flip_of[f.t1] = none;
                        --flips;
                        undone = true;
                    }
                }
                if (!undone) {
                    meets = true;
                    break;
                }
            }
        }
        if (meets) {
            s.triangles = triangles_before;
            centroid_value = centroids_before;
            dirty = dirty_before;
            return;
        }
        for (std::size_t t = 0; t < s.size(); ++t) {
            if (!changed[t]) continue;
            centroid_value[t] = nan;
            dirty[t] = 1;
        }
        result.collapses += collapses;
        result.flips += flips;
        // A round that changes under one triangle in a thousand is the last.
        if (1000 * (collapses + flips) < s.size()) break;
    }
}

}  // namespace

namespace {

/// The root of G for one edge's split, found or not.
struct NormalRoot {
    std::uint32_t edge = 0;
    Vec3 point;
    bool found = false;
    bool crease = false;  ///< the point is where the edge crosses a crease (crease_point)
};

/// A line searched for a root of G: from `origin`, where G is g0 (|g0| > η), along the unit
/// `direction` in which G falls towards zero, as far as bracket_reach[2] times `length`.
struct RootLine {
    Vec3 origin;
    Vec3 direction;
    double length = 0.0;
    double g0 = 0.0;
};

/// A root of G on a line, and its distance along it (NaN: none found).
struct LineRoot {
    Vec3 point;
    double distance = nan;
};

/// A root of G (|G| ≤ η) on each line, where one is found. First
/// Newton's step from the origin as if G were a signed distance (slope 1 along the line), then a
/// secant step through it: on a distance-like G one or two evaluations settle a line. The rest
/// get brackets reaching ½, 1, then 2 lengths, shrunk by find_roots. Each round is one batch of
/// G; the answers do not depend on the threads.
std::vector<LineRoot> roots_along_lines(std::span<const RootLine> lines, const SpaceEvaluator& g,
                                        const RootOptions& roots) {
    std::vector<LineRoot> at(lines.size());
    struct Search {
        std::uint32_t line;
        double s1 = 0.0, g1 = 0.0;  // the last point probed, and G there (first the origin)
    };
    std::vector<Search> open;
    open.reserve(lines.size());
    for (std::uint32_t i = 0; i < lines.size(); ++i) open.push_back({i, 0.0, lines[i].g0});
    std::vector<Bracket3> brackets;
    std::vector<std::uint32_t> bracketed;
    std::vector<std::pair<double, double>> bracket_span;  // the distances of a bracket's ends
    // One probe of every open line that `step` gives a distance for (NaN: none), in one batch: a
    // root, or a bracket with the line's last point, settles it. The lines not probed stay open,
    // then those probed, with that point as their last.
    auto probe = [&](auto step) {
        std::vector<Search> probed, rest, unsettled;
        std::vector<Vec3> points;
        for (const Search& o : open) {
            const double d = step(o);
            if (std::isnan(d)) {
                rest.push_back(o);
            } else {
                probed.push_back(o);
                points.push_back(lines[o.line].origin + d * lines[o.line].direction);
            }
        }
        std::vector<double> values(points.size());
        g(points, values);
        for (std::size_t k = 0; k < probed.size(); ++k) {
            Search o = probed[k];
            const RootLine& l = lines[o.line];
            const double d = step(o), v = values[k];
            if (std::abs(v) <= roots.eta) {
                at[o.line] = {points[k], d};
            } else if ((v > 0.0) != (o.g1 > 0.0)) {
                brackets.push_back({l.origin + o.s1 * l.direction, points[k], o.g1, v});
                bracketed.push_back(o.line);
                bracket_span.emplace_back(o.s1, d);
            } else {
                o.s1 = d, o.g1 = v;
                unsettled.push_back(o);
            }
        }
        rest.insert(rest.end(), unsettled.begin(), unsettled.end());
        open = std::move(rest);
    };
    const auto within_reach = [&](const Search& o, double d) {
        return std::isfinite(d) && d <= bracket_reach[2] * lines[o.line].length ? d : nan;
    };
    // Newton's step, G's slope taken as 1: |G(origin)|, within the brackets' reach (a G far from
    // a distance goes to the brackets at once).
    probe([&](const Search& o) { return within_reach(o, std::abs(lines[o.line].g0)); });
    // The secant step through the origin and Newton's point, onward and within reach.
    probe([&](const Search& o) {
        if (o.s1 == 0.0) return nan;
        const double g0 = lines[o.line].g0;
        const double d = o.s1 * g0 / (g0 - o.g1);
        return d > o.s1 ? within_reach(o, d) : nan;
    });
    // Brackets from the origin along the line, reaching ½, 1, then 2 lengths.
    for (const double reach : bracket_reach) {
        for (Search& o : open) o.s1 = 0.0, o.g1 = lines[o.line].g0;
        probe([&](const Search& o) { return reach * lines[o.line].length; });
    }
    const std::vector<Root3> found =
        find_roots([&](std::span<const Vec3> x, std::span<double> v) { g(x, v); }, brackets, roots);
    for (std::size_t i = 0; i < found.size(); ++i) {
        if (!found[i].converged) continue;
        const auto [s0, s1] = bracket_span[i];
        at[bracketed[i]] = {found[i].point, s0 + found[i].t * (s1 - s0)};
    }
    return at;
}

/// An edge whose midpoint lies this far from the zero set, in edge lengths, may cross a crease
/// (a fold of about 3.6° or more): a smooth surface's chord is off it by κL²/8, below L/64 once
/// edges are shorter than an eighth of the radius of curvature.
constexpr double crease_sagitta = 1.0 / 64.0;
/// The profile of the zero set above an edge is a crease's (two lines) when the height at the
/// midpoint is twice the lesser of those at the quarters within this fraction; a smooth
/// surface's (a parabola) has 1.5 times it.
constexpr double crease_fit = 0.05;
/// A crease point's G is settled within a quarter of the edge's length (twice this times it).
constexpr double crease_reach = 0.125;

/// Where the edge from a to b (both on the zero set) crosses a crease, from the heights of the
/// zero set above it along one direction at its quarters and midpoint (h1, hm, h3): two lines
/// through the edge's ends, h = α s and h = β (1 − s), meet at s = β / (α + β), height
/// αβ / (α + β). Nothing when the heights are not such a tent.
std::optional<Vec3> crease_point(Vec3 a, Vec3 b, Vec3 direction, double h1, double hm, double h3) {
    if (!(h1 > 0.0 && h3 > 0.0 && hm > 0.0)) return std::nullopt;
    if (std::abs(hm - 2.0 * std::min(h1, h3)) > crease_fit * hm) return std::nullopt;
    const double alpha = 4.0 * h1, beta = 4.0 * h3;
    const double s = beta / (alpha + beta);
    return a + s * (b - a) + (alpha * s) * direction;
}

/// For each candidate edge, the new vertex of its split: a root of G (|G| ≤ η) on the line
/// through its midpoint along the normal (the sum of its two triangles' area normals), on the
/// side where G falls towards zero (roots_along_lines). Where the midpoint lies far from the zero
/// set for the edge's length (crease_sagitta), the roots on the parallel lines through the edge's
/// quarters tell a crease from a curve; on a crease the vertex goes to the crease (crease_point,
/// its G settled along the same line), so that the children of the triangles across it lie on
/// its two sides, and a surface of flat facets converges in a pass where halving its edges
/// only halves their error. An edge whose normal vanishes or whose line meets no sign change
/// within reach has no root. Returned in edge order of the candidates, whatever the threads.
std::vector<NormalRoot> roots_along_normals(const Surface& s, const Edges& edges,
                                            std::span<const std::uint32_t> candidates,
                                            std::span<const double> mid, const SpaceEvaluator& g,
                                            const RootOptions& roots, bool creases) {
    std::vector<NormalRoot> out(candidates.size());
    std::vector<RootLine> lines;
    std::vector<std::uint32_t> line_of;  // the candidate of each line
    for (std::uint32_t c = 0; c < candidates.size(); ++c) {
        const std::uint32_t e = candidates[c];
        out[c].edge = e;
        const auto [t0, t1] = edges.triangles[e];
        const Vec3 n = area_normal(s, s.triangles[t0]) + area_normal(s, s.triangles[t1]);
        const double size = norm(n);
        const Vec3 a = s.vertices[edges.ends[e][0]], b = s.vertices[edges.ends[e][1]];
        if (!(size > 0.0)) continue;
        const Vec3 origin = 0.5 * (a + b);
        if (std::abs(mid[e]) <= roots.eta) {
            out[c].point = origin, out[c].found = true;
            continue;
        }
        // Towards the zero set: against the normal where G > 0 (outside).
        lines.push_back({origin, (mid[e] > 0.0 ? -1.0 : 1.0) / size * n, distance(a, b), mid[e]});
        line_of.push_back(c);
    }
    const std::vector<LineRoot> at = roots_along_lines(lines, g, roots);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (std::isnan(at[i].distance)) continue;
        out[line_of[i]].point = at[i].point;
        out[line_of[i]].found = true;
    }
    if (!creases) return out;

    // Creases: G at the quarters of the edges whose midpoint lies far off, in one batch.
    std::vector<std::uint32_t> suspects;  // indices into lines
    std::vector<Vec3> quarters;
    for (std::uint32_t i = 0; i < lines.size(); ++i) {
        if (std::isnan(at[i].distance) ||
            !(std::abs(lines[i].g0) > crease_sagitta * lines[i].length))
            continue;
        const std::uint32_t e = candidates[line_of[i]];
        const Vec3 a = s.vertices[edges.ends[e][0]], b = s.vertices[edges.ends[e][1]];
        suspects.push_back(i);
        quarters.push_back(0.75 * a + 0.25 * b);
        quarters.push_back(0.25 * a + 0.75 * b);
    }
    if (suspects.empty()) return out;
    std::vector<double> quarter_value(quarters.size());
    g(quarters, quarter_value);
    std::vector<RootLine> quarter_lines;
    std::vector<std::uint32_t> quarter_of;  // the suspect of each pair of quarter lines
    for (std::uint32_t k = 0; k < suspects.size(); ++k) {
        const RootLine& l = lines[suspects[k]];
        const double v1 = quarter_value[2 * k], v3 = quarter_value[2 * k + 1];
        // A tent's quarters lie on the midpoint's side, off the zero set, and G at the midpoint
        // is twice G at the quarter on its side of the crease (G a distance: the heights times
        // one cosine), where a smooth surface's is 4/3 of both.
        if (!((v1 > 0.0) == (l.g0 > 0.0) && (v3 > 0.0) == (l.g0 > 0.0) &&
              std::abs(v1) > roots.eta && std::abs(v3) > roots.eta))
            continue;
        const double g0 = std::abs(l.g0);
        if (!(std::min(std::abs(g0 - 2.0 * std::abs(v1)), std::abs(g0 - 2.0 * std::abs(v3))) <=
              2.0 * crease_fit * g0))
            continue;
        quarter_lines.push_back({quarters[2 * k], l.direction, l.length, v1});
        quarter_lines.push_back({quarters[2 * k + 1], l.direction, l.length, v3});
        quarter_of.push_back(k);
    }
    const std::vector<LineRoot> quarter_at = roots_along_lines(quarter_lines, g, roots);
    std::vector<std::uint32_t> crease_of;  // the line of each crease point
    std::vector<Vec3> points;
    for (std::uint32_t j = 0; j < quarter_of.size(); ++j) {
        const std::uint32_t i = suspects[quarter_of[j]];
        const std::uint32_t e = candidates[line_of[i]];
        const std::optional<Vec3> x = crease_point(
            s.vertices[edges.ends[e][0]], s.vertices[edges.ends[e][1]], lines[i].direction,
            quarter_at[2 * j].distance, at[i].distance, quarter_at[2 * j + 1].distance);
        if (!x) continue;
        points.push_back(*x);
        crease_of.push_back(i);
    }
    std::vector<double> values(points.size());
    g(points, values);
    std::vector<RootLine> crease_lines;
    std::vector<std::uint32_t> settle_of;  // the line of each crease point settled
    for (std::uint32_t k = 0; k < points.size(); ++k) {
        const std::uint32_t i = crease_of[k];
        // A rounded edge's profile is a tent with its tip cut off: its lines' meeting point
        // lies off the zero set by a fair part of the height (at the midpoint).
        if (!(std::abs(values[k]) <= crease_fit * at[i].distance)) continue;
        if (std::abs(values[k]) <= roots.eta) {
            out[line_of[i]].point = points[k];
            out[line_of[i]].crease = true;
            continue;
        }
        // Settled along the edge's line from the crease point, towards the zero set.
        const Vec3 d =
            (values[k] > 0.0) == (lines[i].g0 > 0.0) ? lines[i].direction : -lines[i].direction;
        crease_lines.push_back({points[k], d, crease_reach * lines[i].length, values[k]});
        settle_of.push_back(i);
    }
    const std::vector<LineRoot> settled = roots_along_lines(crease_lines, g, roots);
    for (std::size_t k = 0; k < crease_lines.size(); ++k) {
        // A crease point whose G settles nowhere near keeps the midpoint's root.
        if (std::isnan(settled[k].distance)) continue;
        NormalRoot& r = out[line_of[settle_of[k]]];
        r.point = settled[k].point;
        r.crease = true;
    }
    return out;
}

}  // namespace

SurfaceRefinement refine_surface(Surface& s, const SpaceEvaluator& g, double eps,
                                 const RootOptions& roots, int passes, int max_passes,
                                 std::size_t max_vertices, bool creases) {
    SurfaceRefinement result;
    KeyMap<double> midpoint_value;  // G at the midpoint of edge (a, b); vertices never move
    // Edges whose split a safeguard refused, with the vertices opposite them then (opposite_key):
    // an edge is tried again once a split beside it has changed its two triangles.
    KeyMap<std::uint64_t> frozen;
    std::vector<double> centroid_value(s.size(), nan);
    // Triangles changed since the last crossing check; the linear contour is embedded.
    std::vector<std::uint8_t> dirty(s.size(), 0);
    const int limit = passes < 0 ? max_passes : std::min(passes, max_passes);
    CreasePlanes planes;  // following creases: the zero set's planes at the vertices
    const CreasePlanes* crease_planes = creases ? &planes : nullptr;
    int cut_rounds = 0;
    int recoveries = 0;
    std::vector<std::uint8_t> stalled;  // about the parts beyond ε no split could refine
    // Where every split left beyond ε was refused, the needles and clusters about them (the
    // splits' and cuts' own, which improve() collapses only before the first pass) are collapsed
    // before the next pass, at most max_recoveries times.
    auto stall = [&](std::span<const double> mid, const Edges& edges) {
        if (recoveries >= max_recoveries) return false;
        ++recoveries;
        stalled.assign(s.vertices.size(), 0);
        for (std::uint32_t t = 0; t < s.size(); ++t) {
            bool out = std::abs(centroid_value[t]) > eps;
            for (const std::uint32_t e : edges.of_triangle[t]) out = out || std::abs(mid[e]) > eps;
            if (out)
                for (const std::uint32_t v : s.triangles[t]) stalled[v] = 1;
        }
        // Grown by two rings.
        for (int ring = 0; ring < 2; ++ring) {
            std::vector<std::uint8_t> grown = stalled;
            for (const TriangleIndices& t : s.triangles)
                if (stalled[t[0]] || stalled[t[1]] || stalled[t[2]])
                    grown[t[0]] = grown[t[1]] = grown[t[2]] = 1;
            stalled = std::move(grown);
        }
        return true;
    };
    for (int pass = 0; pass < limit; ++pass) {
        check_stop();
        // Needles come from the linear contour, where a root falls near a mesh vertex; splits
        // and cuts make few, and collapsing what they made could undo them pass after pass: they
        // are collapsed only about a part that refinement stalled at (stall).
        if (stalled.empty()) {
            improve(s, centroid_value, dirty, pass == 0 && cut_rounds == 0, crease_planes, eps,
                    result);
        } else {
            improve(s, centroid_value, dirty, true, crease_planes, eps, result, stalled);
            stalled.clear();
        }
        const Edges edges(s);
        const std::size_t m = edges.size();
        auto is_frozen = [&](std::uint32_t e) {
            const std::uint64_t* v = frozen.find(edge_key(edges.ends[e][0], edges.ends[e][1]));
            return v && (!creases || *v == opposite_key(s, edges, e));
        };
        auto midpoint = [&](std::uint32_t e) {
            return 0.5 * (s.vertices[edges.ends[e][0]] + s.vertices[edges.ends[e][1]]);
        };
        // G at the midpoints not yet known, one batch; then at the centroids not yet known of
        // the triangles that no midpoint beyond ε splits anyway, another.
        std::vector<double> mid(m);
        {
            // Known values on all threads (finding in the map only reads it).
            parallel_for(m, [&](std::size_t e) {
                const double* v = midpoint_value.find(edge_key(edges.ends[e][0], edges.ends[e][1]));
                mid[e] = v ? *v : nan;
            });
            std::vector<Vec3> points;
            std::vector<std::uint32_t> which;
            for (std::uint32_t e = 0; e < m; ++e) {
                if (!std::isnan(mid[e])) continue;
                points.push_back(midpoint(e));
                which.push_back(e);
            }
            std::vector<double> values(points.size());
            g(points, values);
            midpoint_value.reserve(midpoint_value.size() + points.size());
            for (std::size_t i = 0; i < points.size(); ++i) {
                const std::uint32_t e = which[i];
                mid[e] = values[i];
                midpoint_value.assign(edge_key(edges.ends[e][0], edges.ends[e][1]), values[i]);
            }
        }
        {
            auto splits_anyway = [&](std::uint32_t t) {
                for (const std::uint32_t e : edges.of_triangle[t]) {
                    if (std::abs(mid[e]) > eps && !is_frozen(e)) return true;
                }
                return false;
            };
            std::vector<std::uint8_t> skip(s.size());
            parallel_for(s.size(), [&](std::size_t t) {
                skip[t] =
                    !std::isnan(centroid_value[t]) || splits_anyway(static_cast<std::uint32_t>(t));
            });
            std::vector<Vec3> points;
            std::vector<std::uint32_t> which;
            for (std::uint32_t t = 0; t < s.size(); ++t) {
                if (skip[t]) continue;
                const Triangle3 tri = s.triangle(t);
                points.push_back((tri.a + tri.b + tri.c) / 3.0);
                which.push_back(t);
            }
            std::vector<double> values(points.size());
            g(points, values);
            for (std::size_t i = 0; i < points.size(); ++i) centroid_value[which[i]] = values[i];
        }
        result.residual = 0.0;
        for (const double v : mid) result.residual = std::max(result.residual, std::abs(v));
        for (const double v : centroid_value)
            if (!std::isnan(v)) result.residual = std::max(result.residual, std::abs(v));
        // The edges to split: midpoints beyond ε, and the longest edge of each triangle whose
        // centroid is.
        std::vector<std::uint8_t> wanted(m, 0);
        for (std::uint32_t e = 0; e < m; ++e) wanted[e] = std::abs(mid[e]) > eps;
        for (std::uint32_t t = 0; t < s.size(); ++t) {
            if (!(std::abs(centroid_value[t]) > eps)) continue;
            std::uint32_t longest = edges.of_triangle[t][0];
            double length = 0.0;
            for (const std::uint32_t e : edges.of_triangle[t]) {
                const double l =
                    distance(s.vertices[edges.ends[e][0]], s.vertices[edges.ends[e][1]]);
                if (l > length) longest = e, length = l;
            }
            wanted[longest] = 1;
        }
        const bool any_beyond = std::find(wanted.begin(), wanted.end(), 1) != wanted.end();
        for (std::uint32_t e = 0; e < m; ++e)
            if (wanted[e] && is_frozen(e)) wanted[e] = 0;
        std::vector<std::uint32_t> candidates;
        for (std::uint32_t e = 0; e < m; ++e)
            if (wanted[e]) candidates.push_back(e);
        // Following creases, the triangles beyond ε whose corners lie on different planes are
        // first cut where the planes meet (cut_creases), round after round while that changes
        // the surface (each round counted in `splits`, not in `passes`), then split.
        if (creases && any_beyond && cut_rounds < max_passes) {
            std::vector<std::uint32_t> beyond;
            for (std::uint32_t t = 0; t < s.size(); ++t) {
                bool out = std::abs(centroid_value[t]) > eps;
                for (const std::uint32_t e : edges.of_triangle[t])
                    out = out || std::abs(mid[e]) > eps;
                if (out) beyond.push_back(t);
            }
            const std::size_t cut = beyond.empty() ? 0
                                                   : cut_creases(s, g, roots.eta, beyond, planes,
                                                                 centroid_value, dirty);
            // G is known no more about the vertices moved onto their planes.
            if (!planes.moved.empty()) {
                std::vector<std::uint8_t> moved(s.vertices.size(), 0);
                for (const std::uint32_t v : planes.moved) moved[v] = 1;
                planes.moved.clear();
                for (std::uint32_t t = 0; t < s.size(); ++t) {
                    const TriangleIndices& v = s.triangles[t];
                    if (!moved[v[0]] && !moved[v[1]] && !moved[v[2]]) continue;
                    centroid_value[t] = nan;
                    dirty[t] = 1;
                    for (int k = 0; k < 3; ++k) {
                        if (moved[v[k]] || moved[v[(k + 1) % 3]])
                            midpoint_value.assign(edge_key(v[k], v[(k + 1) % 3]), nan);
                    }
                }
            }
            if (cut != 0) {
                ++cut_rounds;
                result.splits += cut;
                --pass;
                continue;
            }
        }
        if (!any_beyond) result.converged = 1;
        if (candidates.empty()) {
            if (any_beyond && stall(mid, edges)) continue;
            break;
        }
        if (s.vertices.size() + candidates.size() > max_vertices) {
            throw LimitExceeded(fmt::format(
                "refining the surface to eps {:.3g} needs more than {} vertices (it has {} and "
                "would add {}): raise eps",
                eps, max_vertices, s.vertices.size(), candidates.size()));
        }

        // The new vertex of each edge: G's root along the normal at its midpoint.
        auto refuse = [&](std::uint32_t e) {
            frozen.assign(edge_key(edges.ends[e][0], edges.ends[e][1]), opposite_key(s, edges, e));
            ++result.rejected;
        };
        const std::vector<NormalRoot> found =
            roots_along_normals(s, edges, candidates, mid, g, roots, creases);
        // The new vertices, numbered after the old ones in edge order.
        std::vector<std::uint32_t> vertex_of(m, std::numeric_limits<std::uint32_t>::max());
        std::vector<std::uint8_t> on_crease(m, 0);
        const auto old_vertices = static_cast<std::uint32_t>(s.vertices.size());
        std::vector<Vec3> added;
        for (const NormalRoot& r : found) {
            if (!r.found) {
                refuse(r.edge);
                continue;
            }
            vertex_of[r.edge] = old_vertices + static_cast<std::uint32_t>(added.size());
            on_crease[r.edge] = r.crease;
            added.push_back(r.point);
        }
        s.vertices.insert(s.vertices.end(), added.begin(), added.end());

        // Children, refusing the splits of a triangle whose children are unsound, until none is;
        // then the same for crossings of the rest of the surface.
        std::vector<std::uint8_t> split(m, 0);
        for (std::uint32_t e = 0; e < m; ++e)
            split[e] = vertex_of[e] != std::numeric_limits<std::uint32_t>::max();
        auto mask_of = [&](std::uint32_t t) {
            unsigned mask = 0;
            std::array<std::uint32_t, 3> w{};
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t e = edges.of_triangle[t][k];
                if (split[e]) mask |= 1u << k, w[k] = vertex_of[e];
            }
            return std::pair{mask, w};
        };
        auto refuse_splits_of = [&](std::uint32_t t) {
            for (const std::uint32_t e : edges.of_triangle[t]) {
                if (!split[e]) continue;
                split[e] = 0;
                refuse(e);
            }
        };
        Surface next;
        std::vector<double> next_centroid;
        std::vector<std::uint32_t> parent;
        std::vector<std::uint8_t> next_dirty;
        auto sound = [&](std::uint32_t t, unsigned mask, const std::array<std::uint32_t, 3>& w,
                         std::vector<TriangleIndices>& kids) {
            kids.clear();
            split_children(s, s.triangles[t], mask, w, kids);
            const std::array<std::uint32_t, 3>& sides = edges.of_triangle[t];
            const bool crease = std::any_of(sides.begin(), sides.end(), [&](std::uint32_t e) {
                return split[e] && on_crease[e];
            });
            return children_sound(s, s.triangles[t], normal_around(s, edges, t), creases, crease,
                                  kids);
        };
        // Each sweep's tests for the masks at its start, on all threads; the sweep itself tests
        // again only the triangles whose mask a refusal before them changed, so the outcome is
        // a sweep's on one thread.
        std::vector<unsigned> tested_mask(s.size());
        std::vector<std::uint8_t> tested_sound(s.size());
        std::vector<std::uint32_t> first_child(s.size() + 1);
        for (;;) {
            parallel_for(s.size(), [&](std::size_t i) {
                const auto t = static_cast<std::uint32_t>(i);
                const auto [mask, w] = mask_of(t);
                tested_mask[t] = mask;
                thread_local std::vector<TriangleIndices> kids;
                tested_sound[t] = mask == 0 || sound(t, mask, w, kids);
            });
            bool changed = false;
            std::vector<TriangleIndices> kids;
            for (std::uint32_t t = 0; t < s.size(); ++t) {
                const auto [mask, w] = mask_of(t);
                if (mask == 0) continue;
                if (mask == tested_mask[t] ? tested_sound[t] : sound(t, mask, w, kids)) continue;
                refuse_splits_of(t);
                changed = true;
            }
            if (changed) continue;
            // The children, on all threads, each triangle's at its place: 1 + its splits.
            first_child[0] = 0;
            for (std::uint32_t t = 0; t < s.size(); ++t)
                first_child[t + 1] = first_child[t] + 1 +
                                     static_cast<std::uint32_t>(std::popcount(mask_of(t).first));
            next.vertices = s.vertices;
            next.triangles.resize(first_child.back());
            next_centroid.resize(first_child.back());
            parent.resize(first_child.back());
            next_dirty.resize(first_child.back());
            parallel_for(s.size(), [&](std::size_t i) {
                const auto t = static_cast<std::uint32_t>(i);
                const auto [mask, w] = mask_of(t);
                thread_local std::vector<TriangleIndices> made;
                made.clear();
                split_children(s, s.triangles[t], mask, w, made);
                for (std::size_t k = 0; k < made.size(); ++k) {
                    const std::size_t c = first_child[t] + k;
                    next.triangles[c] = made[k];
                    next_centroid[c] = mask == 0 ? centroid_value[t] : nan;
                    parent[c] = t;
                    next_dirty[c] = mask != 0 || dirty[t] ? 1 : 0;
                }
            });
            // Pairs of triangles neither of which changed since the last check cannot meet.
            const std::vector<TriangleContact> contacts = find_self_intersections(next, next_dirty);
            if (contacts.empty()) break;
            // Which parents this round splits, read before any refusal: refusing one
            // triangle's splits also unsplits its neighbours' shared edges.
            std::vector<std::uint32_t> to_refuse;
            for (const TriangleContact& contact : contacts) {
                const std::uint32_t p = parent[contact.first], q = parent[contact.second];
                const bool p_split = mask_of(p).first != 0, q_split = mask_of(q).first != 0;
                if (!p_split && !q_split) {
                    throw NumericalFailure(fmt::format(
                        "the contour's triangles {} and {} meet before refinement; raise the "
                        "depth K",
                        p, q));
                }
                if (p_split) to_refuse.push_back(p);
                if (q_split) to_refuse.push_back(q);
            }
            for (const std::uint32_t t : to_refuse) refuse_splits_of(t);
        }
        // Vertices no triangle uses (their splits refused) are dropped.
        std::vector<std::uint32_t> renumber(next.vertices.size(),
                                            std::numeric_limits<std::uint32_t>::max());
        for (std::uint32_t v = 0; v < old_vertices; ++v) renumber[v] = v;
        std::uint32_t kept = old_vertices;
        for (std::uint32_t e = 0; e < m; ++e)
            if (split[e]) renumber[vertex_of[e]] = kept++;
        std::vector<Vec3> vertices(kept);
        for (std::uint32_t v = 0; v < next.vertices.size(); ++v)
            if (renumber[v] != std::numeric_limits<std::uint32_t>::max())
                vertices[renumber[v]] = next.vertices[v];
        for (TriangleIndices& t : next.triangles)
            for (std::uint32_t& v : t) v = renumber[v];
        const std::size_t splits = kept - old_vertices;
        s.vertices = std::move(vertices);
        s.triangles = std::move(next.triangles);
        centroid_value = std::move(next_centroid);
        dirty.assign(s.triangles.size(), 0);
        if (splits == 0) {
            if (stall(mid, edges)) continue;
            break;
        }
        result.splits += splits;
        ++result.passes;
    }
    drop_unused_vertices(s);  // those collapses left
    return result;
}

}  // namespace slc::contouring
