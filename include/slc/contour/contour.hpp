/// @file
/// Fast adaptive contouring of any function (paper §2): the zero set of G, a function that can
/// only be evaluated, as closed oriented polygons with a consistent topology and a chosen accuracy.
///
/// 1. Topology (§2.1): a K-level quadtree split while a cell's edge exceeds min|G|/γ over its
///    corners and centre, γ doubled until the tree is 2:1 balanced; its conforming
///    triangulation; vertices with |G| ≤ η perturbed; the zero set of the piecewise-linear
///    interpolant, one segment per triangle with a sign change, chained into closed polygons with
///    G > 0 on their right.
/// 2. Root finding (§2.1 "Bisection"): every vertex moved along its triangle edge to |G| ≤ η.
/// 3. Adaptive refinement (§2.2), P passes, from the curves joined where the interpolant parted
///    what G does not: split segments with |G(midpoint)| > ε, bracket the new vertex along the
///    segment's normal (or, where it cuts a corner, towards the meeting of its neighbours' lines),
///    find the root, apply the safeguards, prune short segments.
///
/// docs/algorithms/contour.md derives each step and the choices made where the paper is terse.
#pragma once

#include <cstddef>
#include <optional>

#include "slc/contour/contour_stats.hpp"
#include "slc/contour/implicit_function.hpp"
#include "slc/contour/root_finding.hpp"
#include "slc/core/box.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc {

/// Parameters of contour() (paper Table 4; DESIGN §4).
struct ContourOptions {
    /// refine_passes value meaning: refine until no segment midpoint exceeds ε, or a pass changes
    /// nothing, but at most max_refine_passes passes.
    static constexpr int until_converged = -1;

    /// K: deepest level of the topology tree, 0..Quadtree::max_supported_depth.
    int depth = 6;
    /// P ≥ 0, or until_converged. Refinement also stops early when no midpoint exceeds ε or a
    /// pass changes nothing, so a large P runs to convergence too.
    int refine_passes = 0;
    /// ε: midpoint tolerance of refinement, ε ≥ η; default 10^−K. Neither can go below what
    /// doubles resolve in the domain, two ulps of its largest coordinate (2.2e−16 b in [−b, b]²):
    /// a given ε below it is InvalidInput, the default 10^−K and η are raised to it.
    std::optional<double> eps = std::nullopt;
    /// η > 0: root-finding tolerance, |G| ≤ η at every vertex. Unset (the default):
    /// default_eta, as for surfaces' linear contour (SurfaceContourOptions::eta).
    std::optional<double> eta = std::nullopt;
    /// Levels beyond K, 0..(Quadtree::max_supported_depth − K), for cells at depth K near the
    /// zero set where G bends within the cell — its centre nearer zero than the mean of the ends
    /// of a diagonal by more than a quarter of the half-diagonal, all three of one sign, which a
    /// distance does not do on one side of a curve turning less than about two cells: a thin
    /// part, two curves in near contact, a corner or a tight turn. Such cells split again, up to
    /// K + thin_depth, so that the linear contour has both sides of what it would otherwise miss
    /// or cut across (as SurfaceContourOptions::thin_depth). 0 (the default) keeps every leaf at
    /// depth K or above.
    int thin_depth = 0;
    /// ρ in [0, 1): prune segments shorter than ρ times both neighbours; 0 disables pruning.
    double rho = 0.1;
    /// γ > 0: starting estimate of the gradient bound |∇G| ≤ γ, doubled until the tree balances.
    double gamma = 1.0;
    /// Cap on the passes of until_converged.
    int max_refine_passes = 64;
    /// Refinement that would pass this many contour vertices throws LimitExceeded naming ε
    /// (about 100 bytes a vertex: 420 MB). A smooth curve of length L and curvature κ refined to
    /// ε needs about L·sqrt(κ/8ε) vertices: 2.2e7 for the unit circle at ε = 1e−14.
    std::size_t max_vertices = std::size_t{1} << 22;
    /// The paper's triangle safeguard: a vertex added by refinement may stay in its segment's
    /// triangle or move into an adjacent one where G has no sign change, no farther. Off, it may
    /// go as far as its bracket reaches (at most three segment lengths, and short of every other
    /// segment), the angle and crossing safeguards still keeping every curve simple and apart:
    /// refinement then finds the corners of the zero set that the tree's triangles cut off.
    bool triangle_safeguard = true;
    /// How brackets are shrunk: Brent (default), Illinois, or the paper's bisection.
    RootMethod root_method = RootMethod::brent;
    /// δ ≥ 0, when the caller can guarantee |G(x) − G(y)| ≤ |x − y| + δ for all x and y: 0 for a
    /// signed distance function, 2k·max|W| for the semi-Lagrangian formula. Tree points where a
    /// nearby sample's value already bounds |G| above the split threshold are then not evaluated
    /// (the bound, with its certain sign, stands in). The tree and the contour are those that
    /// exact values give. Unset (the default): every tree point is evaluated.
    std::optional<double> distance_slack = std::nullopt;

    /// η when none is given.
    static constexpr double default_eta = 1e-10;
    /// η as given, or default_eta.
    double resolved_eta() const { return eta.value_or(default_eta); }
    /// ε as given, or its default 10^−K.
    double resolved_eps() const;
};

/// What a contour of curves cost and what it produced: the fields both dimensions share
/// (BasicContourStats), and the curves' own.
struct ContourStats : BasicContourStats<2> {
    std::size_t triangles = 0;  ///< triangles of the tree's triangulation
    std::size_t curves = 0;     ///< closed polygons in the result
    std::size_t segments = 0;   ///< segments of the result (= vertices: every curve is closed)
    double mean_segment_length = 0.0;  ///< total length / segments; 0 for an empty result
    std::size_t pruned = 0;            ///< vertices removed by pruning
    /// Pairs of the interpolant's curves that refinement started from as one, G between them
    /// having the sign they enclose (a tip parted from its body at a neck narrower than a cell).
    std::size_t joined = 0;
    /// Closed polygons dropped as slivers: mean width 2|A|/L below η, the sign of G flickering
    /// along a line where G jumps across zero, not a component.
    std::size_t slivers = 0;
    /// Largest |G| at the midpoints of the final segments when the last refinement step evaluated
    /// them all (refinement ran to convergence); nullopt otherwise.
    std::optional<double> max_midpoint_value;
};

/// The contour, the topology tree it was resolved on (for pictures), and the statistics.
struct ContourResult {
    Interface curves;    ///< the zero set of G: closed polygons, G > 0 on the right
    Quadtree tree;       ///< the balanced topology tree
    ContourStats stats;  ///< cost and outcome
};

/// Contours the zero set of g in the square domain.
///
/// The result's curves are closed, simple and mutually disjoint polygons with G > 0 on the right
/// of each (counterclockwise around regions where G < 0), every vertex with |G| ≤ η unless
/// stats.unconverged_roots > 0. After refinement to convergence every segment midpoint has
/// |G| ≤ ε except for segments whose split the safeguards refused (stats.rejected). A G without
/// a zero in the domain gives an empty Interface.
///
/// Cost: about one evaluation per tree cell (O(2^K) cells for a curve of bounded length), 2–3 per
/// vertex for root finding, about 4 per vertex added by refinement; all handed to g in batches.
/// Besides G, O(1) work per cell and per vertex (about 2 µs per output vertex).
/// Throws InvalidInput for an invalid option or a domain that is not a square of positive size;
/// NumericalFailure, naming the place, when the contour reaches the boundary of the domain, when
/// repeated perturbation cannot move a vertex off the zero set (G and ∇G vanish together: the
/// problem is ill-posed), or when g returns a value that is not finite.
ContourResult contour(BatchFunctionRef g, const Box& domain, const ContourOptions& options = {});

/// The same contour, bit for bit, with a cheaper function that bounds G: bounds sets each value
/// to an Interval holding G at that point ({−∞, ∞}: nothing known; rounding in G and in the
/// bounds is allowed for here). Tree points whose sign no nearby sample gives
/// (ContourOptions::distance_slack) are offered to bounds, one batch per level. G is evaluated at
/// a tree point only where neither gives its sign, where a split test needs more than the bounds
/// (neither |G| at or above the cell's threshold, nor some sample's |G| below it), or at a vertex
/// of a triangle where G changes sign. For the semi-Lagrangian formula G(x) = F(x − D(x)) with
/// |D(x)| ≤ d(x), F(x) ± d(x) are such bounds, at one distance query instead of G's several.
ContourResult contour(BatchFunctionRef g, const Box& domain, const ContourOptions& options,
                      BatchBoundsRef bounds);

}  // namespace slc
