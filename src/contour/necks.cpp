// Joining curves that the piecewise-linear interpolant parted where G does not: a thin tip of a
// region, narrower than a cell at its neck, whose tree vertices the triangulation does not link
// to its body's, comes out of marching as an island beside the body. And the converse, parting
// what it joined where G does not: two regions a gap narrower than a cell apart, linked by a strip
// of triangles whose corners lie in both. G itself, sampled between them, says which it is.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <utility>

#include "slc/geometry/predicates.hpp"
#include "stages.hpp"

namespace slc::contouring {
namespace {

/// The nearest pair of vertices of two curves, by number: a on the lower-numbered curve.
struct Pair {
    double distance = std::numeric_limits<double>::infinity();
    std::uint32_t a = 0, b = 0;
};

/// Union–find over curve numbers, so that curves joined once are not joined again (a second
/// bridge between the same two would cut the joined curve in two).
struct Sets {
    std::vector<std::uint32_t> parent;
    explicit Sets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    std::uint32_t find(std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
};

/// Whether segments u → next u and v → next v may become u → next v and v → next u: the new
/// segments cross no segment of the chain and each other not (exact predicates).
bool reconnectable(const Chain& chain, const SegmentGrid& segments, std::uint32_t u,
                   std::uint32_t v) {
    const std::uint32_t nu = chain.next[u], nv = chain.next[v];
    const Segment one{chain.points[u], chain.points[nv]};
    const Segment two{chain.points[v], chain.points[nu]};
    const std::array<std::uint32_t, 4> skip_one{chain.prev[u], u, v, nv};
    const std::array<std::uint32_t, 4> skip_two{chain.prev[v], v, u, nu};
    return !segments_intersect(one, two) && !segments.crosses(one, skip_one) &&
           !segments.crosses(two, skip_two);
}

/// Replaces segments u → next u and v → next v by u → next v and v → next u, which refinement
/// evaluates afresh and does not hold to a home triangle (they cross the interpolant's gap or
/// strip), and registers them in segments.
void reconnect(Chain& chain, SegmentGrid& segments, std::uint32_t u, std::uint32_t v) {
    const std::uint32_t nu = chain.next[u], nv = chain.next[v];
    chain.next[u] = nv;
    chain.prev[nv] = u;
    chain.next[v] = nu;
    chain.prev[nu] = v;
    for (std::uint32_t x : {u, v}) {
        chain.lengths[x] = distance(chain.points[x], chain.points[chain.next[x]]);
        chain.mid_value[x] = std::numeric_limits<double>::quiet_NaN();
        chain.frozen[x] = 0;
        chain.unbound[x] = 1;
        segments.insert(x);
    }
}

}  // namespace

std::size_t join_necks(Chain& chain, BatchFunctionRef g, const Topology& topo,
                       const ContourOptions& options) {
    const std::size_t curves = chain.curve_size.size();
    if (curves < 2) return 0;
    // Each curve's orientation: counterclockwise curves enclose G < 0, clockwise ones G > 0.
    std::vector<double> twice_area(curves, 0.0);
    for (std::uint32_t i = 0; i < chain.points.size(); ++i) {
        if (!chain.alive[i]) continue;
        twice_area[chain.curve[i]] += cross(chain.points[i], chain.points[chain.next[i]]);
    }
    // The nearest vertices of each pair of curves of one orientation within a finest cell edge,
    // found on a grid of that cell.
    const double reach = topo.tree.edge(topo.tree.depth());
    const Vec2 origin = chain.points.front();
    auto cell_of = [&](Vec2 p) {
        return std::pair<std::int64_t, std::int64_t>{
            static_cast<std::int64_t>(std::floor((p.x - origin.x) / reach)),
            static_cast<std::int64_t>(std::floor((p.y - origin.y) / reach))};
    };
    std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::uint32_t>> grid;
    for (std::uint32_t i = 0; i < chain.points.size(); ++i)
        if (chain.alive[i]) grid[cell_of(chain.points[i])].push_back(i);
    std::map<std::pair<std::uint32_t, std::uint32_t>, Pair> nearest;
    for (std::uint32_t a = 0; a < chain.points.size(); ++a) {
        if (!chain.alive[a]) continue;
        const auto [cx, cy] = cell_of(chain.points[a]);
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
            for (std::int64_t dx = -1; dx <= 1; ++dx) {
                const auto it = grid.find({cx + dx, cy + dy});
                if (it == grid.end()) continue;
                for (std::uint32_t b : it->second) {
                    const std::uint32_t ca = chain.curve[a], cb = chain.curve[b];
                    if (ca >= cb || (twice_area[ca] > 0.0) != (twice_area[cb] > 0.0)) continue;
                    const double d = distance(chain.points[a], chain.points[b]);
                    Pair& best = nearest[{ca, cb}];
                    if (d < reach && d < best.distance) best = {d, a, b};
                }
            }
        }
    }
    SegmentGrid segments(chain, reach);
    // Facing segments of two curves of one orientation run opposite ways, so the nearest
    // vertices a and b are bridged in place of the segments leaving a and entering b (bridges
    // a → b and prev b → next a), or entering a and leaving b; the shorter of the two whose
    // bridges cross no segment and each other not. The segments u → next u and v → next v are
    // replaced by u → next v and v → next u.
    struct Way {
        std::uint32_t u, v;
    };
    auto bridgeable = [&](const Way& w) { return reconnectable(chain, segments, w.u, w.v); };
    auto bridge_length = [&](const Way& w) {
        return distance(chain.points[w.u], chain.points[chain.next[w.v]]) +
               distance(chain.points[w.v], chain.points[chain.next[w.u]]);
    };
    struct Candidate {
        std::uint32_t first, second;  // the curves
        Way way;
        std::uint32_t nu, nv;  // the far ends of the replaced segments, when chosen
    };
    std::vector<Candidate> candidates;
    std::vector<Vec2> probes;
    for (const auto& [key, pair] : nearest) {
        if (!std::isfinite(pair.distance)) continue;
        std::optional<Way> chosen;
        for (const Way& w : {Way{pair.a, chain.prev[pair.b]}, Way{chain.prev[pair.a], pair.b}}) {
            if (bridgeable(w) && (!chosen || bridge_length(w) < bridge_length(*chosen))) chosen = w;
        }
        if (!chosen) continue;
        const std::uint32_t nu = chain.next[chosen->u], nv = chain.next[chosen->v];
        candidates.push_back({key.first, key.second, *chosen, nu, nv});
        // G between the two replaced segments, at the centre of the four ends: of the sign the
        // curves enclose where the gap is the interpolant's alone.
        probes.push_back(0.25 * (chain.points[chosen->u] + chain.points[nu] +
                                 chain.points[chosen->v] + chain.points[nv]));
    }
    if (probes.empty()) return 0;
    std::vector<double> values(probes.size());
    g(probes, values);

    Sets sets(curves);
    std::size_t joined = 0;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        const Candidate& c = candidates[k];
        const bool counterclockwise = twice_area[c.first] > 0.0;
        if (!(std::abs(values[k]) > options.resolved_eta()) ||
            (values[k] < 0.0) != counterclockwise)
            continue;
        const std::uint32_t ra = sets.find(c.first), rb = sets.find(c.second);
        if (ra == rb) continue;
        // An earlier join may have used one of these segments or laid a bridge across.
        if (chain.next[c.way.u] != c.nu || chain.next[c.way.v] != c.nv || !bridgeable(c.way))
            continue;
        const std::uint32_t u = c.way.u, v = c.way.v;
        reconnect(chain, segments, u, v);
        // The joined curve takes the lower number.
        const std::uint32_t keep = std::min(chain.curve[u], chain.curve[v]);
        const std::uint32_t gone = std::max(chain.curve[u], chain.curve[v]);
        std::uint32_t x = u;
        do {
            chain.curve[x] = keep;
            x = chain.next[x];
        } while (x != u);
        chain.curve_size[keep] += chain.curve_size[gone];
        chain.curve_size[gone] = 0;
        sets.parent[std::max(ra, rb)] = std::min(ra, rb);
        ++joined;
    }
    return joined;
}

std::size_t part_bridges(Chain& chain, SegmentGrid& segments, BatchFunctionRef g,
                         const Topology& topo, std::span<const std::uint32_t> rootless,
                         const ContourOptions& options) {
    if (rootless.empty()) return 0;
    const double eta = options.resolved_eta();
    auto longest_edge = [&](std::uint32_t t) {
        const auto& tri = topo.mesh.triangles[t];
        const auto& v = topo.mesh.vertices;
        return std::max({distance(v[tri[0]], v[tri[1]]), distance(v[tri[1]], v[tri[2]]),
                         distance(v[tri[2]], v[tri[0]])});
    };
    // The polygon of the vertices from a to b (along next), closed from b back to a: twice its
    // signed area, and whether it has three vertices or more and is at least a quarter of a
    // K-level cell thick (2|A|/L, a disc's radius), a part the uniform tree resolves.
    const double thick = 0.25 * topo.tree.edge(std::min(options.depth, topo.tree.depth()));
    struct Loop {
        double twice_area = 0.0;
        bool resolved = false;
    };
    auto loop = [&](std::uint32_t a, std::uint32_t b) {
        Loop l;
        std::size_t count = 1;
        double perimeter = distance(chain.points[b], chain.points[a]);
        // a and b lie on one curve: b comes within its vertices (the bound only guards the walk).
        const std::size_t most = chain.curve_size[chain.curve[a]];
        for (std::uint32_t x = a; x != b;) {
            if (count > most) return Loop{};
            const std::uint32_t y = chain.next[x];
            l.twice_area += cross(chain.points[x], chain.points[y]);
            perimeter += chain.length(x);
            ++count;
            x = y;
        }
        l.twice_area += cross(chain.points[b], chain.points[a]);
        l.resolved = count >= 3 && std::abs(l.twice_area) >= thick * perimeter;
        return l;
    };
    auto tangent = [&](std::uint32_t u) {
        return (chain.points[chain.next[u]] - chain.points[u]) / chain.length(u);
    };
    // The pairs (u, v), u < v, each with the centre of its four ends.
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::vector<Vec2> probes;
    for (const std::uint32_t u : rootless) {
        const double gu = chain.mid_value[u];
        if (!chain.alive[u] || !(std::abs(gu) > eta)) continue;
        // The bracket's direction: where G should change sign, towards the strip.
        const Vec2 t = tangent(u);
        const Vec2 right{t.y, -t.x};
        const Vec2 towards = gu > 0.0 ? -1.0 * right : right;
        const Vec2 mid = 0.5 * (chain.points[u] + chain.points[chain.next[u]]);
        const double h = longest_edge(chain.home[u]);
        const auto [hit, v] = segments.first_hit_segment(mid, towards, h, u);
        if (v == SegmentGrid::none || v == chain.next[u] || v == chain.prev[u] ||
            chain.curve[v] != chain.curve[u])
            continue;
        const double gv = chain.mid_value[v];
        // v's midpoint may not be known yet (made by the last pass): then G at the centre decides.
        if (gv * gu < 0.0 || !(dot(tangent(v), t) < 0.0)) continue;
        const auto key = std::minmax(u, v);
        if (!seen.insert(key).second) continue;
        pairs.push_back(key);
        probes.push_back(0.25 * (chain.points[u] + chain.points[chain.next[u]] + chain.points[v] +
                                 chain.points[chain.next[v]]));
    }
    if (probes.empty()) return 0;
    std::vector<double> values(probes.size());
    g(probes, values);

    std::size_t parted = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const auto [u, v] = pairs[k];
        // The strip between u and v has the other sign than their midpoints' G by the
        // interpolant; G at its centre decides.
        if (!(values[k] * chain.mid_value[u] > 0.0) || !(std::abs(values[k]) > eta)) continue;
        const std::uint32_t nu = chain.next[u], nv = chain.next[v];
        // An earlier parting may have used one of these segments.
        if (!chain.alive[u] || !chain.alive[v] || nu == v || nv == u) continue;
        if (!reconnectable(chain, segments, u, v)) continue;
        // The curve parts into two loops, nv … u and nu … v: two parts side by side, each
        // oriented as the curve was and at least a quarter of a K-level cell thick. A loop
        // inside the other (a hole, where a strip of the outside crossed a wall thinner than a
        // cell) and a loop thinner than that (such as a lobe G makes at the corner of a
        // non-convex Wulff shape) are left as the interpolant gave them, for the time loop's
        // deeper thin cells to decide; so are strips between two curves.
        const std::uint32_t c = chain.curve[u];
        if (chain.curve[v] != c) continue;
        const Loop one_side = loop(nv, u), other = loop(nu, v);
        if (!one_side.resolved || !other.resolved ||
            (one_side.twice_area > 0.0) != (other.twice_area > 0.0))
            continue;
        reconnect(chain, segments, u, v);
        // v's loop takes a new number.
        const auto fresh = static_cast<std::uint32_t>(chain.curve_size.size());
        std::size_t size = 0;
        std::uint32_t x = v;
        do {
            chain.curve[x] = fresh;
            ++size;
            x = chain.next[x];
        } while (x != v);
        chain.curve_size.push_back(size);
        chain.curve_size[c] -= size;
        ++parted;
    }
    return parted;
}

}  // namespace slc::contouring
