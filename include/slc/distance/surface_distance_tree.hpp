/// @file
/// SurfaceDistanceTree: exact signed distance F and a nearest point of a closed triangle surface
/// anywhere, fast (paper §1.3 with d = 3; DESIGN §8). The 3D counterpart of DistanceTree.
///
/// An octree over the domain in which a cell is split (to depth L) while its edge exceeds its
/// distance to the surface. A cell lists the triangles that meet its concentric triple (the
/// 3×3×3 block of same-size cells around it) when they are few (at most 48). A query starts in
/// the leaf holding x and climbs ancestors, keeping the nearest triangle of their lists, until
/// the cube of half-width m (the best distance so far) around x lies inside the cell's triple:
/// every triangle nearer than m meets that cube and so is on the list, which makes the answer
/// exact. At a cell with no list (far from the surface, where cells are large and their lists
/// would be long), a TriangleHierarchy finishes the search instead. The build needs the long
/// lists only of the few finest levels, and for one level at a time (see build_lists).
/// The sign comes from the angle-weighted pseudo-normal of the face, edge or vertex holding the
/// nearest point, which is right at edges and corners (Bærentzen and Aanæs 2005).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/geometry/triangle_hierarchy.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc {

/// Exact signed distance and nearest point of a valid surface (prepare_surface) at any point, in
/// O(log N) per query near the surface. The tree refers to the surface it was built on and never
/// copies it.
class SurfaceDistanceTree {
public:
    /// The tree's parameters (paper Table 4: L).
    struct Options {
        int depth = 6;          ///< L: deepest level of the octree
        bool balanced = false;  ///< 2:1 balance the octree (for tetrahedral contouring)
    };

    /// Builds the tree for a valid surface inside domain (a cube). The surface must outlive the
    /// tree and stay unchanged. Throws InvalidInput for an empty surface, a domain that is not a
    /// cube, or a depth outside 0..Octree::max_resolvable_depth(domain).
    /// Cost O(N log N) time and memory for N triangles of similar size.
    SurfaceDistanceTree(const Surface& surface, Box3 domain, Options options);

    /// A depth for surface in domain when none is given: the level whose cells are two to four
    /// mean edges wide, between 2 and 10 (and within what doubles resolve there).
    /// Only the cost of a query depends on it. Precondition: surface is not empty.
    static int default_depth(const Surface& surface, const Box3& domain);

    /// Signed closest point of the surface to x (any x, also outside the domain): distance
    /// exact to rounding; sign by pseudo-normals; 0 on the surface. O(log N) near the surface.
    SurfacePoint closest_point(Vec3 x) const;
    /// closest_point(x) without the sign (distance |F(x)|): for the nearest-point extension.
    SurfacePoint nearest_point(Vec3 x) const;

    /// closest_point for a batch, on all worker threads; out.size() == xs.size().
    void closest_points(std::span<const Vec3> xs, std::span<SurfacePoint> out) const;
    /// The same, returning a new vector.
    std::vector<SurfacePoint> closest_points(std::span<const Vec3> xs) const;
    /// Signed distances F for a batch, on all worker threads.
    std::vector<double> signed_distances(std::span<const Vec3> xs) const;

    /// The surface the tree was built on.
    const Surface& surface() const { return *surface_; }
    /// Its pseudo-normals.
    const PseudoNormals& normals() const { return normals_; }
    /// The octree: cells split to depth L near the surface; 2:1 balanced when asked
    /// (Options::balanced), the cells that makes listed as the others.
    const Octree& tree() const { return tree_; }
    /// True when cell c keeps a list: when at most 48 triangles' boxes meet its triple. A query
    /// reaching a cell without one finishes in the triangle hierarchy.
    bool is_listed(std::size_t c) const { return listed_[c] != 0; }
    /// Triangles listed by cell c: those whose bounding boxes meet its concentric triple, in
    /// increasing order; empty when the cell keeps no list (is_listed).
    std::span<const std::uint32_t> cell_triangles(std::size_t c) const {
        return {triangles_.data() + offsets_[c], triangles_.data() + offsets_[c + 1]};
    }

private:
    /// Splits the cells level by level and lists them.
    void build_lists();
    /// Stores the lists of the cells [begin, end) (the last ones) that are short enough, from
    /// the hierarchy: the levels above the deepest, and the cells balancing makes.
    void list_from_hierarchy(std::size_t begin, std::size_t end);
    /// True when cell c is nearer the surface than its edge, by a lower bound of the distance:
    /// the split test, in the hierarchy.
    bool is_near(std::size_t c) const;
    /// Stores the short lists of the deepest level's cells [begin, end) (the last ones) by
    /// binning every triangle into the triples its box meets.
    void bin_lists(std::size_t begin, std::size_t end);
    /// The least (distance², triangle) pair over the surface at x.
    NearestFacet nearest_facet(Vec3 x) const;

    const Surface* surface_;
    std::vector<Triangle3> corners_;  ///< the triangles' corners, contiguous for the queries
    PseudoNormals normals_;
    TriangleHierarchy hierarchy_;
    Octree tree_;
    std::vector<std::uint32_t>
        offsets_;  ///< CSR: triangles of cell c are [offsets_[c], offsets_[c+1])
    std::vector<std::uint32_t> triangles_;  ///< the cells' lists, one after another
    std::vector<std::uint8_t> listed_;      ///< 1 when cell c keeps a list
};

}  // namespace slc
