// Adaptive refinement of the contour (paper §2.2, Figs. 7 and 8): P passes of split (segments
// whose midpoint has |G| > ε), bracket (along the segment's normal, at most one segment length
// away, shortened to avoid the other segments), root finding to |G| ≤ η, safeguards (no
// angle ≤ 2.56° with a neighbour; a vertex may leave its segment's triangle only for an adjacent
// empty one; no crossing of any other segment) and pruning of segments shorter than ρ times both
// neighbours. Each pass hands G one batch of midpoints, one or two of bracket ends, then one per
// round of root finding.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/stop.hpp"
#include "stages.hpp"

namespace slc::contouring {
namespace {

/// The paper's angle safeguard: a new vertex making an angle of 2.56° or less with either
/// neighbour would nearly fold the curve back onto its neighbouring segment.
constexpr double min_angle = 2.56 * std::numbers::pi / 180.0;
/// Bracket end at this many segment lengths from the midpoint (the paper's choice).
constexpr double bracket_distance = 1.0;
/// When G shrinks towards the first bracket end without changing sign, the zero lies beyond it
/// (a chord across a sharp corner): a second end goes this much past the secant's estimate,
/// but never farther than max_bracket_distance segment lengths.
constexpr double extrapolation_overshoot = 1.25;
constexpr double max_bracket_distance = 3.0;
/// When the first bracket end may lie past two zeros, a short second end goes this many times
/// the distance to the zero that the interpolant's slope predicts (enough for slopes
/// overestimated twofold), and at most this fraction of the first distance.
constexpr double short_probe_overshoot = 2.0;
constexpr double short_probe_fraction = 0.5;
/// A bracket that would reach another segment (a neighbour, or another part of the contour
/// across a narrow gap) stops at this fraction of the way there.
constexpr double collision_margin = 0.9;
/// A bracket across which G's secant is this many times the tree's gradient bound γ holds a jump
/// of G, not a root: its split would be refused anyway (a stalled root is no vertex), so it is
/// given up at once instead of being bisected to rounding size (some fifty evaluations).
constexpr double jump_slope_factor = 1024.0;
/// A segment whose neighbours are both within ε of the zero set but which is not, with the
/// neighbours' lines turning by at least this much between them, cuts a corner of the zero set:
/// its bracket aims at where those lines meet.
constexpr double corner_turn = 20.0 * std::numbers::pi / 180.0;
/// Barycentric slack when deciding that a root lies in its home triangle: rounding only.
constexpr double triangle_slack = 1e-12;

/// The safeguards' grid cells are never smaller than this fraction of the finest tree edge
/// (which bounds the hash keys however short the segments become).
constexpr double min_grid_fraction = 1.0 / 4096.0;

constexpr double infinity = std::numeric_limits<double>::infinity();

/// A segment chosen for splitting and what was learned about it.
struct Candidate {
    std::uint32_t u = 0;  ///< the segment runs from vertex u to next[u]
    Vec2 mid;
    double g_mid = 0.0;
    Vec2 dir;            ///< unit direction of the bracket from mid
    double reach = 0.0;  ///< how far the bracket may go: other segments, the domain
    Vec2 near;           ///< the bracket's end on mid's side of the zero (mid, or a probe)
    double g_near = 0.0;
    Vec2 probe;  ///< the bracket's far end
    double g_probe = 0.0;
    bool has_root = false;
    Vec2 root;
    bool at_corner = false;  ///< the bracket aims at a corner of the zero set (corner_of)
};

/// True when the angle at apex between the rays to p and q is at most min_angle.
bool is_sharp(Vec2 apex, Vec2 p, Vec2 q) {
    const Vec2 a = p - apex, b = q - apex;
    return std::atan2(std::abs(cross(a, b)), dot(a, b)) <= min_angle;
}

/// Distance from o (inside box) along the unit direction d to the box's boundary.
double ray_exit(const Box& box, Vec2 o, Vec2 d) {
    double s = infinity;
    if (d.x > 0.0) s = std::min(s, (box.hi.x - o.x) / d.x);
    if (d.x < 0.0) s = std::min(s, (box.lo.x - o.x) / d.x);
    if (d.y > 0.0) s = std::min(s, (box.hi.y - o.y) / d.y);
    if (d.y < 0.0) s = std::min(s, (box.lo.y - o.y) / d.y);
    return std::max(s, 0.0);
}

class Refiner {
public:
    Refiner(Chain& chain, BatchFunctionRef g, const Topology& topo, const Box& domain,
            const ContourOptions& options)
        : chain_(chain),
          g_(g),
          topo_(topo),
          domain_(domain),
          options_(options),
          eps_(options.resolved_eps()) {}

    RefineReport run() {
        const int passes = options_.refine_passes == ContourOptions::until_converged
                               ? options_.max_refine_passes
                               : options_.refine_passes;
        for (int p = 0; p < passes; ++p) {
            check_stop();
            evaluate_midpoints();
            std::vector<Candidate> candidates = select();
            if (candidates.empty()) break;
            check_vertex_limit(candidates.size());
            index_segments();  // read by the bracket, acceptance and pruning steps only
            bracket(candidates);
            solve(candidates);
            const std::size_t changed = accept(candidates) + prune();
            const std::size_t parted =
                options_.part_bridges ? part_bridges(chain_, *grid_, g_, topo_, rootless_, options_)
                                      : 0;
            rootless_.clear();
            report_.parted += parted;
            ++report_.passes;
            if (changed + parted == 0) break;
        }
        report_.max_midpoint_value = max_midpoint_value();
        return report_;
    }

private:
    /// Throws LimitExceeded when accepting every candidate would pass options_.max_vertices.
    void check_vertex_limit(std::size_t candidates) const {
        // Every vertex ever made bounds the alive ones: count those only near the limit.
        if (chain_.points.size() + candidates <= options_.max_vertices) return;
        const auto alive = static_cast<std::size_t>(
            std::count(chain_.alive.begin(), chain_.alive.end(), std::uint8_t{1}));
        if (alive + candidates <= options_.max_vertices) return;
        throw LimitExceeded(fmt::format(
            "refining the contour to eps {:g} needs more than {} vertices (a pass would take "
            "{} to {}): raise eps",
            eps_, options_.max_vertices, alive, alive + candidates));
    }

    /// A fresh grid of the segments for the safeguards, its cells twice the mean segment length:
    /// each pass halves the segments, and a grid sized for the first pass would put hundreds of
    /// segments in a cell by the last.
    void index_segments() {
        double total = 0.0;
        std::size_t count = 0;
        for (std::uint32_t i = 0; i < chain_.points.size(); ++i) {
            if (chain_.alive[i]) {
                total += chain_.length(i);
                ++count;
            }
        }
        const double finest = topo_.tree.edge(topo_.tree.depth());
        const double cell = count > 0 && total > 0.0
                                ? std::clamp(2.0 * total / static_cast<double>(count),
                                             finest * min_grid_fraction, finest)
                                : finest;
        grid_.emplace(chain_, cell);
    }

    /// G at the midpoint of every segment not yet evaluated, in one batch.
    void evaluate_midpoints() {
        std::vector<std::uint32_t> ids;
        std::vector<Vec2> points;
        for (std::uint32_t i = 0; i < chain_.points.size(); ++i) {
            if (chain_.alive[i] && std::isnan(chain_.mid_value[i])) {
                ids.push_back(i);
                points.push_back(0.5 * (chain_.points[i] + chain_.points[chain_.next[i]]));
            }
        }
        std::vector<double> values(points.size());
        if (!points.empty()) g_(points, values);
        for (std::size_t k = 0; k < ids.size(); ++k) chain_.mid_value[ids[k]] = values[k];
    }

    /// Segments whose midpoint misses ε (split step), in vertex order.
    std::vector<Candidate> select() const {
        std::vector<Candidate> out;
        for (std::uint32_t i = 0; i < chain_.points.size(); ++i) {
            if (chain_.alive[i] && !chain_.frozen[i] && std::abs(chain_.mid_value[i]) > eps_) {
                Candidate c;
                c.u = i;
                c.mid = 0.5 * (chain_.points[i] + chain_.points[chain_.next[i]]);
                c.g_mid = chain_.mid_value[i];
                out.push_back(c);
            }
        }
        return out;
    }

    /// Bracket step: the far end lies along the segment's normal, on the side where G has the
    /// other sign (G > 0 lies on the right), one segment length away, shortened so that the
    /// bracket stays off every other segment (the neighbours, or another part of the contour
    /// across a narrow gap, whose zero the bracket would otherwise jump over together with ours)
    /// and inside the domain. One batch, and a second for brackets that fell short of the zero.
    /// The reaches are found on all worker threads: the grid is only read here.
    void bracket(std::vector<Candidate>& candidates) {
        std::vector<Vec2> probes(candidates.size());
        parallel_for(candidates.size(), [&](std::size_t k) {
            Candidate& c = candidates[k];
            const std::uint32_t u = c.u, v = chain_.next[u];
            const Vec2 tangent = (chain_.points[v] - chain_.points[u]) / chain_.length(u);
            const Vec2 right{tangent.y, -tangent.x};
            const Vec2 normal = c.g_mid > 0.0 ? -right : right;
            const double longest = max_bracket_distance * chain_.length(u);
            c.near = c.mid;
            c.g_near = c.g_mid;
            if (const std::optional<Vec2> corner = corner_of(u, normal)) {
                const double d = distance(c.mid, *corner);
                c.dir = (*corner - c.mid) / d;
                c.reach = std::min(collision_margin * grid_->first_hit(c.mid, c.dir, longest, u),
                                   ray_exit(domain_, c.mid, c.dir));
                if (d <= c.reach) {
                    c.at_corner = true;
                    c.probe = *corner;
                    probes[k] = c.probe;
                    return;
                }
            }
            c.dir = normal;
            c.reach = std::min(collision_margin * grid_->first_hit(c.mid, c.dir, longest, u),
                               ray_exit(domain_, c.mid, c.dir));
            c.probe = domain_.clamp(c.mid +
                                    std::min(bracket_distance * chain_.length(u), c.reach) * c.dir);
            probes[k] = c.probe;
        });
        std::vector<double> values(probes.size());
        g_(probes, values);
        for (std::size_t k = 0; k < candidates.size(); ++k) candidates[k].g_probe = values[k];
        extend_brackets(candidates);
    }

    /// A second probe for every bracket whose far end kept mid's sign. If G fell towards the far
    /// end, the zero may lie beyond it: probe at the secant's extrapolation of the zero (times
    /// extrapolation_overshoot, within max_bracket_distance segment lengths and the reach). Else,
    /// or if that is out of reach, the bracket may have jumped over two zeros (a narrow gap):
    /// probe short, at short_probe_overshoot times the distance the slope of the interpolant in
    /// the home triangle predicts, at most half the first distance. One batch.
    void extend_brackets(std::vector<Candidate>& candidates) {
        std::vector<std::size_t> ids;
        std::vector<Vec2> probes;
        for (std::size_t k = 0; k < candidates.size(); ++k) {
            Candidate& c = candidates[k];
            const bool same_sign = (c.g_probe > 0.0) == (c.g_mid > 0.0);
            if (!same_sign || std::abs(c.g_probe) <= options_.resolved_eta()) continue;
            const double d = distance(c.mid, c.probe);
            double far = 0.0;
            if (std::abs(c.g_probe) < std::abs(c.g_mid)) {
                const double estimate = d * c.g_mid / (c.g_mid - c.g_probe);
                far = std::min({extrapolation_overshoot * estimate,
                                max_bracket_distance * chain_.length(c.u), c.reach});
            }
            if (far > d) {
                c.near = c.probe;
                c.g_near = c.g_probe;
            } else {
                far = std::min(short_probe_overshoot * std::abs(c.g_mid) / slope(chain_.home[c.u]),
                               short_probe_fraction * d);
                if (!(far > 0.0)) continue;
            }
            c.probe = domain_.clamp(c.mid + far * c.dir);
            ids.push_back(k);
            probes.push_back(c.probe);
        }
        if (probes.empty()) return;
        std::vector<double> values(probes.size());
        g_(probes, values);
        for (std::size_t i = 0; i < ids.size(); ++i) candidates[ids[i]].g_probe = values[i];
    }

    /// Where the lines of u's neighbouring segments meet, when segment u cuts a corner of the zero
    /// set there: both neighbours are within ε of it and u is not, their lines turn by at least
    /// corner_turn, and they meet on the side of u where G has the other sign (normal), ahead of
    /// both neighbours and within max_bracket_distance segment lengths of u's midpoint. On
    /// straight sides, such as a polygon's offsets or its rigid motions, that is the corner itself.
    std::optional<Vec2> corner_of(std::uint32_t u, Vec2 normal) const {
        const std::uint32_t v = chain_.next[u], p = chain_.prev[u], n = chain_.next[v];
        if (n == p || std::abs(chain_.mid_value[p]) > eps_ || std::abs(chain_.mid_value[v]) > eps_)
            return std::nullopt;
        const Vec2 pu = chain_.points[u], pv = chain_.points[v];
        const Vec2 d1 = (pu - chain_.points[p]) / chain_.length(p);
        const Vec2 d2 = (chain_.points[n] - pv) / chain_.length(v);
        const double sine = cross(d1, d2);
        if (std::atan2(std::abs(sine), dot(d1, d2)) < corner_turn) return std::nullopt;
        // pu + s d1 = pv + t d2: the corner lies ahead of u (s > 0) and behind v (t < 0).
        const double s = cross(pv - pu, d2) / sine, t = cross(pv - pu, d1) / sine;
        if (!(s > 0.0) || !(t < 0.0)) return std::nullopt;
        const Vec2 corner = pu + s * d1;
        const Vec2 mid = 0.5 * (pu + pv);
        if (!(dot(corner - mid, normal) > 0.0) ||
            distance(corner, mid) > max_bracket_distance * chain_.length(u))
            return std::nullopt;
        return corner;
    }

    /// Root finding on every bracket with a sign change, in batched rounds.
    void solve(std::vector<Candidate>& candidates) {
        std::vector<Bracket> brackets;
        std::vector<std::size_t> owner;
        for (std::size_t k = 0; k < candidates.size(); ++k) {
            Candidate& c = candidates[k];
            if (std::abs(c.g_probe) <= options_.resolved_eta()) {
                c.has_root = true;
                c.root = c.probe;
            } else if ((c.g_probe > 0.0) != (c.g_near > 0.0)) {
                brackets.push_back({c.near, c.probe, c.g_near, c.g_probe});
                owner.push_back(k);
            }
        }
        const std::vector<Root> roots = find_roots(g_, brackets,
                                                   {.eta = options_.resolved_eta(),
                                                    .method = options_.root_method,
                                                    .jump_slope = jump_slope_factor * topo_.gamma});
        for (std::size_t k = 0; k < roots.size(); ++k) {
            // A stalled root (G jumps across zero) is no vertex of a refined contour.
            candidates[owner[k]].has_root = roots[k].converged;
            candidates[owner[k]].root = roots[k].point;
        }
    }

    /// Safeguards, then insertion, one candidate at a time in vertex order so that each sees the
    /// vertices its predecessors added. Returns the number of vertices added.
    std::size_t accept(const std::vector<Candidate>& candidates) {
        // Whether a root may leave its segment's triangle does not depend on the other splits:
        // that safeguard goes first, on all threads.
        std::vector<std::uint8_t> allowed(candidates.size());
        parallel_for(candidates.size(), [&](std::size_t i) {
            const Candidate& c = candidates[i];
            allowed[i] =
                c.has_root && (options_.triangle_safeguard && !c.at_corner && !chain_.unbound[c.u]
                                   ? in_allowed_triangle(chain_.home[c.u], c.root)
                                   : domain_.contains(c.root));
        });
        std::size_t added = 0;
        for (std::size_t i = 0; i < candidates.size(); ++i) {
            const Candidate& c = candidates[i];
            if (!allowed[i] || !split_is_safe(c.u, c.root)) {
                chain_.frozen[c.u] = 1;
                if (!c.has_root) rootless_.push_back(c.u);
                ++report_.rejected;
                continue;
            }
            const std::uint32_t w = chain_.insert_after(c.u, c.root);
            if (c.at_corner) {
                corners_.resize(chain_.points.size());
                corners_[w] = 1;
            }
            grid_->insert(c.u);
            grid_->insert(w);
            ++added;
        }
        report_.splits += added;
        return added;
    }

    /// The safeguards that depend on the splits accepted before: angles and crossings.
    bool split_is_safe(std::uint32_t u, Vec2 w) const {
        const std::uint32_t v = chain_.next[u];
        const Vec2 pu = chain_.points[u], pv = chain_.points[v];
        if (is_sharp(pu, chain_.points[chain_.prev[u]], w) ||
            is_sharp(pv, chain_.points[chain_.next[v]], w) || is_sharp(w, pu, pv)) {
            return false;
        }
        const std::array<std::uint32_t, 2> skip_uw{chain_.prev[u], u}, skip_wv{u, v};
        return !grid_->crosses({pu, w}, skip_uw) && !grid_->crosses({w, pv}, skip_wv);
    }

    /// |∇Q| of the linear interpolant Q of G in triangle t: an O(h) estimate of |∇G| there.
    double slope(std::uint32_t t) const {
        const auto& mesh = topo_.mesh;
        const auto& tri = mesh.triangles[t];
        const Vec2 a = mesh.vertices[tri[0]], ab = mesh.vertices[tri[1]] - a,
                   ac = mesh.vertices[tri[2]] - a;
        const double gb = topo_.values[tri[1]] - topo_.values[tri[0]];
        const double gc = topo_.values[tri[2]] - topo_.values[tri[0]];
        const double det = cross(ab, ac);
        return norm(Vec2{gb * ac.y - gc * ab.y, gc * ab.x - gb * ac.x} / det);
    }

    /// A new vertex may stay in its segment's home triangle or move to an adjacent (edge-sharing)
    /// triangle in which G does not change sign (an empty one), and must stay in the domain.
    bool in_allowed_triangle(std::uint32_t home, Vec2 w) const {
        if (!domain_.contains(w)) return false;
        const auto& mesh = topo_.mesh;
        const auto& tri = mesh.triangles[home];
        const Vec2 a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
        const double area = cross(b - a, c - a);
        const double wa = cross(b - w, c - w) / area, wb = cross(c - w, a - w) / area;
        if (wa >= -triangle_slack && wb >= -triangle_slack && 1.0 - wa - wb >= -triangle_slack)
            return true;
        const std::uint32_t t = locate(topo_.tree, mesh, w).triangle;
        if (t == home) return true;
        if (topo_.crossed[t]) return false;
        int shared = 0;
        for (std::uint32_t p : tri)
            for (std::uint32_t q : mesh.triangles[t]) shared += p == q ? 1 : 0;
        return shared == 2;
    }

    /// Prune step: removes an end of every segment shorter than ρ times both neighbours (the end
    /// whose other segment is shorter, so that the merged segment is the shorter choice, unless
    /// that end is a corner placed by refinement: then the other end, if it is none), when
    /// the merged segment passes the angle and crossing safeguards. Returns the number removed.
    std::size_t prune() {
        if (options_.rho == 0.0) return 0;
        std::size_t removed = 0;
        for (std::uint32_t u = 0; u < chain_.points.size(); ++u) {
            if (!chain_.alive[u] || chain_.curve_size[chain_.curve[u]] <= 3) continue;
            const std::uint32_t v = chain_.next[u];
            const double before = chain_.length(chain_.prev[u]), after = chain_.length(v);
            if (!(chain_.length(u) < options_.rho * std::min(before, after))) continue;
            // A corner that refinement placed is kept: the segment loses its other end.
            std::uint32_t x = before <= after ? u : v;
            if (is_corner(x)) x = x == u ? v : u;
            if (is_corner(x) || !merge_is_safe(x)) continue;
            const std::uint32_t a = chain_.prev[x];
            chain_.remove(x);
            grid_->insert(a);
            ++removed;
        }
        report_.pruned += removed;
        return removed;
    }

    bool is_corner(std::uint32_t x) const { return x < corners_.size() && corners_[x] != 0; }

    bool merge_is_safe(std::uint32_t x) const {
        const std::uint32_t a = chain_.prev[x], b = chain_.next[x];
        const Vec2 pa = chain_.points[a], pb = chain_.points[b];
        if (is_sharp(pa, chain_.points[chain_.prev[a]], pb) ||
            is_sharp(pb, chain_.points[chain_.next[b]], pa))
            return false;
        const std::array<std::uint32_t, 4> skip{chain_.prev[a], a, x, b};
        return !grid_->crosses({pa, pb}, skip);
    }

    std::optional<double> max_midpoint_value() const {
        double worst = 0.0;
        for (std::uint32_t i = 0; i < chain_.points.size(); ++i) {
            if (!chain_.alive[i]) continue;
            if (std::isnan(chain_.mid_value[i])) return std::nullopt;
            worst = std::max(worst, std::abs(chain_.mid_value[i]));
        }
        return worst;
    }

    Chain& chain_;
    BatchFunctionRef g_;
    const Topology& topo_;
    Box domain_;
    const ContourOptions& options_;
    double eps_;
    std::optional<SegmentGrid> grid_;
    std::vector<std::uint8_t> corners_;  ///< vertices placed at a corner (corner_of), by number
    /// Segments of this pass whose split was refused with no zero in their bracket: the
    /// candidates of part_bridges.
    std::vector<std::uint32_t> rootless_;
    RefineReport report_;
};

}  // namespace

RefineReport refine(Chain& chain, BatchFunctionRef g, const Topology& topo, const Box& domain,
                    const ContourOptions& options) {
    if (chain.points.empty()) return {};
    return Refiner(chain, g, topo, domain, options).run();
}

}  // namespace slc::contouring
