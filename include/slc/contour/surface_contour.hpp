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

#include "slc/contour/contour_options.hpp"
#include "slc/contour/contour_stats.hpp"
#include "slc/contour/implicit_function.hpp"
#include "slc/contour/root_finding.hpp"
#include "slc/core/box3.hpp"
#include "slc/geometry/surface.hpp"

namespace slc {

/// Parameters of contour_surface (paper Table 4): contour_options.hpp, as ContourOptions in the
/// plane.
using SurfaceContourOptions = BasicContourOptions<3>;

/// What a surface contour cost and what it produced: the fields both dimensions share
/// (BasicContourStats), and the surfaces' own.
struct SurfaceContourStats : BasicContourStats<3> {
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
