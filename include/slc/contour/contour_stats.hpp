/// @file
/// What a contour cost and what it produced, in the fields that mean the same for curves and for
/// surfaces; ContourStats (contour.hpp) and SurfaceContourStats (surface_contour.hpp) add what
/// each dimension has of its own. `slc contour` and Python's contour functions report them under
/// the same keys (contour_stats_json in slc/io/summary.hpp).
#pragma once

#include <cstddef>

#include "slc/core/space.hpp"

namespace slc {

/// The statistics of a contour in dimension dim (2 or 3) that both dimensions share.
template <int dim>
struct BasicContourStats {
    std::size_t cells = 0;       ///< cells of the topology tree, all levels (as the paper counts)
    std::size_t leaves = 0;      ///< leaves of the topology tree
    std::size_t thin_cells = 0;  ///< cells split beyond K where G bends (thin_depth)
    /// Cells that bend were left whole: thin cells are at most twice as many as the cells at K.
    bool thin_budget_reached = false;
    double finest_cell = 0.0;  ///< the edge of the tree's finest cells, thin cells included
    /// Closed components of the contour less than a finest cell across, dropped where cells went
    /// beyond K: below what the mesh resolves (a speck beside a convex corner, or where the
    /// corner of a non-convex Wulff shape leaves G a loop).
    std::size_t specks = 0;
    PointOf<dim> finest_at{};  ///< the centre of the first of them
    std::size_t vertices = 0;  ///< vertices of the result

    std::size_t g_evals = 0;         ///< all evaluations of G, each point counted once
    std::size_t g_evals_tree = 0;    ///< of which: the tree, its mesh's vertices and perturbation
    std::size_t g_evals_roots = 0;   ///< of which: root finding on the mesh's edges
    std::size_t g_evals_refine = 0;  ///< of which: adaptive refinement (midpoints, brackets, roots)
    double g_evals_per_vertex = 0.0;  ///< g_evals / vertices; 0 for an empty result
    /// Tree points that distance_slack, the bounds or the gradient bound settled without
    /// evaluating G.
    std::size_t settled = 0;
    std::size_t bound_evals = 0;  ///< evaluations of the bounds (not counted in g_evals)
    double gamma = 0.0;           ///< the gradient bound γ at which the tree was balanced

    std::size_t perturbed = 0;  ///< mesh vertices moved off |G| ≤ η
    /// Surfaces: mesh vertices moved across the zero set to keep the shape's topology
    /// (BasicContourOptions::keep_topology).
    std::size_t moved_across = 0;
    /// Roots left with |G| > η: G jumps across zero there (a continuous G never does this).
    std::size_t unconverged_roots = 0;
    int passes = 0;            ///< refinement passes that split something
    std::size_t splits = 0;    ///< vertices added by refinement
    std::size_t rejected = 0;  ///< split candidates refused (no bracket, or a safeguard)
};

}  // namespace slc
