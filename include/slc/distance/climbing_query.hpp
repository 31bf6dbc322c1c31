/// @file
/// ClimbingQuery: the exact closest-point query of paper §1.3, written once for curves
/// (DistanceTree) and surfaces (SurfaceDistanceTree), with the batch and signed queries both
/// trees answer through it (DESIGN §8).
///
/// A query starts in the leaf of the 2^d tree holding x and climbs ancestors, keeping the least
/// (distance², element) pair over their lists, until the box of half-width m (the best distance
/// so far) around x lies inside the cell's triple: every element nearer than m meets that box and
/// so is on the list, which makes the answer exact. At a cell that keeps no list short enough to
/// scan (far from the interface, where cells are large), a bounding-volume hierarchy over all
/// elements finishes the search instead. Ties go to the lower index, so the answer does not
/// depend on the order in which elements are examined.
///
/// What differs between the dimensions stands beside each tree: its kernel (SegmentKernel in
/// distance_tree.hpp, TriangleKernel in surface_distance_tree.hpp) names the element, its exact
/// closest point, the accumulator of the nearest one, the answer and the box around x; the tree
/// builds its lists its own way and gives the query its parts (the contract below). The members
/// are defined in src/distance/climbing_query_impl.hpp and instantiated once for each tree, so
/// the query is compiled, and inlined, with the tree's own parts.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace slc {

/// The public queries of a distance tree Tree over the elements of Kernel, as a base of Tree
/// (which derives from ClimbingQuery<Tree, Kernel> and makes it a friend). Tree provides:
///   - `std::uint32_t leaf_at(Point x) const`: the leaf holding x (clamped to the domain);
///   - `const Orthtree<Kernel::dim>& tree() const`: the tree of cells;
///   - `bool is_listed(std::size_t c) const`: whether cell c keeps a list short enough to scan;
///   - `std::span<const std::uint32_t> cell_list(std::size_t c) const`: the elements meeting
///     the triple of a listed cell c, in increasing order; the root, when listed, lists all;
///   - `std::span<const Kernel::Element> elements() const`: the elements, by index;
///   - `const Kernel::Hierarchy& hierarchy() const`: the hierarchy over all elements;
///   - `Kernel::Answer signed_point(const Kernel::Nearest& best, Point x) const`: the signed
///     closest point from the nearest element, by the interface's sign rule.
template <class Tree, class Kernel>
class ClimbingQuery {
public:
    using Point = typename Kernel::Point;    ///< Vec2 or Vec3
    using Answer = typename Kernel::Answer;  ///< ClosestPoint or SurfacePoint

    /// Signed closest point of the interface to x (any x, also outside the domain): distance
    /// exact to rounding; sign right at corners and edges (pseudo-normals); 0 on the interface.
    /// O(log N) near the interface.
    Answer closest_point(Point x) const;
    /// closest_point(x) without the sign: the same nearest point and element, with distance
    /// |F(x)|. For callers that need only where the nearest point lies (the nearest-point
    /// extension): it skips the side test. O(log N) near the interface.
    Answer nearest_point(Point x) const;

    /// closest_point for a batch, on all worker threads; out.size() == xs.size(). The answer for
    /// each point does not depend on the thread count.
    void closest_points(std::span<const Point> xs, std::span<Answer> out) const;
    /// The same, returning a new vector.
    std::vector<Answer> closest_points(std::span<const Point> xs) const;
    /// Signed distances F for a batch, on all worker threads.
    std::vector<double> signed_distances(std::span<const Point> xs) const;

protected:
    ClimbingQuery() = default;

private:
    /// The least (distance², element) pair over the interface at x: the query closest_point and
    /// nearest_point both answer.
    typename Kernel::Nearest nearest(Point x) const;

    const Tree& self() const { return static_cast<const Tree&>(*this); }
};

}  // namespace slc
