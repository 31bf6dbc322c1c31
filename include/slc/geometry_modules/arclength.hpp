/// @file
/// The arclength geometry module: normals and curvature at the vertices of a polygon from the
/// circle through each vertex and its two neighbours, the curvature then averaged along the curve
/// over a width σ of arc length. No mesh; meant for curvature-driven motion, where an
/// explicit step of size k is stable only if the curvature it uses is averaged over about √k.
#pragma once

#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry_modules/vertex_geometry.hpp"

namespace slc {

/// The signed curvature of the circle through x − u, x and x + v (u, v nonzero): −1/R when the
/// three points run counterclockwise round it (C = −∇·N, as everywhere), 0 when they are in line.
inline double circle_curvature(Vec2 u, Vec2 v) {
    return -2.0 * cross(u, v) / (norm(u) * norm(v) * norm(u + v));
}

/// Vertex normals and curvature of every curve of Γ:
///
///     N_i = −(t_{i−1} + t_i)^⊥ / |t_{i−1} + t_i|     t_i the unit tangent of segment i
///     κ_i = −2 (u × v) / (|u| |v| |u + v|)            u = x_i − x_{i−1}, v = x_{i+1} − x_i
///     C   = 2 G_σ κ − G_σ G_σ κ                        ("twicing")
///
/// κ_i is the signed curvature of the circle through x_{i−1}, x_i, x_{i+1} (−1/R on a circle, as
/// everywhere: C = −∇·N). G_σ averages a vertex field along its curve with the weights
/// B(s/(√3 σ)) ds: s the arc length along the polygon from the vertex, ds half the two segments
/// at the other vertex, and B the cubic B-spline (support |s| < 2√3 σ, at most once around the
/// curve), whose standard deviation in s is σ and whose Fourier transform sinc⁴ is nonnegative,
/// as a Gaussian's. Averaging a constant returns it, so C is exact at every vertex of a polygon
/// inscribed in a circle, however unevenly spaced; twicing leaves a bias of O(σ⁴ C'''') on
/// other curves where G_σ alone leaves O(σ² C''). On a sampling of spacing h, κ_i is O(h)
/// accurate (O(h²) at even spacing). width = 0: C = κ, unsmoothed. The step uses σ = √k
/// (StepOptions::arc_width): an explicit step of curvature flow of size k is stable on any
/// polygon from σ = 0.76 √k (docs/algorithms/geometry.md).
///
/// Throws InvalidInput when width is negative or not finite, or a vertex coincides with the next
/// one. Cost O(N m), m the vertices within 2√3 σ of a vertex; parallel, the result does not depend
/// on the thread count.
VertexGeometry arclength_geometry(const Interface& curves, double width);

/// f averaged along each curve with cubic B-spline weights of standard deviation `width` in
/// arc length.
std::vector<double> average_along_curves(const Interface& curves, const std::vector<double>& f,
                                         double width);

}  // namespace slc
