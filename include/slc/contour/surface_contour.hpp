/// @file
/// Contouring in space (paper §2 with d = 3, DESIGN §8): the zero surface of a function G given
/// only by evaluation, as a closed, oriented triangle surface. Topology resolution as in the
/// plane: an octree split where |G| is small against γ times the cell's edge (γ doubled until
/// the tree is 2:1 balanced), its conforming tetrahedral mesh (tetrahedralize()), G at the mesh
/// vertices, vertices with |G| ≤ η moved off zero, and the zero set of the piecewise-linear
/// interpolant: one or two triangles a tetrahedron, their vertices the roots of G on the
/// tetrahedra's edges (find_roots). A root depends only on its edge, which the tetrahedra around
/// it share, so the surface is watertight and manifold by construction, and its triangles face
/// the side where G > 0 (outward for a signed distance negative inside). Adaptive refinement
/// (§2.2) then splits edges until G at every edge midpoint and triangle centroid is within ε, the
/// new vertices roots of G along the surface's normal, under safeguards that keep the surface
/// closed, manifold, oriented and free of crossings.
#pragma once

#include <cstddef>
#include <optional>

#include "slc/contour/contour_stats.hpp"
#include "slc/contour/implicit_function.hpp"
#include "slc/contour/root_finding.hpp"
#include "slc/core/box3.hpp"
#include "slc/geometry/surface.hpp"

namespace slc {

/// Parameters of contour_surface (paper Table 4, as ContourOptions in the plane).
struct SurfaceContourOptions {
    /// refine_passes value meaning: refine until no midpoint or centroid exceeds ε, or a pass
    /// changes nothing, but at most max_refine_passes passes.
    static constexpr int until_converged = -1;

    /// K: deepest level of the topology octree, 0..max_tetrahedralized_depth.
    int depth = 5;
    /// P ≥ 0, or until_converged: passes of adaptive refinement (§2.2); 0 is the linear contour.
    int refine_passes = 0;
    /// ε ≥ η: refinement splits edges whose midpoint, and triangles whose centroid, has
    /// |G| > ε; default 10^−K.
    std::optional<double> eps = std::nullopt;
    /// Cap on the passes of until_converged.
    int max_refine_passes = 64;
    /// Refinement that would pass this many vertices throws LimitExceeded naming ε.
    std::size_t max_vertices = std::size_t{1} << 23;
    /// η > 0: root-finding tolerance, |G| ≤ η at every vertex; mesh vertices with |G| ≤ η
    /// are moved off zero. Unset (the default): resolved_eta().
    std::optional<double> eta = std::nullopt;
    /// γ > 0: starting estimate of the gradient bound |∇G| ≤ γ, doubled until the tree balances.
    double gamma = 1.0;
    /// Levels beyond K, 0..(max_tetrahedralized_depth − K), for cells at depth K near the zero
    /// set where G bends within the cell — its centre nearer zero than the mean of the ends of a
    /// body diagonal by more than a quarter of the half-diagonal, all three of one sign, which a
    /// distance does not do on one side of a sheet curved less than about two cells: a thin part,
    /// two sheets in near contact, a sharp edge or a tight curve. Such cells split again, up to
    /// K + thin_depth, so that the linear contour has both sides of what it would otherwise miss
    /// or cut across. 0 (the default) keeps every leaf at depth K or above; Enright's test,
    /// whose sheet thins below a cell, takes 2 (docs/surfaces.md).
    int thin_depth = 0;
    /// Refinement follows creases, for G the distance of a surface of flat facets (a user's
    /// mesh): an edge whose midpoint lies off the zero set by more than L/64 and whose profile
    /// along the normal at its quarters and midpoint is two lines (a fold of the surface) is split
    /// where the lines meet, on the crease, and the children of the triangles across it lie on
    /// its two sides, where halving edges that cross a crease only halves their error. A split
    /// refused is tried again once a split beside it changed its triangles. Should that leave a
    /// part beyond ε (slivers about a vertex where several creases meet), plain refinement of
    /// the linear contour is kept instead if it comes nearer. Off (the default) for the steps of
    /// a run, whose G rounds what a crease would sharpen (docs/surfaces.md).
    bool creases = false;
    /// How brackets are shrunk.
    RootMethod root_method = RootMethod::brent;
    /// δ ≥ 0, when the caller can guarantee |G(x) − G(y)| ≤ |x − y| + δ for all x and y: 0 for a
    /// signed distance, 2k·max|W| for the semi-Lagrangian formula. Tree points where a nearby
    /// sample's value already bounds |G| above the split threshold are then not evaluated (the
    /// bound, with its certain sign, stands in), so cells far from the zero set cost no
    /// evaluation. The surface is the one exact values give, bit for bit. Unset (the default):
    /// every tree point is evaluated.
    std::optional<double> distance_slack = std::nullopt;

    /// η when ε is not refined to: the linear contour's vertices on the zero set to 10⁻¹⁰.
    static constexpr double default_eta = 1e-10;
    /// η as given; unset, default_eta for the linear contour (P = 0), and max(default_eta, ε/100)
    /// when refinement follows. Refinement holds G within ε at every edge midpoint and centroid,
    /// so vertices within ε/100 change the surface's error by at most a hundredth of ε, and
    /// roots found to that tolerance rather than 10⁻¹⁰ cost about one evaluation of G fewer per
    /// split (docs/tables/table3_3d.md).
    double resolved_eta() const;
    /// ε as given, or its default 10^−K.
    double resolved_eps() const;
};

/// What a surface contour cost and what it produced: the fields both dimensions share
/// (BasicContourStats), and the surfaces' own.
struct SurfaceContourStats : BasicContourStats<3> {
    /// Closed components of the linear contour less than a finest cell across, dropped when
    /// cells went beyond K (a speck beside a convex corner).
    std::size_t specks = 0;
    std::size_t tetrahedra = 0;  ///< tetrahedra of its mesh
    std::size_t triangles = 0;   ///< triangles of the result
    std::size_t collapses = 0;   ///< needle edges collapsed by refinement
    std::size_t flips = 0;       ///< edges flipped by refinement
    bool converged = false;      ///< refinement stopped with no midpoint or centroid beyond ε
    /// The largest |G| refinement saw at the edge midpoints and centroids of its last pass: at
    /// most ε when converged; 0 without refinement.
    double residual = 0.0;
};

/// A contoured surface and its statistics.
struct SurfaceContour {
    Surface surface;            ///< the contour: closed, oriented, its vertices on the zero set
    SurfaceContourStats stats;  ///< what contouring it took
};

/// Contours the zero set of G inside domain (a cube). The result is a closed surface (possibly
/// empty, possibly several components) whose triangles face G > 0; its vertices satisfy
/// |G| ≤ η (SurfaceContourOptions::resolved_eta). Deterministic: the same for any thread count.
/// Throws InvalidInput for bad options or a domain that is not a cube; LeftDomain when the zero set
/// reaches the domain's boundary; NumericalFailure when G is not finite somewhere it is evaluated,
/// or stays within η of zero around a mesh vertex.
SurfaceContour contour_surface(SpaceFunctionRef g, const Box3& domain,
                               const SurfaceContourOptions& options);

/// The same surface, bit for bit, with a cheaper function that bounds G, as contour() takes in
/// the plane: tree points whose sign no nearby sample gives are offered to bounds, one batch per
/// level, and G is evaluated only where neither gives what a split test, the thin-cell test or a
/// tetrahedron where G changes sign needs.
SurfaceContour contour_surface(SpaceFunctionRef g, const Box3& domain,
                               const SurfaceContourOptions& options, SpaceBoundsRef bounds);

}  // namespace slc
