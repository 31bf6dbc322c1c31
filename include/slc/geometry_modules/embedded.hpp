/// @file
/// The embedded geometry module (paper §3.2, Equation 9): Γ embedded as the zero set of its exact
/// signed distance F on a local uniform mesh; N = ∇F/|∇F| and C = −∇·N by ENO differences of order
/// E, S passes of cosine smoothing after each differentiation, and ENO interpolation of order E
/// back to the vertices.
#pragma once

#include <vector>

#include "slc/core/box.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/geometry_modules/local_mesh.hpp"
#include "slc/geometry_modules/vertex_geometry.hpp"

namespace slc {

/// The paper's M, E and S (Table 4).
struct EmbeddedOptions {
    /// M: lattice points per side of the domain, spacing h = width/M. The paper's default is
    /// 2^(K+1) for a contouring tree of depth K (see default_mesh_size); 128 here is K = 6.
    int mesh = 128;
    /// E: order of the ENO differences and of the ENO interpolation, 1..eno::max_order.
    int eno_order = 3;
    /// S: passes of cosine smoothing after each differentiation, >= 0 (the paper raises S
    /// logarithmically with M for curvature flows).
    int smoothing = 0;
    /// The bias, >= 1, of the ENO differences of F (eno::derivative); 1, the default: the
    /// paper's plain ENO. F is the distance to a polygon, kinked inside it along each vertex's
    /// bisector by the vertex's small turn: the plain rule steps round such a kink or not as it
    /// falls between the nodes, so N leaves out part of the turn of vertices far apart (the long
    /// segments where a contour runs along the tree's lines), and C on the polygon a depth-7
    /// contour makes of a circle at Fig. 18's settings is off by a four-fold 2.1e−2 (2.0e−3 with
    /// a bias of 2), which sets the shape that a flow standing still at circles ends in. Over
    /// Table 7 the plain rule's error partly cancels the smoothing's shift of C, and a bias of 2
    /// raises 14 of its 25 errors (docs/notes/area-preserving.md): Figs. 18 and 19's problems
    /// take 2. The differences of N keep the plain rule.
    double eno_bias = 1.0;
    /// Width, in mesh spacings h, over which the vertex curvature is averaged along Γ (the
    /// arclength module's cubic B-spline weights, standard deviation average · h); 0, the
    /// default: none, the paper's module. The module resolves C to about h, and a polygon's
    /// distance field is kinked at every vertex (its fans), so the interpolated C varies from
    /// vertex to vertex at scales the mesh cannot resolve; over the thousands of steps of a
    /// nonlocal flow that stands still at circles, that roughens the curve below the mesh, where
    /// C cannot see it to damp it (docs/notes/area-preserving.md). Figs. 18 and 19's problems
    /// take 1.
    double average = 0.0;
};

/// M = 2^(K+1), the paper's embedded mesh size for a contouring tree of depth K (0..29).
int default_mesh_size(int depth);

/// Everything the embedded module computes on its local mesh, for inspection and pictures.
struct EmbeddedFields {
    LocalMesh mesh;                 ///< points within R = E + S steps of Γ
    std::vector<double> distance;   ///< F at the mesh points (exact, from the distance tree)
    std::vector<Vec2> normals;      ///< N = ∇F/|∇F| after S smoothing passes, renormalized
    std::vector<double> curvature;  ///< C = −∇·N after S smoothing passes
};

/// The fields of the embedded module on the local mesh of range R = E + S around the tree's
/// curves, h = width/M, the lattice offset by (h/2, h/2) from the corner of the tree's domain
/// (cell-centred: a contour of a depth-K tree over the same domain has its vertices on the tree's
/// cell edges, which at M = 2^(K+1) would otherwise be lattice lines; see below):
///  1. F at every mesh point from the tree (exact);
///  2. ∇F by ENO differences of order E along rows and columns, biased towards the centred
///     stencil by EmbeddedOptions::eno_bias, N = ∇F/|∇F| (N = 0 where the differences cancel,
///     which happens only on the medial axis of Γ);
///  3. S passes of cosine smoothing of each component of N, then renormalization;
///  4. C = −(∂x N_x + ∂y N_y) by ENO differences of order E, then S passes of smoothing.
/// Every ENO stencil stays inside its interval, which holds at least E + 1 points since R ≥ E.
/// Accuracy on a smooth curve: N to O(h^E), C to O(h^(E−1)) at least (ENO switches stencils
/// between neighbours, so the O(h^E) error of N is not smooth); measured orders are in
/// docs/algorithms/geometry.md. Throws InvalidInput for options out of range.
/// Cost O(P log N) for P = O(R · length/h) mesh points; memory O(P + M).
EmbeddedFields embedded_fields(const DistanceTree& tree, const EmbeddedOptions& options = {});

/// The fields interpolated to points (normally the vertices of Γ) by ENO interpolation of order
/// `order`, N renormalized. Throws NumericalFailure, naming the point, if a point lies outside
/// the local mesh (more than R − 1 steps from Γ).
VertexGeometry interpolate_geometry(const EmbeddedFields& fields, std::span<const Vec2> points,
                                    int order);

/// Vertex normals and curvature of the tree's curves by the embedded module: embedded_fields
/// followed by interpolate_geometry at the vertices, and the curvature averaged along Γ over
/// EmbeddedOptions::average mesh spacings. Parallel; the result does not depend on
/// the thread count.
VertexGeometry embedded_geometry(const DistanceTree& tree, const EmbeddedOptions& options = {});

/// The same for curves inside domain (a square) when no distance tree is at hand: builds one of
/// depth log2(M) for the call.
VertexGeometry embedded_geometry(const Interface& curves, Box domain,
                                 const EmbeddedOptions& options = {});

}  // namespace slc
