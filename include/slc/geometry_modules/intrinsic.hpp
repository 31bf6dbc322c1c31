/// @file
/// The intrinsic geometry module (paper §3.1): normals and curvature at the vertices of a polygon
/// from the left-right average difference along the curve, Equations (7) and (8), with no mesh.
#pragma once

#include "slc/geometry/interface.hpp"
#include "slc/geometry_modules/vertex_geometry.hpp"

namespace slc {

/// Vertex normals and curvature of every curve of Γ by the paper's left-right average difference
///
///     δg_i = ½ [ (g_{i+1} − g_i)/|x_{i+1} − x_i| + (g_i − g_{i−1})/|x_i − x_{i−1}| ],
///
///     N_i = −(δx_i)^⊥ / |δx_i|                (Eq. 7; outward: the right of the traversal)
///     C_i = −(N_i^⊥ · δN_i) / |δx_i|           (Eq. 8; C = −dθ/ds, so −1/R on a circle)
///
/// with (x, y)^⊥ = (−y, x). The paper's Eq. 7 has the opposite sign because its normal points
/// into a counterclockwise curve; ours points out (DESIGN §2). N_i bisects the angle between the
/// two segments' normals; it is first-order accurate on a smooth curve sampled at unequal
/// spacing and second order at equal spacing. C_i is exact (−1/R) at every vertex of a regular
/// polygon inscribed in a circle of radius R, but oscillates on irregular samplings (hence the
/// embedded module). O(N).
///
/// Throws InvalidInput when a vertex coincides with the next one. At a vertex where the curve
/// turns back on itself (δx_i = 0, impossible for a valid interface) N_i is the normal of the
/// outgoing segment and C_i is not finite.
VertexGeometry intrinsic_geometry(const Interface& curves);

}  // namespace slc
