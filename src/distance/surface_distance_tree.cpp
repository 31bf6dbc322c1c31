// SurfaceDistanceTree: building the octree and its triangle lists, and the climbing query.
#include "slc/distance/surface_distance_tree.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

/// Relative growth of a triple before testing triangles against it: a triangle that misses the
/// triple only by rounding still makes the list, which can only lengthen it.
constexpr double triple_slack = 1e-12;

/// A query meeting a cell list longer than this turns to the triangle hierarchy.
constexpr std::size_t longest_scanned_list = 48;

/// Half the diagonal of a unit cube, √3/2.
constexpr double half_diagonal = 0.8660254037844386;

/// A lower bound of the distance from the cube b (edge h) to triangle t: the larger of the
/// distance between their bounding boxes and the distance from the cube's centre less its
/// half-diagonal. NOTE: §1.3 splits on the exact cell–surface distance; a lower bound splits a
/// few more cells (never fewer), which changes the cost of a query, never its answer.
double distance_lower_bound(const Triangle3& t, const Box3& b, double h) {
    const double boxes = std::sqrt(distance2(bounding_box(t), b));
    const double centre = std::sqrt(closest_point(t, b.center()).distance2) - half_diagonal * h;
    return std::max(boxes, centre);
}

}  // namespace

SurfaceDistanceTree::SurfaceDistanceTree(const Surface& surface, Box3 domain, Options options)
    : surface_(&surface), tree_(domain, options.depth) {
    if (surface.empty()) throw InvalidInput("distance tree: the surface is empty");
    corners_.resize(surface.size());
    for (std::size_t t = 0; t < surface.size(); ++t) corners_[t] = surface.triangle(t);
    normals_ = pseudo_normals(surface);
    hierarchy_ = TriangleHierarchy(corners_);
    build_lists();
}

void SurfaceDistanceTree::build_lists() {
    std::vector<Box3> bounds(corners_.size());
    for (std::size_t t = 0; t < corners_.size(); ++t) bounds[t] = bounding_box(corners_[t]);
    triangles_.resize(corners_.size());
    std::iota(triangles_.begin(), triangles_.end(), 0u);
    offsets_ = {0, static_cast<std::uint32_t>(triangles_.size())};
    // Level by level (cells are appended breadth-first, so [begin, end) is one level): split a
    // cell while its edge exceeds its distance to the surface (§1.3). Only triangles on its list
    // can be that near, since the triple holds every point within one edge. The tests and the
    // children's lists are computed on all worker threads, then packed in cell order, so the
    // tree is the same for any thread count.
    for (std::size_t begin = 0, end = tree_.size(); begin < end; begin = end, end = tree_.size()) {
        const int level = tree_.cell(begin).level;
        if (level == tree_.max_depth()) break;
        const double h = tree_.edge(level);
        std::vector<std::uint8_t> near(end - begin, 0);
        parallel_for(
            end - begin,
            [&](std::size_t i) {
                const Box3 b = tree_.box(begin + i);
                for (std::uint32_t t : cell_triangles(begin + i)) {
                    // The box distance alone rules out most triangles of a far cell.
                    if (!(std::sqrt(distance2(bounds[t], b)) < h)) continue;
                    if (distance_lower_bound(corners_[t], b, h) < h) {
                        near[i] = 1;
                        return;
                    }
                }
            },
            expensive_grain);
        std::vector<std::uint32_t> parents;
        for (std::size_t c = begin; c < end; ++c) {
            if (!near[c - begin]) continue;
            tree_.split(c);
            parents.push_back(static_cast<std::uint32_t>(c));
        }
        if (parents.empty()) break;
        list_children(parents, bounds);
    }
}

void SurfaceDistanceTree::list_children(std::span<const std::uint32_t> parents,
                                        std::span<const Box3> bounds) {
    // Child k is high along axis a when bit a of k is set: the children low along x are
    // 0, 2, 4, 6 (mask 0x55), high 1, 3, 5, 7 (0xaa); along y 0x33 and 0xcc; along z 0x0f and
    // 0xf0. sides[a][s]: the children on the sides s (bit 0 low, bit 1 high) of axis a.
    static constexpr std::uint8_t sides[3][4] = {
        {0x00, 0x55, 0xaa, 0xff}, {0x00, 0x33, 0xcc, 0xff}, {0x00, 0x0f, 0xf0, 0xff}};
    // First pass, one parent per iteration: for each triangle of the parent's list, the mask of
    // the children whose triples its box meets (along each axis it meets the triples of the low
    // children, of the high ones, or both), and the length of each child's list.
    std::vector<std::size_t> entry(parents.size() + 1, 0);
    for (std::size_t j = 0; j < parents.size(); ++j)
        entry[j + 1] = entry[j] + cell_triangles(parents[j]).size();
    std::vector<std::uint8_t> masks(entry.back());
    std::vector<std::uint32_t> counts(8 * parents.size(), 0);
    parallel_for(
        parents.size(),
        [&](std::size_t j) {
            const std::uint32_t first = tree_.cell(parents[j]).first_child;
            const double slack = triple_slack * tree_.edge(tree_.cell(first).level);
            const Box3 low = tree_.triple(first).inflated(slack);
            const Box3 high = tree_.triple(first + 7).inflated(slack);
            std::uint32_t count[8] = {};
            std::uint8_t* mask = masks.data() + entry[j];
            for (std::uint32_t s : cell_triangles(parents[j])) {
                const Box3& b = bounds[s];
                unsigned m = 0xff;
                for (int a = 0; a < 3; ++a) {
                    const unsigned side =
                        (b.lo[a] <= low.hi[a] && b.hi[a] >= low.lo[a] ? 1u : 0u) |
                        (b.lo[a] <= high.hi[a] && b.hi[a] >= high.lo[a] ? 2u : 0u);
                    m &= sides[a][side];
                }
                *mask++ = static_cast<std::uint8_t>(m);
                for (unsigned k = 0; k < 8; ++k) count[k] += (m >> k) & 1u;
            }
            std::copy(count, count + 8, counts.begin() + static_cast<std::ptrdiff_t>(8 * j));
        },
        expensive_grain);
    // The children follow their parents in order, so their lists are appended in cell order.
    SLC_ASSERT(offsets_.size() == std::size_t{tree_.cell(parents[0]).first_child} + 1,
               "lists follow cell order");
    for (const std::uint32_t n : counts) {
        SLC_ASSERT(offsets_.back() + std::uint64_t{n} <= 0xffffffffu, "lists fit 32-bit offsets");
        offsets_.push_back(offsets_.back() + n);
    }
    triangles_.resize(offsets_.back());
    // Second pass: each triangle to the lists its mask names, in the parent's (increasing) order.
    parallel_for(
        parents.size(),
        [&](std::size_t j) {
            const std::uint32_t first = tree_.cell(parents[j]).first_child;
            std::uint32_t at[8];
            for (unsigned k = 0; k < 8; ++k) at[k] = offsets_[first + k];
            const std::uint8_t* mask = masks.data() + entry[j];
            for (std::uint32_t s : cell_triangles(parents[j])) {
                for (unsigned m = *mask++; m != 0; m &= m - 1)
                    triangles_[at[std::countr_zero(m)]++] = s;
            }
        },
        expensive_grain);
}

NearestFacet SurfaceDistanceTree::nearest_facet(Vec3 x) const {
    std::uint32_t c = tree_.leaf_at(x);
    NearestFacet best;
    for (;;) {
        const auto list = cell_triangles(c);
        if (list.size() > longest_scanned_list) {
            hierarchy_.nearest(corners_, x, best);
            break;
        }
        for (std::uint32_t t : list) best.offer(t, slc::closest_point(corners_[t], x));
        if (best.distance2 < std::numeric_limits<double>::infinity()) {
            const double m = std::sqrt(best.distance2);
            if (tree_.triple(c).contains(Box3::cube(x, m))) break;
        }
        if (c == 0) break;  // the root lists every triangle
        c = tree_.cell(c).parent;
    }
    return best;
}

SurfacePoint SurfaceDistanceTree::closest_point(Vec3 x) const {
    return signed_closest_point(*surface_, normals_, nearest_facet(x), x);
}

SurfacePoint SurfaceDistanceTree::nearest_point(Vec3 x) const {
    const NearestFacet best = nearest_facet(x);
    const FacetPoint& p = best.nearest;
    return {std::sqrt(best.distance2), p.point, best.triangle, p.weights, p.feature, p.index};
}

void SurfaceDistanceTree::closest_points(std::span<const Vec3> xs,
                                         std::span<SurfacePoint> out) const {
    SLC_ASSERT(xs.size() == out.size(), "one answer per query point");
    parallel_for(
        xs.size(), [&](std::size_t i) { out[i] = closest_point(xs[i]); }, expensive_grain);
}

std::vector<SurfacePoint> SurfaceDistanceTree::closest_points(std::span<const Vec3> xs) const {
    std::vector<SurfacePoint> out(xs.size());
    closest_points(xs, out);
    return out;
}

std::vector<double> SurfaceDistanceTree::signed_distances(std::span<const Vec3> xs) const {
    std::vector<double> out(xs.size());
    parallel_for(
        xs.size(), [&](std::size_t i) { out[i] = closest_point(xs[i]).distance; }, expensive_grain);
    return out;
}

int SurfaceDistanceTree::default_depth(const Surface& surface, const Box3& domain) {
    double total = 0.0;
    for (std::size_t t = 0; t < surface.size(); ++t) {
        const Triangle3 tri = surface.triangle(t);
        total += distance(tri.a, tri.b) + distance(tri.b, tri.c) + distance(tri.c, tri.a);
    }
    const double mean = total / (3.0 * static_cast<double>(surface.size()));
    const int level =
        static_cast<int>(std::ceil(std::log2(domain.width() / std::max(mean, 1e-300))));
    const int deepest = Octree::max_resolvable_depth(domain);
    return std::clamp(level, std::min(2, deepest), std::min(10, deepest));
}

}  // namespace slc
