/// @file
/// VertexGeometry: outward unit normals and curvature at the vertices of Γ, what both geometry
/// modules of paper §3 return, and the arc-length weights of the vertices for integrals over Γ
/// (the nonlocal law of paper Equation 13).
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// Geometry of Γ at its vertices, indexed like Interface::points(). Signs as in DESIGN §2:
/// normals point outward (towards F > 0), N = (cos θ, sin θ); curvature C = −∇·N, so C = −1/R
/// on a circle of radius R and +1/R on a circular hole.
struct VertexGeometry {
    std::vector<Vec2> normals;      ///< outward unit normal N_i at vertex i
    std::vector<double> curvature;  ///< C_i at vertex i, −1/R on a circle of radius R
    /// k, the time step the velocities are for (advance() sets it), or 0 outside a step: the
    /// stiff laws (potential_laws.hpp) damp the modes an explicit step of k would amplify.
    double step = 0.0;
};

/// The length of each segment i (from vertex i to next(i)). Throws InvalidInput, naming `module`
/// and the vertex, when a vertex coincides with the next one. O(N).
std::vector<double> segment_lengths(const Interface& curves, std::string_view module);

/// The arc length that belongs to each vertex: half of each of its two segments. Weights of the
/// trapezoidal rule ∫_Γ g ds ≈ Σ g_i w_i, which is exact for g linear on each segment. O(N).
std::vector<double> vertex_arc_lengths(const Interface& curves);

/// The arc-length mean Σ g_i w_i / Σ w_i of vertex values g over all of Γ, w the
/// vertex_arc_lengths, summed in vertex order. Precondition: g.size() == curves.size() > 0.
double arc_length_mean(const Interface& curves, std::span<const double> g);

}  // namespace slc
