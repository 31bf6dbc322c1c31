/// @file
/// Surface: a closed oriented triangle surface in space (DESIGN §8), the 3D counterpart of
/// Interface; its measures (area, enclosed volume, components, Euler characteristic, genus); the
/// angle-weighted pseudo-normals that give the sign of the distance at edges and corners
/// (Bærentzen and Aanæs, "Signed distance computation using the angle weighted pseudonormal",
/// IEEE TVCG 2005); and the brute-force signed closest point, the oracle of the distance tree.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/core/vec3.hpp"
#include "slc/geometry/triangle3.hpp"

namespace slc {

/// Three vertex indices of a triangle, counterclockwise seen from outside.
using TriangleIndices = std::array<std::uint32_t, 3>;

/// Triangles over shared vertices. A valid surface (prepare_surface) is closed, edge- and
/// vertex-manifold, consistently oriented with outward normals (F < 0 inside), free of
/// degenerate triangles and of self-intersections; it may have several components and handles.
struct Surface {
    std::vector<Vec3> vertices;              ///< the points
    std::vector<TriangleIndices> triangles;  ///< indices into vertices

    /// Number of triangles.
    std::size_t size() const { return triangles.size(); }
    /// True when there are no triangles.
    bool empty() const { return triangles.empty(); }
    /// The corners of triangle t.
    Triangle3 triangle(std::size_t t) const {
        const TriangleIndices& i = triangles[t];
        return {vertices[i[0]], vertices[i[1]], vertices[i[2]]};
    }
};

/// Total area. O(N).
double area(const Surface& s);
/// Enclosed volume by the divergence theorem: positive for outward orientation. O(N).
double volume(const Surface& s);
/// The sign of the volume a closed surface encloses, decided exactly: +1 facing outward, −1
/// inward, 0 only when the exact sum is zero (no valid surface). A floating-point sum with an
/// error bound decides almost always; a shell thinner than rounding (1e−17 of its size), or
/// coordinates small enough for the products to underflow, take exact_volume_sign. O(N).
int volume_sign(const Surface& s);
/// The smallest box holding every vertex used by a triangle.
Box3 bounding_box(const Surface& s);

/// The half-edges of s bucketed by their lower vertex: half-edge 3t + k runs from corner k to
/// corner k + 1 of triangle t; bucket v, halves[start[v]] to halves[start[v + 1] − 1], holds
/// the pairs (higher vertex, half-edge) of the half-edges whose lower vertex is v, sorted, so
/// the two half-edges of an edge of a closed surface are side by side. O(N + V), on all
/// threads, the same for any number of them.
struct HalfEdgeBuckets {
    std::vector<std::uint32_t> start;                             ///< V + 1 offsets
    std::vector<std::pair<std::uint32_t, std::uint32_t>> halves;  ///< 3N pairs
};
/// The half-edges of s by lower vertex (HalfEdgeBuckets).
HalfEdgeBuckets half_edges_by_lower_vertex(const Surface& s);

/// For each triangle and each of its edges k (corner k to corner k + 1), the triangle across
/// that edge. Precondition: every edge is shared by exactly two triangles (a valid surface).
/// O(N + V) for V vertices.
std::vector<std::array<std::uint32_t, 3>> triangle_neighbours(const Surface& s);
/// The same from s's half-edges already bucketed (half_edges_by_lower_vertex(s)).
std::vector<std::array<std::uint32_t, 3>> triangle_neighbours(const Surface& s,
                                                              const HalfEdgeBuckets& buckets);

/// The corners at each vertex, in triangle order: vertex v's corners 3t + k (corner k of
/// triangle t) are corners[start[v]] to corners[start[v + 1] − 1]. O(N + V).
struct VertexCorners {
    std::vector<std::uint32_t> start;    ///< V + 1 offsets
    std::vector<std::uint32_t> corners;  ///< 3N corner numbers
};
/// The corners of s at each vertex (VertexCorners).
VertexCorners vertex_corners(const Surface& s);

/// Removes the vertices no triangle uses; the others keep their order.
void drop_unused_vertices(Surface& s);

/// The component of each triangle, numbered 0, 1, ... in order of first triangle.
/// Precondition: as triangle_neighbours. O(N + V).
std::vector<std::uint32_t> component_labels(const Surface& s);
/// The same from s's triangle_neighbours.
std::vector<std::uint32_t> component_labels(
    const Surface& s, const std::vector<std::array<std::uint32_t, 3>>& neighbours);
/// Number of connected components. Precondition: as triangle_neighbours.
std::size_t component_count(const Surface& s);
/// Euler characteristic V − E + F, V counting the vertices used by triangles (2 for a sphere,
/// 0 for a torus, summed over components). Precondition: closed (E = 3F/2).
long long euler_characteristic(const Surface& s);
/// Total genus Σ (2 − χ_c)/2 over the components (number of handles). Precondition: valid.
long long genus(const Surface& s);

/// Angle-weighted pseudo-normals of a valid surface: the sign of F at x is the sign of
/// (x − p) · n for p the nearest point and n the pseudo-normal of the feature holding p.
struct PseudoNormals {
    std::vector<Vec3> face;                 ///< unit outward normal of each triangle
    std::vector<std::array<Vec3, 3>> edge;  ///< per triangle and edge k: sum of the two normals
    std::vector<Vec3> vertex;               ///< per vertex: Σ (angle at the vertex) · normal
};
/// The pseudo-normals of a valid surface. O(N + V).
PseudoNormals pseudo_normals(const Surface& s);
/// PseudoNormals::vertex alone, without the edges' (which need the triangles' neighbours).
std::vector<Vec3> vertex_pseudo_normals(const Surface& s);

/// The nearest triangle found so far: the least (distance2, triangle) pair, so that the answer
/// does not depend on the order in which triangles are examined.
struct NearestFacet {
    double distance2 = std::numeric_limits<double>::infinity();          ///< squared distance to x
    std::uint32_t triangle = std::numeric_limits<std::uint32_t>::max();  ///< its index
    FacetPoint nearest;  ///< the nearest point on that triangle

    /// Takes triangle t with its nearest point p if (p.distance2, t) is less than the best.
    void offer(std::uint32_t t, const FacetPoint& p) {
        if (p.distance2 < distance2 || (p.distance2 == distance2 && t < triangle)) {
            distance2 = p.distance2;
            triangle = t;
            nearest = p;
        }
    }
};

/// Signed closest point of a surface to a query point x.
struct SurfacePoint {
    double distance = 0.0;            ///< signed distance F(x): negative inside, positive outside
    Vec3 point;                       ///< a nearest point of the surface to x
    std::uint32_t triangle = 0;       ///< the triangle holding point
    std::array<double, 3> weights{};  ///< barycentric weights of point in that triangle
    Feature feature = Feature::face;  ///< face, edge or corner of the triangle holding point
    std::uint8_t index = 0;           ///< which edge or corner
};

/// The sign of F at x (+1 or −1; +1 on the surface) given that `nearest` on triangle t is a
/// nearest point of the surface to x: the sign of (x − p) · n with n the pseudo-normal of the
/// face, edge or vertex holding p, right at convex and concave edges and corners alike. O(1).
int side_of(const Surface& s, const PseudoNormals& normals, std::uint32_t t,
            const FacetPoint& nearest, Vec3 x);

/// The signed closest point from the nearest triangle and its nearest point to x.
SurfacePoint signed_closest_point(const Surface& s, const PseudoNormals& normals,
                                  const NearestFacet& best, Vec3 x);

/// Signed closest point by comparing every triangle: O(N). The oracle of the distance tree.
/// Precondition: s is valid and not empty.
SurfacePoint closest_point_brute_force(const Surface& s, const PseudoNormals& normals, Vec3 x);

/// Generalised winding number of the surface at x (Σ of the triangles' signed solid angles over
/// 4π): 1 inside and 0 outside an outward closed surface, −1 inside an inward one; rounding
/// aside. The orientation-independent inside test of validation and of the tests. O(N).
double winding_number(const Surface& s, Vec3 x);

}  // namespace slc
