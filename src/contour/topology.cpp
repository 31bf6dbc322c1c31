// Topology resolution (paper §2.1): the K-level tree split by min|G|/γ with γ doubled until the
// tree is 2:1 balanced, G on its triangulation, perturbation of vertices where |G| ≤ η, the
// boundary check, and marching triangles into closed polygons with G > 0 on their right.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/core/key_map.hpp"
#include "slc/core/parallel.hpp"
#include "stages.hpp"

namespace slc::contouring {
namespace {

/// After this many doublings of γ (a factor of about 10^7) the tree is balanced by brute force
/// instead: G has a gradient far beyond any estimate, or no useful one.
constexpr int max_gamma_doublings = 24;
/// Perturbation: the first displacement is this fraction of the finest cell edge, doubled at each
/// attempt. After max_perturbations attempts it is 3.2% of that edge: far below the 35% of the
/// edge that the smallest triangle altitude allows, so the triangulation stays valid.
constexpr double first_perturbation = 1e-3;
constexpr int max_perturbations = 6;

/// Integer coordinates on the grid of half the finest cell edge (fan_leaves() names vertices by
/// them), with the formula triangulate() uses to place its vertices: the triangulation's vertices
/// are the sample points themselves, and G is never evaluated twice at one point.
class SampleGrid {
public:
    explicit SampleGrid(const Quadtree& tree)
        : lo_(tree.root_box().lo),
          shift_(tree.max_depth() + 1),
          step_(tree.edge(0) / static_cast<double>(std::uint64_t{1} << shift_)) {}

    std::uint64_t units(int level) const { return std::uint64_t{1} << (shift_ - level); }
    std::uint64_t extent() const { return std::uint64_t{1} << shift_; }
    Vec2 point(std::uint64_t gx, std::uint64_t gy) const {
        return {lo_.x + static_cast<double>(gx) * step_, lo_.y + static_cast<double>(gy) * step_};
    }
    static std::uint64_t key(std::uint64_t gx, std::uint64_t gy) { return (gx << 32) | gy; }

private:
    Vec2 lo_;
    int shift_;
    double step_;
};

/// Where a sample's value comes from: G itself, or a stand-in from the parent's samples or
/// from the caller's bounds (after which only G can tighten it).
enum class Source : std::uint8_t { g, parents, bounds };
/// G at a point, or a stand-in: a lower bound on |G| with G's sign, and an upper bound.
struct Sample {
    double value;
    double upper;  ///< |G| ≤ upper: |value| when exact
    Source source;
    std::uint32_t vertex = no_vertex;  ///< its number in the triangulation, once numbered
};
/// A point in the batch for G.
constexpr Sample pending{std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::infinity(), Source::g};

/// G at the corners and centres of the tree's cells, each point evaluated at most once, in one
/// batch per call, and the smallest |G| over each cell's sample points. Cells at the depth limit
/// are never tested for splitting, so their centres wait for complete_centres().
///
/// A point is evaluated only when a split test, the sign of a triangle or root finding needs G
/// there. With ContourOptions::distance_slack δ, |G(x) − G(y)| ≤ |x − y| + δ, so a new point x
/// near a known sample y has |G(y)| − |x − y| − δ ≤ |G(x)| ≤ |G(y)| + |x − y| + δ and, when the
/// lower bound is positive, G(y)'s sign; the caller's bounds on G, one batch, are tried next.
/// Where either gives the sign, the lower bound with that sign stands in for G, beside the upper
/// bound. A cell's test needs no value where some sample's upper bound is below its threshold
/// γ·edge (it splits), nor where a stand-in's lower bound reaches it; the stand-ins it does need
/// are offered to the caller's bounds, then evaluated. So every split decision is the one exact
/// values give, and stand-ins left in triangles where G changes sign are evaluated before the
/// contour is marched.
///
/// The samples live in one array, and every cell keeps the ids of its samples, so the split
/// tests, the donors and the triangulation read them without a search. A new cell's corners are
/// its parent's corners and centre, or midpoints of its parent's edges, which a neighbour's
/// children may share: only those are looked up in a table of keys. A cell's centre is its own
/// (its children's corners reach it through their parent), and so is never in the table.
/// The new points' stand-ins are worked out on all threads, each from the first cell that
/// meets it, so they are the same for any thread count.
class TreeSampler {
public:
    TreeSampler(BatchFunctionRef g, std::optional<BatchBoundsRef> bounds, const Quadtree& tree,
                const ContourOptions& options, double rounding)
        : g_(g),
          bounds_(bounds),
          tree_(tree),
          grid_(tree),
          slack_(options.distance_slack ? std::optional(*options.distance_slack + rounding)
                                        : std::nullopt),
          rounding_(rounding),
          eta_(options.eta) {
        // Room for the samples of a large contour up front: pages are touched only as the
        // samples come, and the arrays are never copied as they grow.
        samples_.reserve(reserved_samples);
        keys_.reserve(reserved_samples);
    }

    /// Samples the given cells (the root, or children of split cells): new points whose sign
    /// neither their parent's samples nor the bounds (one batch) give are evaluated, in one batch.
    void sample(std::span<const std::uint32_t> cells) {
        cell_samples_.resize(tree_.size(), no_samples);
        // Numbers the points in cell order, then works out the new points' stand-ins cell by
        // cell on all threads: each new point's donors are the samples of the parent of the
        // first cell that meets it, which the parent has before the call.
        std::vector<std::uint8_t> fresh(cells.size(), 0);  // per cell, a bit per new sample
        for (std::size_t i = 0; i < cells.size(); ++i) {
            const std::uint32_t c = cells[i];
            const std::uint32_t parent = c == 0 ? Quadtree::no_cell : tree_.cell(c).parent;
            SLC_ASSERT(parent == Quadtree::no_cell || has_samples(parent),
                       "a cell is sampled after its parent");
            const Keys keys = sample_keys(c);
            for (std::size_t j = 0; j < keys.n; ++j) {
                const auto [id, is_new] = parent == Quadtree::no_cell
                                              ? add_point(keys.k[j])
                                              : child_point(c, j, keys.k[j]);
                cell_samples_[c][j] = id;
                if (is_new) fresh[i] |= static_cast<std::uint8_t>(1u << j);
            }
        }
        parallel_for(
            cells.size(),
            [&](std::size_t i) {
                if (fresh[i] == 0 || cells[i] == 0) return;  // the root has no donors
                const Donors donors = donors_of(samples_of(tree_.cell(cells[i]).parent));
                for (std::size_t j = 0; j < 5; ++j) {
                    if ((fresh[i] >> j & 1u) == 0) continue;
                    const std::uint32_t id = cell_samples_[cells[i]][j];
                    if (const auto stand_in = from_donors(point(id), donors))
                        samples_[id] = *stand_in;
                }
            },
            parallel_grain);
        std::vector<std::uint32_t> open;
        for (std::size_t i = 0; i < cells.size(); ++i) {
            for (std::size_t j = 0; j < 5; ++j) {
                const std::uint32_t id = cell_samples_[cells[i]][j];
                if ((fresh[i] >> j & 1u) != 0 && std::isnan(samples_[id].value)) open.push_back(id);
            }
        }
        evaluate(apply_bounds(open));
        cell_min_.resize(tree_.size(), infinity);
        parallel_for(cells.size(), [&](std::size_t i) { update_min(cells[i]); });
    }

    /// Before the cells are tested against γ: resolves the stand-ins on which a test would rest,
    /// so each test sees what exact values would decide. The parents' stand-ins among them are
    /// offered to the bounds first (one batch); those still below the threshold are evaluated
    /// (one batch).
    void settle_tests(std::span<const std::uint32_t> cells, double gamma) {
        std::vector<std::uint32_t> touched;
        for (std::uint32_t c : cells) {
            const int level = tree_.cell(c).level;
            // The cell's least value may also be stale: a neighbour's test resolved a stand-in
            // it shares.
            if (level < tree_.max_depth() && gamma * tree_.edge(level) > cell_min_[c])
                touched.push_back(c);
        }
        if (bounds_) {
            std::vector<std::uint32_t> ids;
            for_needed_stand_ins(touched, gamma, [&](std::uint32_t id, Sample& s) {
                if (s.source != Source::parents) return;
                s.source = Source::bounds;  // offered once
                ids.push_back(id);
            });
            apply_bounds(ids);
        }
        std::vector<std::uint32_t> ids;
        for_needed_stand_ins(touched, gamma, [&](std::uint32_t id, Sample& s) {
            s = pending;
            ids.push_back(id);
        });
        evaluate(ids);
        for (std::uint32_t c : touched) update_min(c);
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
        keys_.resize(first + finest.size());
        parallel_for(finest.size(), [&](std::size_t i) {
            const std::uint32_t c = finest[i];
            const auto id = static_cast<std::uint32_t>(first + i);
            std::array<std::uint32_t, 5>& ids = cell_samples_[c];
            ids[4] = id;
            keys_[id] = sample_keys(c, true).k[4];
            double lo = infinity, hi = -infinity;
            for (int j = 0; j < 4; ++j) {
                lo = std::min(lo, samples_[ids[j]].value);
                hi = std::max(hi, samples_[ids[j]].value);
            }
            if (lo > clearance || hi < -clearance) {
                samples_[id] = Sample{lo > 0.0 ? lo : hi, infinity, Source::parents};
            } else if (const auto stand_in =
                           from_donors(point(id), donors_of(std::span(ids).first(4)))) {
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

    /// Whether cell c has been sampled: sample() needs every cell's parent sampled first.
    bool has_samples(std::uint32_t c) const {
        return c < cell_samples_.size() && cell_samples_[c][0] != no_sample;
    }
    double min_abs(std::uint32_t c) const { return cell_min_[c]; }
    std::size_t bound_evals() const { return bound_evals_; }

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
                topo.mesh.vertices.push_back(grid_.point(gx, gy));
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
                const std::uint32_t* id = index_.find(SampleGrid::key(gx, gy));
                return id == nullptr ? no_vertex : number(samples_[*id], gx, gy);
            },
            topo.mesh);
    }

private:
    static constexpr double infinity = std::numeric_limits<double>::infinity();

    /// A cell's sample points: corners, then the centre when the cell can be split (or always,
    /// with with_centre).
    struct Keys {
        std::array<std::uint64_t, 5> k;
        std::size_t n;
    };
    Keys sample_keys(std::uint32_t c, bool with_centre = false) const {
        const auto& cell = tree_.cell(c);
        const std::uint64_t u = grid_.units(cell.level), x0 = cell.coords[0] * u,
                            y0 = cell.coords[1] * u;
        const bool centre = with_centre || cell.level < tree_.max_depth();
        return {{SampleGrid::key(x0, y0), SampleGrid::key(x0 + u, y0), SampleGrid::key(x0, y0 + u),
                 SampleGrid::key(x0 + u, y0 + u), SampleGrid::key(x0 + u / 2, y0 + u / 2)},
                centre ? 5u : 4u};
    }
    /// The sample ids of cell c: its corners, then its centre when the cell can be split.
    std::span<const std::uint32_t> samples_of(std::uint32_t c) const {
        return std::span(cell_samples_[c]).first(tree_.cell(c).level < tree_.max_depth() ? 5 : 4);
    }
    /// The id of the sample at key, and whether it is new (then pending for G).
    std::pair<std::uint32_t, bool> add_point(std::uint64_t key) {
        const auto [id, fresh] =
            index_.try_emplace(key, static_cast<std::uint32_t>(samples_.size()));
        if (fresh) {
            samples_.push_back(pending);
            keys_.push_back(key);
        }
        return {*id, fresh};
    }
    /// A new point that no other cell shares: the centre of a cell, which only its children's
    /// corners (found through their parent's samples) meet again. It stays out of the table.
    std::uint32_t add_centre(std::uint64_t key) {
        samples_.push_back(pending);
        keys_.push_back(key);
        return static_cast<std::uint32_t>(samples_.size() - 1);
    }
    /// Sample j of child c, as add_point(key) would give it: of the nine corners of its
    /// parent's four children, the parent's corners and centre are its samples already, and
    /// only the midpoints of its edges, which the children of a neighbour may have added, are
    /// looked up in the table; the child's centre is new.
    std::pair<std::uint32_t, bool> child_point(std::uint32_t c, std::size_t j, std::uint64_t key) {
        if (j == 4) return {add_centre(key), true};
        const auto& cell = tree_.cell(c);
        const std::uint32_t k = c - tree_.cell(cell.parent).first_child;
        const std::uint32_t a = (k & 1u) + (j & 1u), b = (k >> 1) + (j >> 1);  // in 0..2
        const auto& parent = cell_samples_[cell.parent];
        if (a != 1 && b != 1) return {parent[a / 2 + b], false};
        if (a == 1 && b == 1) return {parent[4], false};
        return add_point(key);
    }
    Vec2 point(std::uint32_t id) const {
        const std::uint64_t k = keys_[id];
        return grid_.point(k >> 32, k & 0xffffffffu);
    }

    /// Calls f(id, sample) once for each stand-in that the test of a touched cell needs: one
    /// whose lower bound is below the cell's threshold, in a cell where no sample's upper bound
    /// is below it.
    template <class F>
    void for_needed_stand_ins(std::span<const std::uint32_t> touched, double gamma, F f) {
        for (std::uint32_t c : touched) {
            const double threshold = gamma * tree_.edge(tree_.cell(c).level);
            const auto ids = samples_of(c);
            if (std::any_of(ids.begin(), ids.end(),
                            [&](std::uint32_t id) { return samples_[id].upper < threshold; })) {
                continue;  // the cell splits whatever G is at its stand-ins
            }
            for (std::uint32_t id : ids) {
                Sample& s = samples_[id];
                if (s.source != Source::g && std::abs(s.value) < threshold) f(id, s);
            }
        }
    }

    /// Known samples near a new point: where they are and G (or a stand-in) there.
    struct Donors {
        std::array<Vec2, 5> at;
        std::array<double, 5> value;
        std::array<double, 5> upper;
        std::size_t n = 0;
    };
    Donors donors_of(std::span<const std::uint32_t> ids) const {
        Donors d;
        if (!slack_) return d;
        for (std::uint32_t id : ids) {
            const Sample& s = samples_[id];
            if (std::isnan(s.value)) continue;
            d.at[d.n] = point(id);
            d.upper[d.n] = s.upper;
            d.value[d.n++] = s.value;
        }
        return d;
    }
    /// The donors' bounds on G at x: a stand-in when they give its sign.
    std::optional<Sample> from_donors(Vec2 x, const Donors& donors) const {
        double lower = 0.0, sign = 0.0, upper = infinity;
        for (std::size_t i = 0; i < donors.n; ++i) {
            const Vec2 r = x - donors.at[i];  // |r| to within an ulp, which the slack covers
            const double reach = std::sqrt(dot(r, r)) + *slack_;
            const double b = std::abs(donors.value[i]) - reach;
            if (b > lower) {
                lower = b;
                sign = donors.value[i];
            }
            upper = std::min(upper, donors.upper[i] + reach);
        }
        if (!certain(lower)) return std::nullopt;
        return Sample{std::copysign(lower, sign), upper, Source::parents};
    }
    /// A lower bound of |G| gives G's sign, and a stand-in, when it exceeds η (so that the point
    /// is never a perturbation candidate).
    bool certain(double lower) const { return lower > eta_; }

    /// The bounds at the samples (one batch; none without bounds), widened by the rounding
    /// allowance, tighten their stand-ins, or make stand-ins of the points pending for G whose
    /// sign they give. Returns the samples still pending.
    std::vector<std::uint32_t> apply_bounds(std::vector<std::uint32_t> ids) {
        if (!bounds_ || ids.empty()) return ids;
        const std::vector<Vec2> points = points_of(ids);
        std::vector<Interval> bounds(points.size());
        (*bounds_)(points, bounds);
        bound_evals_ += points.size();
        std::vector<std::uint32_t> left;
        for (std::size_t i = 0; i < ids.size(); ++i) {
            Sample& s = samples_[ids[i]];
            const auto [lo, hi] = bounds[i];
            // An interval that excludes 0 gives G's sign and |G| at least its end nearer 0; a
            // NaN, or ends out of order, say nothing.
            const bool valid = lo <= hi;
            const double lower = valid ? (lo > 0.0 ? lo : (hi < 0.0 ? -hi : 0.0)) - rounding_ : 0.0;
            const double upper =
                valid ? std::max(std::abs(lo), std::abs(hi)) + rounding_ : infinity;
            if (s.source != Source::g) {
                // A stand-in already: both are true bounds, so they agree on a certain sign.
                if (certain(lower) && lower > std::abs(s.value))
                    s.value = std::copysign(lower, s.value);
                s.upper = std::min(s.upper, upper);
                s.source = Source::bounds;
            } else if (certain(lower)) {
                s = Sample{std::copysign(lower, lo), upper, Source::bounds};
            } else {
                left.push_back(ids[i]);
            }
        }
        return left;
    }
    std::vector<Vec2> points_of(std::span<const std::uint32_t> ids) const {
        std::vector<Vec2> points;
        points.reserve(ids.size());
        for (std::uint32_t id : ids) points.push_back(point(id));
        return points;
    }
    void update_min(std::uint32_t c) {
        double m = infinity;
        for (std::uint32_t id : samples_of(c)) m = std::min(m, std::abs(samples_[id].value));
        cell_min_[c] = m;
    }
    void evaluate(std::span<const std::uint32_t> ids) {
        if (ids.empty()) return;
        const std::vector<Vec2> points = points_of(ids);
        std::vector<double> values(points.size());
        g_(points, values);
        for (std::size_t i = 0; i < ids.size(); ++i)
            samples_[ids[i]] = Sample{values[i], std::abs(values[i]), Source::g};
    }

    /// Samples the arrays have room for before they first grow.
    static constexpr std::size_t reserved_samples = std::size_t{1} << 16;
    /// No sample yet: the centre of a cell at the depth limit before complete_centres().
    static constexpr std::uint32_t no_sample = 0xffffffffu;
    static constexpr std::array<std::uint32_t, 5> no_samples{no_sample, no_sample, no_sample,
                                                             no_sample, no_sample};

    BatchFunctionRef g_;
    std::optional<BatchBoundsRef> bounds_;
    std::size_t bound_evals_ = 0;
    const Quadtree& tree_;
    SampleGrid grid_;
    std::optional<double> slack_;
    double rounding_;
    double eta_;
    /// Every sample point: its key on the grid, G there or a stand-in, and its id in the table.
    std::vector<std::uint64_t> keys_;
    std::vector<Sample> samples_;
    KeyMap<std::uint32_t> index_;
    /// Per cell, the ids of its corners (in sample_keys() order) and centre.
    std::vector<std::array<std::uint32_t, 5>> cell_samples_;
    std::vector<double> cell_min_;
};

/// Splits, level by level from the frontier, every cell whose edge exceeds min|G|/γ, sampling
/// each new level in one batch.
void split_while_coarse(Quadtree& tree, TreeSampler& sampler, std::vector<std::uint32_t> frontier,
                        double gamma) {
    while (!frontier.empty()) {
        sampler.settle_tests(frontier, gamma);
        std::vector<std::uint32_t> children;
        for (std::uint32_t c : frontier) {
            const int level = tree.cell(c).level;
            if (level < tree.max_depth() && gamma * tree.edge(level) > sampler.min_abs(c)) {
                const std::uint32_t first = tree.split(c);
                for (std::uint32_t k = 0; k < 4; ++k) children.push_back(first + k);
            }
        }
        sampler.sample(children);
        frontier = std::move(children);
    }
}

/// The split criterion is monotone in γ, so the tree for 2γ refines the tree for γ: instead of
/// rebuilding from the root, the leaves are offered to the criterion again. Returns γ.
double build_tree(Quadtree& tree, TreeSampler& sampler, double gamma) {
    sampler.sample(std::vector<std::uint32_t>{0});
    std::vector<std::uint32_t> frontier{0};
    for (int doubling = 0;; ++doubling) {
        split_while_coarse(tree, sampler, std::move(frontier), gamma);
        if (tree.is_balanced()) return gamma;
        if (doubling == max_gamma_doublings) break;
        gamma *= 2.0;
        frontier.clear();
        for (std::uint32_t c : tree.leaves())
            if (tree.cell(c).level < tree.max_depth()) frontier.push_back(c);
    }
    std::vector<std::uint32_t> children;
    tree.balance([&](std::size_t c) {
        for (std::uint32_t k = 0; k < 4; ++k) children.push_back(tree.cell(c).first_child + k);
    });
    // balance() may split a cell it split itself: such children wait for their parent's samples.
    while (!children.empty()) {
        std::vector<std::uint32_t> ready, later;
        for (std::uint32_t c : children)
            (sampler.has_samples(tree.cell(c).parent) ? ready : later).push_back(c);
        sampler.sample(ready);
        children = std::move(later);
    }
    return gamma;
}

std::string place(Vec2 p) { return fmt::format("({:.6g}, {:.6g})", p.x, p.y); }

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

/// Moves interior vertices with |G| ≤ η (§2.1) until none is left; all such vertices of one
/// attempt are evaluated in one batch. Returns the number of vertices moved.
std::size_t perturb(Topology& topo, BatchFunctionRef g, double eta) {
    struct Pending {
        std::size_t vertex;
        Vec2 original;
    };
    auto& mesh = topo.mesh;
    const double h = topo.tree.edge(topo.tree.depth());
    std::vector<Pending> todo;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (std::abs(topo.values[v]) <= eta) todo.push_back({v, mesh.vertices[v]});
    const std::size_t moved = todo.size();
    for (int k = 0; !todo.empty(); ++k) {
        if (k == max_perturbations) {
            throw NumericalFailure(fmt::format(
                "G vanishes (|G| <= eta = {}) at and around {} after {} perturbations up to "
                "{:.3g}: "
                "G and its gradient seem to vanish together, so the contour is ill-posed there",
                eta, place(todo.front().original), max_perturbations,
                first_perturbation * std::ldexp(h, max_perturbations - 1)));
        }
        std::vector<Vec2> points;
        for (const Pending& p : todo) {
            const double step = first_perturbation * std::ldexp(h, k);
            points.push_back(p.original + step * perturbation_direction(p.vertex, k));
        }
        std::vector<double> values(points.size());
        g(points, values);
        std::vector<Pending> left;
        for (std::size_t i = 0; i < todo.size(); ++i) {
            mesh.vertices[todo[i].vertex] = points[i];
            topo.values[todo[i].vertex] = values[i];
            if (std::abs(values[i]) <= eta) left.push_back(todo[i]);
        }
        todo = std::move(left);
    }
    return moved;
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
    Topology topo{Quadtree(domain, options.depth), {}, {}, {}, {}, options.gamma, 0, 0, 0};
    // Both bounds allow for rounding in G and in the bound: a few thousand ulps of the
    // coordinates.
    const double rounding = 1e-12 * std::max(domain.largest_magnitude(), domain.width());
    TreeSampler sampler(g, bounds, topo.tree, options, rounding);
    topo.gamma = build_tree(topo.tree, sampler, options.gamma);
    sampler.complete_centres(topo.gamma);
    topo.bound_evals = sampler.bound_evals();
    std::vector<std::uint8_t> on_boundary;
    sampler.triangulate(topo, on_boundary);
    check_boundary(topo, on_boundary, options.eta);
    topo.perturbed = perturb(topo, g, options.eta);
    topo.perturbed += evaluate_crossed_stand_ins(topo, g, options.eta);
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
