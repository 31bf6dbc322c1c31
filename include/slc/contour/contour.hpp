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

#include "slc/contour/contour_options.hpp"
#include "slc/contour/contour_stats.hpp"
#include "slc/contour/implicit_function.hpp"
#include "slc/contour/root_finding.hpp"
#include "slc/core/box.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc {

/// Parameters of contour() (paper Table 4; DESIGN §4): contour_options.hpp.
using ContourOptions = BasicContourOptions<2>;

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
    /// Strips that refinement removed where the interpolant linked two parts across a gap
    /// narrower than a cell, G between them having the other sign (part_bridges: two particles
    /// a sub-cell gap apart kept two, a wall thinner than a cell kept whole).
    std::size_t parted = 0;
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
