/// @file
/// The arclength geometry module: normals and curvature at the vertices of a polygon from the
/// circle through each vertex and its two neighbours, the curvature then averaged along the curve
/// over a width σ of arc length. No mesh; meant for curvature-driven motion, where an
/// explicit step of size k is stable only if the curvature it uses is averaged over about √k.
#pragma once

#include <cmath>

#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry_modules/vertex_geometry.hpp"

namespace slc {

/// The signed curvature of the circle through x − u, x and x + v (u, v nonzero): −1/R when the
/// three points run counterclockwise round it (C = −∇·N, as everywhere), 0 when they are in line.
inline double circle_curvature(Vec2 u, Vec2 v) {
    return -2.0 * cross(u, v) / (norm(u) * norm(v) * norm(u + v));
}

/// A vertex whose segments turn by more than this many radians is a corner of the polygon, not a
/// sample of a smooth curve: a step reads the curve as sharp there (StepOptions::arc_corner), and
/// the arclength module gives it the curvature of its turn (vertex_curvature).
inline constexpr double corner_turn = 0.5;

/// The curvature of the polygon at x, its segments u into x and v out of it: circle_curvature
/// where they turn by at most corner_turn, and at a corner the turn θ spread over the vertex's
/// half segments, −θ / ((|u| + |v|)/2), so that κ ds integrates to the turn. The circle through a
/// corner and its neighbours has a curvature of 2 sin θ / |u + v|, which makes κ ds at a corner
/// of 90° 10% short of its turn (26% at 150°), and curvature flow then moves a polygon's corners,
/// and its area, too slowly: a square's first step moved 86% of the law's area, and a step
/// of an L-shaped region with a hole closed off a speck (docs/notes/corners.md).
inline double vertex_curvature(Vec2 u, Vec2 v) {
    const double turn = turn_angle(u, v);
    if (std::abs(turn) <= corner_turn) return circle_curvature(u, v);
    return -2.0 * turn / (norm(u) + norm(v));
}

/// Vertex normals and curvature of every curve of Γ:
///
///     N_i = −(t_{i−1} + t_i)^⊥ / |t_{i−1} + t_i|     t_i the unit tangent of segment i
///     κ_i = −2 (u × v) / (|u| |v| |u + v|)            u = x_i − x_{i−1}, v = x_{i+1} − x_i
///         = −2 θ_i / (|u| + |v|) at a corner (|θ_i| > corner_turn, θ_i the turn from u to v)
///     C   = 2 G_σ κ − G_σ G_σ κ                        ("twicing")
///
/// κ_i is the signed curvature of the circle through x_{i−1}, x_i, x_{i+1} (−1/R on a circle, as
/// everywhere: C = −∇·N), and at a corner its turn over its half segments (vertex_curvature), so
/// that Σ κ_i ds_i over a closed simple polygon read as chords at its corners and as circles
/// elsewhere is −2π, as for the curve. G_σ averages a vertex field along its curve with the weights
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
