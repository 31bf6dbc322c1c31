// The stages of contour_surface() (paper §2 in space), internal to the contour module: G
// evaluated and checked, and adaptive refinement of the linear contour (§2.2).
#pragma once

#include <cstddef>
#include <span>

#include "slc/contour/implicit_function.hpp"
#include "slc/contour/root_finding.hpp"
#include "slc/geometry/surface.hpp"

namespace slc::contouring {

/// G evaluated in batches, counted, and checked finite: a non-finite value is NumericalFailure
/// naming the point, so that no NaN reaches a sign test.
class SpaceEvaluator {
public:
    SpaceEvaluator(SpaceFunctionRef g, std::size_t& count) : g_(g), count_(&count) {}
    void operator()(std::span<const Vec3> points, std::span<double> values) const;

private:
    SpaceFunctionRef g_;
    std::size_t* count_;
};

/// What refinement did.
struct SurfaceRefinement {
    int passes = 0;             ///< passes that split something
    std::size_t splits = 0;     ///< edges split (a vertex added on the zero set)
    std::size_t rejected = 0;   ///< splits refused by a safeguard (never retried)
    std::size_t collapses = 0;  ///< needle edges collapsed
    std::size_t flips = 0;      ///< edges flipped
    /// 1 when refinement stopped because a pass found no midpoint or centroid beyond ε.
    std::size_t converged = 0;
    /// The largest |G| at the edge midpoints and the centroids the last pass evaluated.
    double residual = 0.0;
};

/// Adaptive refinement of a closed surface on the zero set of G (§2.2 in space): up to `passes`
/// passes (until converged when negative, at most max_passes). Each pass first improves the
/// triangles' shapes — needle edges collapsed, edges flipped to the Delaunay rule, no triangle
/// turned more than 30° — then splits every edge whose
/// midpoint has |G| > ε and the longest edge of every triangle whose centroid has |G| > ε. The
/// new vertex is the root of G along the surface's normal at the midpoint: Newton's step as if G
/// were a distance, then a secant step, then brackets out to two edge lengths. Safeguards refuse a
/// split, for good, when no root is found within reach, when a triangle it makes turns more than
/// 60° from its parent or loses its area, or when the triangles it makes meet the rest of the
/// surface; the surface stays closed, manifold and oriented. Throws LimitExceeded naming ε when the
/// vertices would pass max_vertices.
SurfaceRefinement refine_surface(Surface& s, const SpaceEvaluator& g, double eps,
                                 const RootOptions& roots, int passes, int max_passes,
                                 std::size_t max_vertices);

}  // namespace slc::contouring
