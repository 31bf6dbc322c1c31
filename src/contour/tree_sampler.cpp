// The topology tree of contouring (paper §2.1) in the plane and in space: G sampled at the
// cells' corners and centres, stand-ins from donors and bounds, and γ doubled until the tree is
// 2:1 balanced. Instantiated for dim = 2 and 3.
#include "tree_sampler.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/stop.hpp"

namespace slc::contouring {

template <int dim>
TreeSampler<dim>::TreeSampler(const Tree& tree, FunctionRef g, std::optional<BoundsRef> bounds,
                              std::optional<double> distance_slack, double rounding, double eta,
                              int limit)
    : tree_(tree),
      grid_(tree),
      g_(g),
      bounds_(bounds),
      slack_(distance_slack ? std::optional(*distance_slack + rounding) : std::nullopt),
      rounding_(rounding),
      eta_(eta),
      limit_(limit) {
    // Room for the samples of a large contour up front: pages are touched only as the samples
    // come, and the arrays are never copied as they grow.
    samples_.reserve(reserved_samples);
    points_.reserve(reserved_samples);
}

template <int dim>
void TreeSampler<dim>::sample(std::span<const std::uint32_t> cells) {
    CellSamples none;
    none.fill(no_sample);
    cell_samples_.resize(tree_.size(), none);
    // Numbers the points in cell order, then works out the new points' stand-ins cell by cell on
    // all threads: each new point's donors are the samples of the parent of the first cell that
    // meets it, which the parent has before the call.
    std::vector<std::uint16_t> fresh(cells.size(), 0);  // per cell, a bit per new sample
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const std::uint32_t c = cells[i];
        const std::uint32_t parent = c == 0 ? Tree::no_cell : tree_.cell(c).parent;
        SLC_ASSERT(parent == Tree::no_cell || has_samples(parent),
                   "a cell is sampled after its parent");
        const Keys keys = sample_keys(c);
        for (std::size_t j = 0; j < keys.n; ++j) {
            const auto [id, is_new] =
                parent == Tree::no_cell ? add_point(keys, j) : child_point(c, keys, j);
            cell_samples_[c][j] = id;
            if (is_new) fresh[i] |= static_cast<std::uint16_t>(1u << j);
        }
    }
    parallel_for(
        cells.size(),
        [&](std::size_t i) {
            if (fresh[i] == 0 || cells[i] == 0) return;  // the root has no donors
            const auto donors = samples_of(tree_.cell(cells[i]).parent);
            for (std::size_t j = 0; j < cell_points; ++j) {
                if ((fresh[i] >> j & 1u) == 0) continue;
                const std::uint32_t id = cell_samples_[cells[i]][j];
                if (const auto stand_in = from_donors(points_[id], donors))
                    samples_[id] = *stand_in;
            }
        },
        parallel_grain);
    std::vector<std::uint32_t> open;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        for (std::size_t j = 0; j < cell_points; ++j) {
            const std::uint32_t id = cell_samples_[cells[i]][j];
            if ((fresh[i] >> j & 1u) != 0 && std::isnan(samples_[id].value)) open.push_back(id);
        }
    }
    evaluate(apply_bounds(open));
    cell_min_.resize(tree_.size(), infinity);
    parallel_for(cells.size(), [&](std::size_t i) { update_min(cells[i]); });
}

template <int dim>
void TreeSampler<dim>::settle_tests(std::span<const std::uint32_t> cells, double gamma) {
    if (!slack_ && !bounds_) return;  // no stand-ins: every sample is G
    std::vector<std::uint32_t> touched;
    for (std::uint32_t c : cells) {
        const int level = tree_.cell(c).level;
        // The cell's least value may also be stale: a neighbour's test resolved a stand-in it
        // shares.
        if (level < limit_ && gamma * tree_.edge(level) > cell_min_[c]) touched.push_back(c);
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

template <int dim>
auto TreeSampler<dim>::sample_keys(std::uint32_t c, bool with_centre) const -> Keys {
    using Coords = typename SampleGrid<dim>::Coords;
    const auto& cell = tree_.cell(c);
    const std::uint64_t u = grid_.units(cell.level);
    Coords lo, centre;
    for (int i = 0; i < dim; ++i) {
        lo[i] = cell.coords[i] * u;
        centre[i] = lo[i] + u / 2;
    }
    Keys keys;
    for (std::uint32_t j = 0; j < Tree::children; ++j) {
        keys.at[j] = lo;
        for (int i = 0; i < dim; ++i) keys.at[j][i] += ((j >> i) & 1u) * u;
    }
    keys.at[Tree::children] = centre;
    for (std::size_t j = 0; j < cell_points; ++j) keys.k[j] = SampleGrid<dim>::key(keys.at[j]);
    const bool has_centre = with_centre || centres_at_depth_limit || cell.level < tree_.max_depth();
    keys.n = has_centre ? cell_points : cell_points - 1;
    return keys;
}

template <int dim>
std::uint32_t TreeSampler<dim>::add_pending(const Keys& keys, std::size_t j) {
    samples_.push_back(pending);
    points_.push_back(grid_.point(keys.at[j]));
    return static_cast<std::uint32_t>(samples_.size() - 1);
}

template <int dim>
std::pair<std::uint32_t, bool> TreeSampler<dim>::add_point(const Keys& keys, std::size_t j) {
    const auto [id, is_new] =
        index_.try_emplace(keys.k[j], static_cast<std::uint32_t>(samples_.size()));
    if (is_new) add_pending(keys, j);
    return {*id, is_new};
}

template <int dim>
std::pair<std::uint32_t, bool> TreeSampler<dim>::child_point(std::uint32_t c, const Keys& keys,
                                                             std::size_t j) {
    if (j == Tree::children) {
        const std::uint32_t id = add_pending(keys, j);
        if constexpr (centres_in_table) index_.try_emplace(keys.k[j], id);
        return {id, true};
    }
    const auto& cell = tree_.cell(c);
    const std::uint32_t k = c - tree_.cell(cell.parent).first_child;
    // Along axis i the corner is at 0, 1 or 2 half parent edges: at 0 or 2 along every axis it
    // is the parent's corner, at 1 along every axis its centre; otherwise it is on the parent's
    // boundary, where a neighbour's children may have added it.
    int halves = 0;
    std::uint32_t corner = 0;
    for (int i = 0; i < dim; ++i) {
        const std::uint32_t a = ((k >> i) & 1u) + ((j >> i) & 1u);
        if (a == 1) ++halves;
        corner |= (a / 2) << i;
    }
    const CellSamples& parent = cell_samples_[cell.parent];
    if (halves == 0) return {parent[corner], false};
    if (halves == dim) {
        if constexpr (!centres_in_table)
            if (centres_as_corners_) index_.try_emplace(keys.k[j], parent[Tree::children]);
        return {parent[Tree::children], false};
    }
    return add_point(keys, j);
}

template <int dim>
template <class F>
void TreeSampler<dim>::for_needed_stand_ins(std::span<const std::uint32_t> touched, double gamma,
                                            F f) {
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

template <int dim>
double TreeSampler<dim>::reach(Point x, std::uint32_t id) const {
    // |r| to within two ulps, which the slack covers; std::hypot where r·r would lose digits to
    // underflow (in a root box some 1e-146 across). Overflow (a box 1e154 across) makes the
    // reach infinite: no bound, as safe.
    const Point r = x - points_[id];
    const double rr = dot(r, r);
    return (rr > 1e-290 ? std::sqrt(rr) : norm(r)) + *slack_;
}

template <int dim>
std::optional<Sample> TreeSampler<dim>::from_donors(Point x,
                                                    std::span<const std::uint32_t> ids) const {
    if (!slack_) return std::nullopt;
    double lower = 0.0, sign = 0.0, upper = infinity;
    for (const std::uint32_t id : ids) {
        const Sample& donor = samples_[id];
        if (std::isnan(donor.value)) continue;  // pending: not known yet
        const double r = reach(x, id);
        const double b = std::abs(donor.value) - r;
        if (b > lower) {
            lower = b;
            sign = donor.value;
        }
        upper = std::min(upper, donor.upper + r);
    }
    if (!certain(lower)) return std::nullopt;
    return Sample{std::copysign(lower, sign), upper, Source::parents};
}

template <int dim>
bool TreeSampler<dim>::signed_by_donors(Point x, std::span<const std::uint32_t> ids) const {
    if (!slack_) return false;
    // from_donors' lower bound is the largest of 0 and the donors' bounds, certain above η.
    for (const std::uint32_t id : ids) {
        const double value = samples_[id].value;
        if (!std::isnan(value) && certain(std::max(0.0, std::abs(value) - reach(x, id))))
            return true;
    }
    return false;
}

template <int dim>
std::vector<std::uint32_t> TreeSampler<dim>::apply_bounds(std::vector<std::uint32_t> ids) {
    if (!bounds_ || ids.empty()) return ids;
    const std::vector<Point> points = points_of(ids);
    std::vector<Interval> bounds(points.size());
    (*bounds_)(points, bounds);
    bound_evals_ += points.size();
    std::vector<std::uint32_t> left;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        Sample& s = samples_[ids[i]];
        const auto [lo, hi] = bounds[i];
        // An interval that excludes 0 gives G's sign and |G| at least its end nearer 0; a NaN,
        // or ends out of order, say nothing.
        const bool valid = lo <= hi;
        const double lower = valid ? (lo > 0.0 ? lo : (hi < 0.0 ? -hi : 0.0)) - rounding_ : 0.0;
        const double upper = valid ? std::max(std::abs(lo), std::abs(hi)) + rounding_ : infinity;
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

template <int dim>
auto TreeSampler<dim>::points_of(std::span<const std::uint32_t> ids) const -> std::vector<Point> {
    std::vector<Point> points;
    points.reserve(ids.size());
    for (std::uint32_t id : ids) points.push_back(points_[id]);
    return points;
}

template <int dim>
void TreeSampler<dim>::update_min(std::uint32_t c) {
    double m = infinity;
    for (std::uint32_t id : samples_of(c)) m = std::min(m, std::abs(samples_[id].value));
    cell_min_[c] = m;
}

template <int dim>
void TreeSampler<dim>::evaluate(std::span<const std::uint32_t> ids) {
    if (ids.empty()) return;
    const std::vector<Point> points = points_of(ids);
    std::vector<double> values(points.size());
    g_(points, values);
    for (std::size_t i = 0; i < ids.size(); ++i)
        samples_[ids[i]] = Sample{values[i], std::abs(values[i]), Source::g};
}

namespace {

/// Splits, level by level from the frontier (sampled cells), every cell above the sampler's
/// limit whose edge exceeds min|G|/γ, sampling each new level in one batch.
template <int dim>
void split_while_coarse(Orthtree<dim>& tree, TreeSampler<dim>& sampler,
                        std::vector<std::uint32_t> frontier, double gamma) {
    while (!frontier.empty()) {
        sampler.settle_tests(frontier, gamma);
        std::vector<std::uint32_t> children;
        for (std::uint32_t c : frontier) {
            const int level = tree.cell(c).level;
            if (level < sampler.limit() && gamma * tree.edge(level) > sampler.min_abs(c)) {
                const std::uint32_t first = tree.split(c);
                for (std::uint32_t k = 0; k < Orthtree<dim>::children; ++k)
                    children.push_back(first + k);
            }
        }
        sampler.sample(children);
        frontier = std::move(children);
    }
}

}  // namespace

template <int dim>
double build_tree(Orthtree<dim>& tree, TreeSampler<dim>& sampler, double gamma) {
    sampler.sample(std::vector<std::uint32_t>{0});
    std::vector<std::uint32_t> frontier{0};
    for (int doubling = 0;; ++doubling) {
        check_stop();
        split_while_coarse(tree, sampler, std::move(frontier), gamma);
        if (tree.is_balanced()) return gamma;
        if (doubling == max_gamma_doublings) break;
        gamma *= 2.0;
        frontier.clear();
        for (std::uint32_t c : tree.leaves())
            if (tree.cell(c).level < sampler.limit()) frontier.push_back(c);
    }
    std::vector<std::uint32_t> children;
    tree.balance([&](std::size_t c) {
        for (std::uint32_t k = 0; k < Orthtree<dim>::children; ++k)
            children.push_back(tree.cell(c).first_child + k);
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

template <int dim>
typename TreeSampler<dim>::Bend TreeSampler<dim>::bends(std::uint32_t c,
                                                        std::vector<std::uint32_t>& wanted) const {
    constexpr std::size_t corners = cell_points - 1;
    const CellSamples& ids = cell_samples_[c];
    const int level = tree_.cell(c).level;
    const double edge = tree_.edge(level);
    const double half_diagonal = 0.5 * std::sqrt(static_cast<double>(dim)) * edge;
    const Sample& m = samples_[ids[corners]];
    if (std::abs(m.value) > half_diagonal) return Bend::no;
    if (m.upper > half_diagonal) {
        wanted.push_back(ids[corners]);
        return Bend::unsure;
    }
    bool unsure = false;
    // Whether G at the middle one of three equally spaced samples on a line, the ends of one
    // sign and the middle of theirs or within η of zero, is nearer zero than the ends' mean by
    // more than thin_dip of half the span; unsure is set, and the stand-ins that would settle it
    // wanted, when the bounds leave it open.
    auto dips = [&](std::uint32_t a, std::uint32_t mid, std::uint32_t b, double half_span) {
        const Sample &sa = samples_[a], &sm = samples_[mid], &sb = samples_[b];
        const bool positive = sa.value > 0.0;
        if ((sb.value > 0.0) != positive) return false;
        if ((sm.value > 0.0) != positive && !(std::abs(sm.value) <= eta_)) return false;
        // |G| ≥ |value| and ≤ upper at each point, with the value's sign.
        const double threshold = thin_dip * half_span;
        const double least = 0.5 * (std::abs(sa.value) + std::abs(sb.value)) - sm.upper;
        const double most = 0.5 * (sa.upper + sb.upper) - std::abs(sm.value);
        if (least > threshold) return true;
        if (most > threshold) {
            unsure = true;
            for (const std::uint32_t id : {a, mid, b})
                if (!samples_[id].is_exact()) wanted.push_back(id);
        }
        return false;
    };
    // The diagonals through the centre.
    for (std::size_t k = 0; k < corners / 2; ++k)
        if (dips(ids[k], ids[corners], ids[corners - 1 - k], half_diagonal)) return Bend::yes;
    // The grid lines through the corners, with the corners an edge away on both sides (this
    // cell's and a neighbour's at its level): a part thinner than a cell that crosses the line
    // beside a corner bends G there, where no diagonal need see it.
    const Keys keys = sample_keys(c);
    const std::uint64_t u = grid_.units(level);
    for (std::size_t j = 0; j < corners; ++j) {
        for (int i = 0; i < dim; ++i) {
            if (keys.at[j][i] < u || keys.at[j][i] + u > grid_.extent()) continue;
            auto lo = keys.at[j], hi = keys.at[j];
            lo[i] -= u;
            hi[i] += u;
            const std::uint32_t* a = index_.find(SampleGrid<dim>::key(lo));
            const std::uint32_t* b = index_.find(SampleGrid<dim>::key(hi));
            if (a != nullptr && b != nullptr && dips(*a, ids[j], *b, edge)) return Bend::yes;
        }
    }
    return unsure ? Bend::unsure : Bend::no;
}

template <int dim>
void TreeSampler<dim>::make_exact(std::vector<std::uint32_t> ids,
                                  std::span<const std::uint32_t> cells) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (std::uint32_t id : ids) samples_[id] = pending;
    evaluate(ids);
    for (std::uint32_t c : cells) update_min(c);
}

template <int dim>
std::size_t TreeSampler<dim>::settled() const {
    return static_cast<std::size_t>(std::count_if(samples_.begin(), samples_.end(),
                                                  [](const Sample& s) { return !s.is_exact(); }));
}

template <int dim>
ThinSplit split_thin(Orthtree<dim>& tree, TreeSampler<dim>& sampler, double gamma) {
    using Bend = typename TreeSampler<dim>::Bend;
    const int limit = sampler.limit();
    const std::size_t budget = thin_cell_budget * tree.size();
    ThinSplit out;
    std::vector<std::uint32_t> frontier;
    for (std::uint32_t c : tree.leaves())
        if (tree.cell(c).level == limit && gamma * tree.edge(limit) > sampler.min_abs(c))
            frontier.push_back(c);
    std::size_t& split = out.cells;
    while (!frontier.empty() && tree.cell(frontier.front()).level < tree.max_depth()) {
        check_stop();
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
        // The zero set runs on from a cell where G bends into its neighbours: those of the
        // frontier where G changes sign split too, so that a thin part is followed where it
        // crosses a cell between two corners of one sign, beside a corner inside it.
        std::sort(frontier.begin(), frontier.end());
        const std::size_t bending = bent.size();
        for (std::size_t i = 0; i < bending; ++i) {
            for (int d = 0; d < 2 * dim; ++d) {
                const std::uint32_t n = tree.neighbour(bent[i], d);
                if (n != Orthtree<dim>::no_cell &&
                    std::binary_search(frontier.begin(), frontier.end(), n) &&
                    sampler.changes_sign(n))
                    bent.push_back(n);
            }
        }
        std::sort(bent.begin(), bent.end());
        bent.erase(std::unique(bent.begin(), bent.end()), bent.end());
        if (bent.size() > budget - split) {
            bent.resize(budget - split);
            out.budget_reached = true;
        }
        std::vector<std::uint32_t> next;
        for (std::uint32_t c : bent) {
            const std::uint32_t first = tree.split(c);
            for (std::uint32_t k = 0; k < Orthtree<dim>::children; ++k) next.push_back(first + k);
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
    return out;
}

template class TreeSampler<2>;
template class TreeSampler<3>;
template double build_tree(Orthtree<2>&, TreeSampler<2>&, double);
template double build_tree(Orthtree<3>&, TreeSampler<3>&, double);
template ThinSplit split_thin(Orthtree<2>&, TreeSampler<2>&, double);
template ThinSplit split_thin(Orthtree<3>&, TreeSampler<3>&, double);

}  // namespace slc::contouring
