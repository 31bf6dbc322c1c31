// SurfaceDistanceTree: building the octree and its triangle lists, and the climbing query.
#include "slc/distance/surface_distance_tree.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

/// A grid position holding no cell of the level.
constexpr std::uint32_t no_slot = 0xffffffffu;

/// Relative growth of a triple before testing triangles against it: a triangle that misses the
/// triple only by rounding still makes the list, which can only lengthen it.
constexpr double triple_slack = 1e-12;

/// Cells whose lists would be longer than this keep none: a query reaching one turns to the
/// triangle hierarchy.
constexpr std::size_t longest_scanned_list = 48;

/// Levels above the binned one (coarse cells, few, with long lists) keep no working lists: they
/// are tested for splitting in the triangle hierarchy, and the cells of the binned level get
/// theirs by binning every triangle into a grid of the level's triples. Deeper levels filter
/// their lists from their parents'. This spares the list work of the coarse levels, each about
/// as costly as a fine one. The binned level is one above the deepest, at most 7 (a grid of
/// 2^21 cells): the fastest of 0..4 above it on icospheres (bench/surface_distance_bench.cpp).
constexpr int binned_level = 7;
constexpr int levels_below_binned = 1;

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

/// The children of a cell whose triples a box meets, from where it meets them along each axis.
/// Child k is high along axis a when bit a of k is set: the children low along x are 0, 2, 4, 6
/// (mask 0x55), high 1, 3, 5, 7 (0xaa); along y 0x33 and 0xcc; along z 0x0f and 0xf0. A side
/// code holds two bits an axis (bit 0: the box meets the low children's triples along it, bit 1:
/// the high ones'), axis a at bits 2a and 2a + 1; the mask of that code is the children met.
constexpr std::array<std::uint8_t, 64> children_met = [] {
    constexpr std::uint8_t sides[3][4] = {
        {0x00, 0x55, 0xaa, 0xff}, {0x00, 0x33, 0xcc, 0xff}, {0x00, 0x0f, 0xf0, 0xff}};
    std::array<std::uint8_t, 64> out{};
    for (unsigned code = 0; code < 64; ++code) {
        unsigned m = 0xff;
        for (unsigned a = 0; a < 3; ++a) m &= sides[a][(code >> (2 * a)) & 3u];
        out[code] = static_cast<std::uint8_t>(m);
    }
    return out;
}();
static_assert(children_met[0b111111] == 0xff && children_met[0b010101] == 0x01 &&
              children_met[0b101010] == 0x80);

}  // namespace

SurfaceDistanceTree::SurfaceDistanceTree(const Surface& surface, Box3 domain, Options options)
    : surface_(&surface), tree_(domain, options.depth) {
    if (surface.empty()) throw InvalidInput("distance tree: the surface is empty");
    corners_.resize(surface.size());
    for (std::size_t t = 0; t < surface.size(); ++t) corners_[t] = surface.triangle(t);
    normals_ = pseudo_normals(surface);
    hierarchy_ = TriangleHierarchy(corners_);
    build_lists();
    if (options.balanced) {
        tree_.balance([&](std::size_t c) {
            const std::size_t first = tree_.cell(c).first_child;
            list_from_hierarchy(first, first + 8);
        });
    }
}

/// The lists of the cells [begin, begin + offsets.size() - 1) of one level while the tree is
/// built, for the cells that keep none for the queries (their lists are longer): the lists of
/// the level's children are filtered from them. Two of these take turns, so that their arrays
/// are allocated once.
struct SurfaceDistanceTree::Level {
    std::size_t begin = 0;
    std::vector<std::size_t> offsets;  ///< cell begin + i: work[offsets[i], offsets[i + 1])
    std::vector<std::uint32_t> work;   ///< the lists, one after another
};

std::span<const std::uint32_t> SurfaceDistanceTree::list_of(const Level& level,
                                                            std::size_t c) const {
    if (listed_[c]) return cell_triangles(c);
    const std::size_t i = c - level.begin;
    return {level.work.data() + level.offsets[i], level.work.data() + level.offsets[i + 1]};
}

void SurfaceDistanceTree::build_lists() {
    std::vector<Box3> bounds(corners_.size());
    for (std::size_t t = 0; t < corners_.size(); ++t) bounds[t] = bounding_box(corners_[t]);
    const int binned = std::clamp(tree_.max_depth() - levels_below_binned, 0, binned_level);
    Level level, next;
    offsets_ = {0};
    // Level by level (cells are appended breadth-first, so [begin, end) is one level): split a
    // cell while its edge exceeds its distance to the surface (§1.3). Only triangles on its list
    // can be that near, since the triple holds every point within one edge. The tests and the
    // children's lists are computed on all worker threads, then packed in cell order, so the
    // tree is the same for any thread count.
    for (std::size_t begin = 0, end = tree_.size(); begin < end; begin = end, end = tree_.size()) {
        const int l = tree_.cell(begin).level;
        if (l < binned) list_from_hierarchy(begin, end);
        if (l == binned) bin_lists(begin, end, bounds, level);
        if (l == tree_.max_depth()) break;
        std::vector<std::uint8_t> near(end - begin, 0);
        parallel_for(
            end - begin,
            [&](std::size_t i) {
                near[i] =
                    l < binned ? is_near_coarse(begin + i) : is_near(level, begin + i, bounds);
            },
            expensive_grain);
        std::vector<std::uint32_t> parents;
        for (std::size_t c = begin; c < end; ++c) {
            if (!near[c - begin]) continue;
            tree_.split(c);
            parents.push_back(static_cast<std::uint32_t>(c));
        }
        if (parents.empty()) break;
        if (l >= binned) {
            list_children(level, parents, bounds, next);
            std::swap(level, next);
        }
    }
}

void SurfaceDistanceTree::place_lists(std::size_t begin, std::span<const std::uint32_t> counts,
                                      Level& level) {
    SLC_ASSERT(offsets_.size() == begin + 1 && begin + counts.size() == tree_.size(),
               "lists follow cell order");
    level.begin = begin;
    level.offsets.assign(counts.size() + 1, 0);
    listed_.resize(tree_.size(), 0);
    // The deepest level's cells are never split, so a list too long to store is not needed.
    const bool deepest = tree_.cell(begin).level == tree_.max_depth();
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const std::uint32_t m = counts[i];
        const bool stored = m <= longest_scanned_list;
        SLC_ASSERT(!stored || offsets_.back() + std::uint64_t{m} <= 0xffffffffu,
                   "lists fit 32-bit offsets");
        offsets_.push_back(offsets_.back() + (stored ? m : 0));
        listed_[begin + i] = stored ? 1 : 0;
        level.offsets[i + 1] = level.offsets[i] + (stored || deepest ? 0 : m);
    }
    triangles_.resize(offsets_.back());
    level.work.resize(level.offsets.back());
}

std::uint32_t* SurfaceDistanceTree::list_start(Level& level, std::size_t c) {
    return listed_[c] ? triangles_.data() + offsets_[c]
                      : level.work.data() + level.offsets[c - level.begin];
}

void SurfaceDistanceTree::list_from_hierarchy(std::size_t begin, std::size_t end) {
    // Up to one more than a stored list, from the hierarchy; the root's is every triangle.
    std::vector<std::vector<std::uint32_t>> found(end - begin);
    parallel_for(
        end - begin,
        [&](std::size_t i) {
            const std::size_t c = begin + i;
            std::vector<std::uint32_t>& got = found[i];
            if (c == 0) {
                got.resize(std::min(corners_.size(), longest_scanned_list + 1));
                std::iota(got.begin(), got.end(), 0u);
                return;
            }
            const double slack = triple_slack * tree_.edge(tree_.cell(c).level);
            got.reserve(longest_scanned_list + 1);
            hierarchy_.any_overlapping(tree_.triple(c).inflated(slack), [&](std::uint32_t t) {
                got.push_back(t);
                return got.size() > longest_scanned_list;
            });
            std::sort(got.begin(), got.end());
        },
        expensive_grain);
    listed_.resize(tree_.size(), 0);
    for (std::size_t i = 0; i < found.size(); ++i) {
        const bool stored = found[i].size() <= longest_scanned_list;
        if (stored) triangles_.insert(triangles_.end(), found[i].begin(), found[i].end());
        offsets_.push_back(static_cast<std::uint32_t>(triangles_.size()));
        listed_[begin + i] = stored ? 1 : 0;
    }
}

bool SurfaceDistanceTree::is_near_coarse(std::size_t c) const {
    const Box3 b = tree_.box(c);
    const double h = tree_.edge(tree_.cell(c).level);
    // The same triangles as its list, those whose boxes meet the triple (for the root, the
    // others are farther than h), less those whose boxes are h or more from the cell, which
    // distance_lower_bound would rule out: a node's box is no farther than the boxes inside it,
    // so a node that far holds none nearer.
    const Box3 triple = tree_.triple(c).inflated(triple_slack * h);
    return hierarchy_.any_of(
        [&](const Box3& box) { return box.overlaps(triple) && std::sqrt(distance2(box, b)) < h; },
        [&](std::uint32_t t) { return distance_lower_bound(corners_[t], b, h) < h; });
}

void SurfaceDistanceTree::bin_lists(std::size_t begin, std::size_t end,
                                    std::span<const Box3> bounds, Level& level) {
    const int l = tree_.cell(begin).level;
    const std::uint32_t g = std::uint32_t{1} << l;
    const double h = tree_.edge(l), slack = triple_slack * h;
    // Along each axis, the triples' extents at this level, computed as Octree::triple and
    // Box3::inflated compute them, so that the tests below are exactly the lists' tests. Both
    // ends increase with the index: the triples a box meets along an axis are a range.
    std::vector<double> lo[3], hi[3];
    const Box3& root = tree_.root_box();
    for (int a = 0; a < 3; ++a) {
        lo[a].resize(g);
        hi[a].resize(g);
        for (std::uint32_t i = 0; i < g; ++i) {
            const double cell_lo = root.lo[a] + i * h, cell_hi = cell_lo + h;
            lo[a][i] = cell_lo - h - slack;
            hi[a][i] = cell_hi + h + slack;
        }
    }
    // The level's cells by grid position (the root's when the level is 0, the same way).
    std::vector<std::uint32_t> slot(std::size_t{g} * g * g, no_slot);
    for (std::size_t c = begin; c < end; ++c) {
        const Octree::Cell& cell = tree_.cell(c);
        slot[cell.ix + std::size_t{g} * (cell.iy + std::size_t{g} * cell.iz)] =
            static_cast<std::uint32_t>(c - begin);
    }
    // Every triangle to the existing cells whose triples its box meets: counted, then written,
    // in increasing triangle order (one thread: the order of the lists is the triangles').
    auto for_each_cell = [&](std::uint32_t t, auto&& f) {
        std::uint32_t from[3], to[3];
        for (int a = 0; a < 3; ++a) {
            // First triple reaching up to the box's low end; last starting below its high end.
            from[a] = static_cast<std::uint32_t>(
                std::lower_bound(hi[a].begin(), hi[a].end(), bounds[t].lo[a]) - hi[a].begin());
            to[a] = static_cast<std::uint32_t>(
                std::upper_bound(lo[a].begin(), lo[a].end(), bounds[t].hi[a]) - lo[a].begin());
        }
        for (std::uint32_t z = from[2]; z < to[2]; ++z)
            for (std::uint32_t y = from[1]; y < to[1]; ++y)
                for (std::uint32_t x = from[0]; x < to[0]; ++x) {
                    const std::uint32_t i = slot[x + std::size_t{g} * (y + std::size_t{g} * z)];
                    if (i != no_slot) f(i);
                }
    };
    const auto n = static_cast<std::uint32_t>(corners_.size());
    std::vector<std::uint32_t> counts(end - begin, 0);
    if (begin == 0) {
        counts[0] = n;  // the root lists every triangle
    } else {
        for (std::uint32_t t = 0; t < n; ++t)
            for_each_cell(t, [&](std::uint32_t i) { ++counts[i]; });
    }
    place_lists(begin, counts, level);
    std::vector<std::uint32_t*> to(end - begin);
    for (std::size_t i = 0; i < to.size(); ++i) to[i] = list_start(level, begin + i);
    if (begin == 0) {
        std::iota(to[0], to[0] + n, 0u);
    } else {
        for (std::uint32_t t = 0; t < n; ++t)
            for_each_cell(t, [&](std::uint32_t i) { *to[i]++ = t; });
    }
}

bool SurfaceDistanceTree::is_near(const Level& level, std::size_t c,
                                  std::span<const Box3> bounds) const {
    const Box3 b = tree_.box(c);
    const double h = tree_.edge(tree_.cell(c).level);
    // The box distance alone rules out most triangles of a far cell.
    const auto list = list_of(level, c);
    return std::any_of(list.begin(), list.end(), [&](std::uint32_t t) {
        return std::sqrt(distance2(bounds[t], b)) < h &&
               distance_lower_bound(corners_[t], b, h) < h;
    });
}

void SurfaceDistanceTree::list_children(const Level& level, std::span<const std::uint32_t> parents,
                                        std::span<const Box3> bounds, Level& next) {
    // First pass, one parent per iteration: for each triangle of its list, the mask of the
    // children whose triples its box meets (children_met), and the length of each child's list.
    std::vector<std::size_t> entry(parents.size() + 1, 0);
    for (std::size_t j = 0; j < parents.size(); ++j)
        entry[j + 1] = entry[j] + list_of(level, parents[j]).size();
    std::vector<std::uint8_t> masks(entry.back());
    std::vector<std::uint32_t> counts(8 * parents.size(), 0);
    parallel_for(
        parents.size(),
        [&](std::size_t j) {
            const std::uint32_t first = tree_.cell(parents[j]).first_child;
            const double slack = triple_slack * tree_.edge(tree_.cell(first).level);
            const Box3 low = tree_.triple(first).inflated(slack);
            const Box3 high = tree_.triple(first + 7).inflated(slack);
            // The lengths from a histogram of the side codes: one increment per triangle.
            std::uint32_t histogram[64] = {};
            std::uint8_t* mask = masks.data() + entry[j];
            for (std::uint32_t s : list_of(level, parents[j])) {
                const Box3& b = bounds[s];
                unsigned code = 0;
                for (int a = 0; a < 3; ++a) {
                    // & rather than &&: no branch to mispredict.
                    const unsigned side =
                        (unsigned{b.lo[a] <= low.hi[a]} & unsigned{b.hi[a] >= low.lo[a]}) |
                        (unsigned{b.lo[a] <= high.hi[a]} & unsigned{b.hi[a] >= high.lo[a]}) << 1;
                    code |= side << (2 * a);
                }
                *mask++ = children_met[code];
                ++histogram[code];
            }
            std::uint32_t count[8] = {};
            for (unsigned code = 0; code < 64; ++code)
                if (histogram[code] != 0)
                    for (unsigned m = children_met[code]; m != 0; m &= m - 1)
                        count[std::countr_zero(m)] += histogram[code];
            std::copy(count, count + 8, counts.begin() + static_cast<std::ptrdiff_t>(8 * j));
        },
        expensive_grain);
    // The children follow their parents in order: the next level is exactly the children, and
    // their stored lists are appended in cell order.
    const std::size_t begin = tree_.cell(parents[0]).first_child;
    const bool deepest = tree_.cell(begin).level == tree_.max_depth();
    place_lists(begin, counts, next);
    // Second pass: each triangle to the lists its mask names, in the parent's (increasing)
    // order.
    parallel_for(
        parents.size(),
        [&](std::size_t j) {
            std::uint32_t* to[8];
            unsigned wanted = 0;  // the children whose lists are kept
            for (std::size_t k = 0; k < 8; ++k) {
                to[k] = list_start(next, begin + 8 * j + k);
                if (!deepest || listed_[begin + 8 * j + k]) wanted |= 1u << k;
            }
            const std::uint8_t* mask = masks.data() + entry[j];
            for (std::uint32_t s : list_of(level, parents[j]))
                for (unsigned m = *mask++ & wanted; m != 0; m &= m - 1)
                    *to[std::countr_zero(m)]++ = s;
        },
        expensive_grain);
}

NearestFacet SurfaceDistanceTree::nearest_facet(Vec3 x) const {
    std::uint32_t c = tree_.leaf_at(x);
    NearestFacet best;
    for (;;) {
        if (!listed_[c]) {
            hierarchy_.nearest(corners_, x, best);
            break;
        }
        for (std::uint32_t t : cell_triangles(c)) best.offer(t, slc::closest_point(corners_[t], x));
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
    // Cells one to two mean edges wide. A level deeper (cells up to one edge wide) builds in
    // about 1.5 times the time and answers queries near the surface no faster: its lists are
    // mostly too long to keep (bench/surface_distance_bench.cpp).
    const int level =
        static_cast<int>(std::ceil(std::log2(domain.width() / std::max(2.0 * mean, 1e-300))));
    const int deepest = Octree::max_resolvable_depth(domain);
    return std::clamp(level, std::min(2, deepest), std::min(10, deepest));
}

}  // namespace slc
