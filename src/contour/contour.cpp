// contour(): the three stages of fast adaptive contouring (paper §2, and the Contour step of §4.3)
// put together — topology resolution, root finding on triangle edges, adaptive refinement — with
// the validation of the options and the statistics.
#include "slc/contour/contour.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "options_check.hpp"
#include "rounding.hpp"
#include "slc/core/error.hpp"
#include "slc/geometry/segment.hpp"
#include "stages.hpp"
#include "tree_sampler.hpp"

namespace slc {
namespace {

void validate(const ContourOptions& o, const Box& domain) {
    contouring::check_options(o, Quadtree::max_supported_depth);
    const double w = domain.width();
    if (!(w > 0.0) || !std::isfinite(w) || !is_finite(domain.lo) || domain.height() != w) {
        throw InvalidInput(
            fmt::format("the contour domain must be a square of positive size, got "
                        "[{}, {}] x [{}, {}]",
                        domain.lo.x, domain.hi.x, domain.lo.y, domain.hi.y));
    }
}

void count_output(const Interface& curves, ContourStats& s) {
    s.curves = curves.curve_count();
    s.vertices = curves.size();
    s.segments = curves.size();
    s.mean_segment_length =
        curves.empty() ? 0.0 : length(curves) / static_cast<double>(curves.size());
    s.g_evals_per_vertex =
        curves.empty() ? 0.0 : static_cast<double>(s.g_evals) / static_cast<double>(curves.size());
}

/// The curves but those `drop(c, curve)` is true of (c the curve's index), added to `dropped`.
template <class Drop>
Interface drop_curves(Interface curves, Drop drop, std::size_t& dropped) {
    std::vector<std::vector<Vec2>> kept;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        const auto curve = curves.curve(c);
        if (!drop(c, curve)) kept.emplace_back(curve.begin(), curve.end());
    }
    if (kept.size() == curves.curve_count()) return curves;
    dropped += curves.curve_count() - kept.size();
    return Interface(kept);
}

/// Whether a curve's mean width 2|A|/L is below the root tolerance η: a loop that thin is not a
/// component but the sign of G flickering along a line where G jumps across zero without a
/// root (the medial axis of a curve about to vanish, where the step's feet part), and it has no
/// interior for the next step's distance to see.
bool is_sliver(std::span<const Vec2> curve, double eta) {
    return 2.0 * std::abs(signed_area(curve)) < eta * length(curve);
}

/// Whether a curve is less than `size` across (the larger side of its box): the rule of the
/// surfaces' drop_specks, for curves.
bool is_speck(std::span<const Vec2> curve, double size) {
    const Box b = bounding_box(curve);
    return std::max(b.hi.x - b.lo.x, b.hi.y - b.lo.y) < size;
}

/// Which curves are flecks: thinner than half the finest cell on the mean (2|A|/L), within two
/// finest cells of a curve that is not. The linear contour cuts such a piece off a sharp tip,
/// along which the part is thinner than the cells at any depth, or off the gap narrowing to
/// nothing where two parts meet (a hole beside the curve that bridges them); whatever made it, a
/// piece that thin that near is below what the cells resolve.
std::vector<std::uint8_t> flecks(const Interface& curves, double finest) {
    const std::size_t n = curves.curve_count();
    const double reach = 2.0 * finest;
    std::vector<double> area(n);
    std::vector<Box> box(n);
    std::vector<std::uint8_t> thin(n), fleck(n, 0);
    for (std::size_t c = 0; c < n; ++c) {
        area[c] = signed_area(curves.curve(c));
        box[c] = bounding_box(curves.curve(c));
        thin[c] = 4.0 * std::abs(area[c]) < finest * length(curves.curve(c));
    }
    const auto apart = [&](const Box& a, const Box& b) {
        return a.lo.x > b.hi.x + reach || b.lo.x > a.hi.x + reach || a.lo.y > b.hi.y + reach ||
               b.lo.y > a.hi.y + reach;
    };
    for (std::size_t c = 0; c < n; ++c) {
        if (!thin[c]) continue;
        for (std::size_t d = 0; d < n && !fleck[c]; ++d) {
            if (thin[d] || apart(box[c], box[d])) continue;
            for (std::size_t i = curves.offsets()[d]; i < curves.offsets()[d + 1] && !fleck[c];
                 ++i) {
                const Segment s = curves.segment(i);
                if (apart(box[c], bounding_box(s))) continue;
                for (const Vec2 p : curves.curve(c)) {
                    if (closest_point(s, p).distance2 < reach * reach) {
                        fleck[c] = 1;
                        break;
                    }
                }
            }
        }
    }
    return fleck;
}

/// contour() with or without bounds on G.
ContourResult contour_with(BatchFunctionRef g, const Box& domain, const ContourOptions& given,
                           std::optional<BatchBoundsRef> bounds) {
    validate(given, domain);
    const ContourOptions options = contouring::within_rounding(given, domain);
    ContourStats stats;
    std::size_t evaluations = 0;
    const contouring::CountingFunction counted(g, evaluations);

    contouring::Topology topo = contouring::resolve_topology(counted, domain, options, bounds);
    stats.g_evals_tree = evaluations;
    stats.cells = topo.tree.size();
    stats.leaves = topo.tree.leaves().size();
    stats.triangles = topo.mesh.triangles.size();
    stats.gamma = topo.gamma;
    stats.thin_cells = topo.thin_cells;
    stats.thin_budget_reached = topo.thin_budget_reached;
    stats.finest_cell = topo.tree.edge(topo.tree.depth());
    stats.finest_at = contouring::deepest_place(topo.tree);
    stats.perturbed = topo.perturbed;
    stats.settled = topo.settled;
    stats.bound_evals = topo.bound_evals;

    const contouring::LinearContour linear = contouring::march(topo);
    const std::vector<Root> roots = find_roots(
        counted, linear.brackets, {.eta = options.resolved_eta(), .method = options.root_method});
    stats.g_evals_roots = evaluations - stats.g_evals_tree;
    std::vector<Vec2> points(roots.size());
    for (std::size_t i = 0; i < roots.size(); ++i) {
        points[i] = roots[i].point;
        if (!roots[i].converged) ++stats.unconverged_roots;
    }

    contouring::Chain chain(std::move(points), linear.next, linear.triangle);
    // Refinement starts from the interpolant's curves joined where G joins them; the linear
    // contour (P = 0) stays the interpolant's zero set.
    if (options.refine_passes != 0)
        stats.joined = contouring::join_necks(chain, counted, topo, options);
    const contouring::RefineReport refined =
        contouring::refine(chain, counted, topo, domain, options);
    stats.g_evals_refine = evaluations - stats.g_evals_tree - stats.g_evals_roots;
    stats.passes = refined.passes;
    stats.splits = refined.splits;
    stats.rejected = refined.rejected;
    stats.pruned = refined.pruned;
    stats.parted = refined.parted;
    stats.max_midpoint_value = refined.max_midpoint_value;
    stats.g_evals = evaluations;

    const double eta = options.resolved_eta();
    Interface curves = drop_curves(
        chain.to_interface(), [&](std::size_t, auto curve) { return is_sliver(curve, eta); },
        stats.slivers);
    // As for surfaces: where cells went beyond K, a closed curve less than a finest cell across
    // is below what the mesh resolves (a loop of G at the corner of a non-convex Wulff shape,
    // which the thin cells of a user's curves would otherwise keep as a hole the law forbids).
    if (stats.thin_cells > 0) {
        const double finest = stats.finest_cell;
        curves = drop_curves(
            std::move(curves), [&](std::size_t, auto curve) { return is_speck(curve, finest); },
            stats.specks);
        const std::vector<std::uint8_t> fleck = flecks(curves, finest);
        curves = drop_curves(
            std::move(curves), [&](std::size_t c, auto) { return fleck[c] != 0; }, stats.specks);
    }
    count_output(curves, stats);
    return {std::move(curves), std::move(topo.tree), stats};
}

}  // namespace

ContourResult contour(BatchFunctionRef g, const Box& domain, const ContourOptions& options) {
    return contour_with(g, domain, options, std::nullopt);
}

ContourResult contour(BatchFunctionRef g, const Box& domain, const ContourOptions& options,
                      BatchBoundsRef bounds) {
    return contour_with(g, domain, options, bounds);
}

}  // namespace slc
