/// @file
/// SurfaceDistanceTree: exact signed distance F and a nearest point of a closed triangle surface
/// anywhere, fast (paper §1.3 with d = 3; DESIGN §8). The 3D counterpart of DistanceTree.
///
/// An octree over the domain in which a cell is split (to depth L) while its edge exceeds its
/// distance to the surface. A cell lists the triangles that meet its concentric triple (the
/// 3×3×3 block of same-size cells around it) when they are few (at most 48). The query is
/// ClimbingQuery's (climbing_query.hpp, written once for curves and surfaces): it starts in the
/// leaf holding x and climbs ancestors until the cube of half-width m (the best distance so far)
/// around x lies inside the cell's triple. At a cell with no list (far from the surface, where
/// cells are large and their lists would be long), a TriangleHierarchy finishes the search
/// instead. The build needs the long lists only of the few finest levels, and for one level at
/// a time (see build_lists). The sign comes from the angle-weighted pseudo-normal of the face,
/// edge or vertex holding the nearest point, which is right at edges and corners (Bærentzen and
/// Aanæs 2005). This file holds the surfaces' part: the triangle kernel, the tree and its lists.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/distance/climbing_query.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/geometry/triangle_hierarchy.hpp"
#include "slc/tree/orthtree.hpp"

namespace slc {

/// The triangles of a surface as the elements of the climbing query (ClimbingQuery).
struct TriangleKernel {
    static constexpr int dim = 3;
    using Point = Vec3;
    using Element = Triangle3;
    using Nearest = NearestFacet;  ///< the least (distance², triangle) pair so far
    using Hierarchy = TriangleHierarchy;
    using Answer = SurfacePoint;

    /// The exact closest point of triangle t to x; plain: t and x are in_plain_range.
    static FacetPoint closest_point(const Triangle3& t, Vec3 x, bool plain) {
        return plain ? closest_point_in_range(t, x) : slc::closest_point(t, x);
    }
    /// The triangle of a nearest pair (or TriangleHierarchy::no_hint when none was found).
    static std::uint32_t element_of(const NearestFacet& n) { return n.triangle; }
    /// The cube of half-width m around x, exactly a cube (Box3::cube), that a cell's triple must
    /// hold to end the climb.
    static Box3 reach(Vec3 x, double m) { return Box3::cube(x, m); }
    /// The nearest point without its sign: distance |F(x)|.
    static SurfacePoint unsigned_point(const NearestFacet& best) {
        const FacetPoint& p = best.nearest;
        return {std::sqrt(best.distance2), p.point, best.triangle, p.weights, p.feature, p.index};
    }
};

/// Exact signed distance and nearest point of a valid surface (prepare_surface) at any point, in
/// O(log N) per query near the surface. The queries (closest_point, nearest_point,
/// closest_points, signed_distances) are ClimbingQuery's; the sign is by pseudo-normals. The
/// tree refers to the surface it was built on and never copies it.
class SurfaceDistanceTree : public ClimbingQuery<SurfaceDistanceTree, TriangleKernel> {
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

    /// A depth for surface in domain when none is given: the level whose cells are four to
    /// eight mean edges wide, between 2 and 10 (and within what doubles resolve there).
    /// Only the cost of a query depends on it. Precondition: surface is not empty.
    static int default_depth(const Surface& surface, const Box3& domain);

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
    friend class ClimbingQuery<SurfaceDistanceTree, TriangleKernel>;

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
    /// The query's view of the tree (ClimbingQuery): leaves, lists, triangles, hierarchy and
    /// sign rule.
    std::uint32_t leaf_at(Vec3 x) const { return tree_.leaf_at(x); }
    std::span<const std::uint32_t> cell_list(std::size_t c) const { return cell_triangles(c); }
    std::span<const Triangle3> elements() const { return corners_; }
    const TriangleHierarchy& hierarchy() const { return hierarchy_; }
    /// True when a query at x may skip the kernel's range checks (TriangleKernel::closest_point).
    bool in_plain_range(Vec3 x) const { return hierarchy_.plain() && slc::in_plain_range(x); }
    SurfacePoint signed_point(const NearestFacet& best, Vec3 x) const {
        return signed_closest_point(*surface_, normals_, best, x);
    }

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

extern template class ClimbingQuery<SurfaceDistanceTree, TriangleKernel>;

}  // namespace slc
