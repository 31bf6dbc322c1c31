/// @file
/// The geometry module of surfaces (paper §3 with d = 3): outward unit normals and mean curvature
/// C = −∇·N at the vertices of a closed triangle surface (−2/R on a sphere of radius R), from a
/// quadric fitted by least squares to each vertex's neighbours within two rings of edges, and
/// the area that belongs to each vertex, for integrals over the surface (the volume-preserving
/// flow, paper Eq. 13 in space).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "slc/core/vec3.hpp"
#include "slc/geometry/surface.hpp"

namespace slc {

/// Geometry of a surface at its vertices, indexed like Surface::vertices. Signs as in DESIGN §8:
/// normals point outward (towards F > 0); C = −∇·N, the sum of the principal curvatures, −2/R on
/// a sphere of radius R.
struct SurfaceGeometry {
    std::vector<Vec3> normals;      ///< outward unit normal N_i at vertex i
    std::vector<double> curvature;  ///< C_i at vertex i, −2/R on a sphere of radius R
};

/// What surface_geometry() computes and how.
struct SurfaceGeometryOptions {
    bool curvature = true;  ///< compute C as well as N
    /// σ ≥ 0: the curvature is replaced by its Gaussian mean of width σ along the surface (the
    /// vertices within 3σ, weighted by exp(−d²/2σ²) and their areas). An explicit step of mean
    /// curvature flow of size k needs σ of order √k to be stable when k is large against h², as
    /// for curves (a mode of wavenumber ω grows by 1 − kω² e^{−σ²ω²/2}: stable for σ > 0.61 √k).
    /// 0: none. Cost: the vertices within 3σ of each.
    double smoothing = 0.0;
};

/// Normals and (if asked) mean curvature at every vertex of s. At each vertex the neighbours
/// within two rings are written in a frame whose third axis is the angle-weighted normal, and the
/// height function w = a u² + b uv + c v² + d u + e v fitted by least squares (weights 1/|q−p|²);
/// N is the fitted graph's normal at the vertex and C its mean-curvature sum
/// ((1 + e²) 2a − 2de·b + (1 + d²) 2c) / (1 + d² + e²)^{3/2}. Exact for quadrics in the frame;
/// O(h) on general meshes, O(h²) on meshes that are locally symmetric. A vertex with fewer than
/// five neighbours, or an ill-conditioned fit, keeps the angle-weighted normal and takes the
/// curvature of the spheres through it tangent to its normal, averaged over its one-ring.
/// Precondition: a valid surface. Throws InvalidInput for a negative or infinite smoothing. O(N),
/// in parallel.
SurfaceGeometry surface_geometry(const Surface& s, const SurfaceGeometryOptions& options = {});

/// Outward unit vertex normals: the angle-weighted mean of the incident triangles' normals.
std::vector<Vec3> angle_weighted_normals(const Surface& s);

/// The area that belongs to each vertex: a third of each incident triangle's. Weights of the
/// rule ∫_S g dA ≈ Σ g_i w_i, exact for g linear on each triangle.
std::vector<double> vertex_areas(const Surface& s);

/// The area mean Σ g_i w_i / Σ w_i of vertex values g, w the vertex_areas. Precondition:
/// g.size() == s.vertices.size() > 0 and s has positive area.
double area_mean(const Surface& s, std::span<const double> g);

/// The vertices joined to each vertex by an edge, in compressed rows: neighbours of vertex i are
/// ring[start[i]] .. ring[start[i + 1] − 1], in increasing order.
struct VertexRings {
    std::vector<std::size_t> start;   ///< size vertices + 1
    std::vector<std::uint32_t> ring;  ///< the neighbours, row by row
    /// The neighbours of vertex i.
    std::span<const std::uint32_t> of(std::size_t i) const {
        return {ring.data() + start[i], ring.data() + start[i + 1]};
    }
};

/// The one-ring of every vertex of s. O(N).
VertexRings vertex_rings(const Surface& s);

}  // namespace slc
