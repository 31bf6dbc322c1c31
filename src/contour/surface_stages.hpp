// The stages of contour_surface() (paper §2 in space), internal to the contour module: G
// evaluated and checked, topology resolution on the tetrahedralized octree (§2.1,
// surface_topology.cpp), and adaptive refinement of the linear contour (§2.2,
// surface_refinement.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "checked_function.hpp"
#include "slc/contour/implicit_function.hpp"
#include "slc/contour/root_finding.hpp"
#include "slc/contour/surface_contour.hpp"
#include "slc/core/box3.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/tree/orthtree.hpp"
#include "slc/tree/tetrahedralization.hpp"

namespace slc::contouring {

/// The topology of the zero set in space (§2.1): the octree, its tetrahedra with G at every
/// vertex (|G| > η everywhere after perturbation), and the tetrahedra G changes sign in.
struct SurfaceTopology {
    explicit SurfaceTopology(Octree t) : tree(std::move(t)) {}

    Octree tree;              ///< balanced, K levels and thin cells beyond
    Tetrahedralization mesh;  ///< vertices moved where they were perturbed
    /// G at mesh.vertices, or a stand-in with G's sign where exact is 0 (never in a crossing
    /// tetrahedron).
    std::vector<double> values;
    std::vector<std::uint8_t> exact;      ///< per vertex: values is G there
    std::vector<std::uint32_t> crossing;  ///< the tetrahedra where G changes sign, in order
    double gamma = 0.0;                   ///< the gradient bound at which the tree balanced
    std::size_t thin_cells = 0;           ///< cells split beyond K where G bends
    bool thin_budget_reached = false;     ///< cells that bend left whole (thin_cell_budget)
    std::size_t settled = 0;              ///< tree points with a stand-in instead of G
    std::size_t bound_evals = 0;          ///< evaluations of the bounds
    std::size_t perturbed = 0;            ///< vertices moved off |G| ≤ η
    std::size_t moved_across = 0;         ///< vertices moved across to keep the shape's topology
};

/// Builds the K-level octree (γ doubled until balanced, thin cells beyond K), tetrahedralizes
/// it, puts G (or a stand-in with its sign) at every vertex, checks that the zero set stays off
/// the domain's boundary, perturbs vertices with |G| ≤ η and evaluates G at the stand-ins of the
/// tetrahedra it changes sign in. Every evaluation through g. Throws LeftDomain naming the place
/// where the zero set reaches the boundary; NumericalFailure when perturbation keeps failing or G
/// is not finite. Options validated by the caller. bounds, when given, are the contour's cheap
/// bounds on G.
SurfaceTopology resolve_surface_topology(const SpaceEvaluator& g, const Box3& domain,
                                         const SurfaceContourOptions& options,
                                         std::optional<SpaceBoundsRef> bounds);

/// The key of the edge between vertices a and b, either way round.
std::uint64_t edge_key(std::uint32_t a, std::uint32_t b);

/// The edges of a closed surface: their ends (lower vertex first), their two triangles, and each
/// triangle's edges (edge k from corner k to corner k + 1). The half-edges are bucketed by their
/// lower vertex (a counting sort) and paired within each bucket: O(N + V), no hashing.
struct Edges {
    std::vector<std::array<std::uint32_t, 2>> ends;
    std::vector<std::array<std::uint32_t, 2>> triangles;
    std::vector<std::array<std::uint32_t, 3>> of_triangle;
    /// Vertex v's edges to higher vertices are first_of[v] to first_of[v + 1], by their other end.
    std::vector<std::uint32_t> first_of;

    explicit Edges(const Surface& s);
    std::size_t size() const { return ends.size(); }
    /// The edge whose ends are a and b, either way round: a binary search among the lower one's
    /// edges.
    std::optional<std::uint32_t> find(std::uint32_t a, std::uint32_t b) const;
    /// Whether a and b are the ends of an edge.
    bool contains(std::uint32_t a, std::uint32_t b) const { return find(a, b).has_value(); }
};

/// Twice the area of triangle t times its unit normal (by the right-hand rule).
Vec3 area_normal(const Surface& s, const TriangleIndices& t);

/// The triangles that replace t = (v0, v1, v2) when the edges flagged in `split` (bit k: edge
/// from corner k to corner k + 1) get the vertices w[k], oriented as t: one edge, two triangles;
/// two, the corner between them cut off and the quadrilateral left split along its shorter
/// diagonal (the longer with `other_diagonal`); three, four.
void split_children(const Surface& s, const TriangleIndices& t, unsigned split,
                    const std::array<std::uint32_t, 3>& w, std::vector<TriangleIndices>& out,
                    bool other_diagonal = false);

/// A plane n · x = c of the zero set (n a unit vector, G's gradient).
struct CreasePlane {
    Vec3 n;
    double c = 0.0;
};

/// The planes of the zero set at the vertices of a contour, for cut_creases(): one where G is a
/// plane's distance about the vertex, two at a vertex on a crease, three or more at a corner (up
/// to max_planes: the apex of a pyramid of that many faces). Indexed by vertex; vertices never
/// move. A vertex's planes are set whole; they are kept one after another in `pool`, so that a
/// vertex asked holds only the planes it has.
struct CreasePlanes {
    static constexpr int max_planes = 16;

    std::vector<CreasePlane> pool;
    std::vector<std::uint32_t> first;    ///< where a vertex's planes start in pool
    std::vector<std::uint8_t> count;     ///< planes known at the vertex
    std::vector<std::uint8_t> measured;  ///< 1 once asked (count 0: G is not flat there)
    /// Vertices moved onto their planes (within their distance from them), since the caller
    /// last cleared it.
    std::vector<std::uint32_t> moved;

    void resize(std::size_t vertices) {
        first.resize(vertices, 0);
        count.resize(vertices, 0);
        measured.resize(vertices, 0);
    }
    std::span<const CreasePlane> of(std::uint32_t v) const {
        return {pool.data() + first[v], count[v]};
    }
    /// Sets the planes of vertex v (at most max_planes).
    void set(std::uint32_t v, std::span<const CreasePlane> planes) {
        first[v] = static_cast<std::uint32_t>(pool.size());
        count[v] = static_cast<std::uint8_t>(planes.size());
        pool.insert(pool.end(), planes.begin(), planes.end());
    }
};

/// Whether the flip of the edge between triangles t0 and t1 into triangles u and v folds the
/// contour across a crease by more than eps: t0 and t1 each lie in a plane of their corners, u
/// or v does not, and a point of u or v (the new edge's midpoint, their centroids) lies beyond
/// eps from each plane of its corners (near a crease G is the nearer plane's distance).
/// Vertices beyond those `planes` knows have no planes.
bool folds_beyond(const Surface& s, const CreasePlanes& planes, const TriangleIndices& t0,
                  const TriangleIndices& t1, const TriangleIndices& u, const TriangleIndices& v,
                  double eps);

/// Cuts the triangles in `beyond` (those some midpoint or centroid puts beyond ε) where the
/// zero set of G folds between their corners (surface_creases.cpp). At each corner G's gradient
/// by central differences, kept as the plane of the zero set there where the one-sided
/// differences agree (a corner within the step of a crease takes its neighbours' planes it lies
/// on and is moved onto them). In a triangle over one crease, an edge whose ends lie on its two
/// planes is split where it crosses their line (seen along their mean normal; an end it crosses
/// beside is moved onto the line instead), and a triangle whose corners lie on three planes gets
/// the point where they meet as a centre; a point is kept only where |G| ≤ η, so a smooth
/// surface, whose tangent planes meet off it, is never cut. Every child then lies in one plane.
/// The cuts of a triangle whose children would fold, lose their area or meet the rest of the
/// surface are withdrawn. Where no cut is left, patches of triangles folded across a crease or
/// about a corner are triangulated again in its planes. centroid_value and dirty follow the
/// triangles (NaN and 1 for the children of a cut triangle); planes.moved lists the vertices
/// moved. Returns the vertices added, moved and patches replaced (0: the surface is unchanged).
std::size_t cut_creases(Surface& s, const SpaceEvaluator& g, double eta,
                        std::span<const std::uint32_t> beyond, CreasePlanes& planes,
                        std::vector<double>& centroid_value, std::vector<std::uint8_t>& dirty);

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
/// surface; the surface stays closed, manifold and oriented. Where every split left beyond ε is
/// refused, the needles and clusters within two rings of those triangles are collapsed before
/// another pass, up to max_recoveries times. Throws LimitExceeded naming ε when the
/// vertices would pass max_vertices. With `creases` (SurfaceContourOptions::creases), each
/// splitting pass is preceded by cut_creases() while it changes the surface, an edge across a
/// crease is split on it, a flat triangle beside a fold may be split in its plane, and a refused
/// edge is tried again once a split beside it changed its triangles.
SurfaceRefinement refine_surface(Surface& s, const SpaceEvaluator& g, double eps,
                                 const RootOptions& roots, int passes, int max_passes,
                                 std::size_t max_vertices, bool creases);

}  // namespace slc::contouring
