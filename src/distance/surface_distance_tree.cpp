// SurfaceDistanceTree: building the octree and its triangle lists; its part of the climbing query
// (climbing_query_impl.hpp) is instantiated here.
#include "slc/distance/surface_distance_tree.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numeric>

#include "climbing_query_impl.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

/// Half the diagonal of a unit cube, √3/2.
constexpr double half_diagonal = 0.8660254037844386;

/// True when a lower bound of the distance from the cube b (edge h) to triangle t (bounding box
/// box, unit normal n) is below h: the larger of the distance between their boxes and the
/// distance from the cube's centre less its half-diagonal. The distance from the centre to t's
/// plane, at most its distance to t, rules out most far pairs before the closest point is
/// found (with a margin beyond rounding). NOTE: §1.3 splits on the exact cell–surface
/// distance; a lower bound splits a few more cells (never fewer), which changes the cost of a
/// query, never its answer.
bool nearer_than_edge(const Triangle3& t, const Box3& box, Vec3 n, const Box3& b, double h) {
    if (!(std::sqrt(distance2(box, b)) < h)) return false;
    const double plane = std::abs(dot(b.center() - t.a, n)) - half_diagonal * h;
    if (plane > h * (1.0 + 1e-9)) return false;
    return std::sqrt(closest_point(t, b.center()).distance2) - half_diagonal * h < h;
}

/// One level's cells in bricks of 4×4×4 grid positions, each brick found by hashing its
/// position: a dense grid of the level would hold 2^(3l) slots, nearly all empty where the
/// cells hug a surface. Position (x, y, z) is bit (x & 3) + 4 (y & 3) + 16 (z & 3) of its brick.
/// A parent's eight children share a brick, so there are at most a level's cells / 8 bricks.
class Bricks {
public:
    struct Brick {
        std::uint64_t present = 0;  ///< the positions holding a cell of the level
        std::uint64_t stored = 0;   ///< the cells whose lists are kept
    };

    Bricks(const Octree& tree, std::size_t begin, std::size_t end) {
        std::size_t capacity = 16;
        while (capacity < (end - begin) / 4 + 1) capacity *= 2;
        keys_.assign(capacity, empty_key);
        slots_.resize(capacity);
        mask_ = capacity - 1;
        bricks_.reserve((end - begin) / 8 + 1);
        for (std::size_t c = begin; c < end; ++c) {
            const Octree::Cell& cell = tree.cell(c);
            at(cell, true)->present |= std::uint64_t{1}
                                       << bit(cell.coords[0], cell.coords[1], cell.coords[2]);
        }
    }

    /// The brick at brick position (x, y, z), nullptr if the level has no cell there; with
    /// add, made when missing.
    Brick* find(std::uint32_t x, std::uint32_t y, std::uint32_t z, bool add = false) {
        const std::uint64_t key = x | std::uint64_t{y} << 21 | std::uint64_t{z} << 42;
        for (std::size_t s = (key * 0x9e3779b97f4a7c15ull) >> 40 & mask_;; s = (s + 1) & mask_) {
            if (keys_[s] == key) return &bricks_[slots_[s]];
            if (keys_[s] != empty_key) continue;
            if (!add) return nullptr;
            keys_[s] = key;
            slots_[s] = static_cast<std::uint32_t>(bricks_.size());
            return &bricks_.emplace_back();
        }
    }

    /// The brick of a cell of the level.
    Brick* at(const Octree::Cell& cell, bool add = false) {
        return find(cell.coords[0] >> 2, cell.coords[1] >> 2, cell.coords[2] >> 2, add);
    }

    /// The number of the brick b, from 0 to size() − 1.
    std::size_t index(const Brick& b) const {
        return static_cast<std::size_t>(&b - bricks_.data());
    }
    std::size_t size() const { return bricks_.size(); }

    static unsigned bit(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        return (x & 3u) + 4u * (y & 3u) + 16u * (z & 3u);
    }

private:
    static constexpr std::uint64_t empty_key = ~std::uint64_t{0};
    std::vector<std::uint64_t> keys_;
    std::vector<std::uint32_t> slots_;
    std::vector<Brick> bricks_;  ///< room for every brick reserved: addresses stay
    std::size_t mask_ = 0;
};

/// The positions [from, to) along one axis of a brick, as bits of its 4-bit run: along x, the
/// mask of a row of the brick.
unsigned run_bits(std::uint32_t from, std::uint32_t to) { return (1u << to) - (1u << from); }

/// The brick mask of the positions [x0, x1) × [y0, y1) × [z0, z1) inside it (each in 0..4):
/// a row's bits repeated at each y, then the plane repeated at each z (no carries: the copies
/// do not overlap).
std::uint64_t block_mask(const std::uint32_t from[3], const std::uint32_t to[3]) {
    const std::uint64_t row = run_bits(from[0], to[0]);
    std::uint64_t ys = 0, zs = 0;
    for (std::uint32_t y = from[1]; y < to[1]; ++y) ys |= std::uint64_t{1} << (4 * y);
    for (std::uint32_t z = from[2]; z < to[2]; ++z) zs |= std::uint64_t{1} << (16 * z);
    return row * ys * zs;
}

}  // namespace

SurfaceDistanceTree::SurfaceDistanceTree(const Surface& surface, Box3 domain, Options options)
    : surface_(&surface), tree_(domain, options.depth) {
    if (surface.empty()) throw InvalidInput("distance tree: the surface is empty");
    corners_.resize(surface.size());
    for (std::size_t t = 0; t < surface.size(); ++t) corners_[t] = surface.triangle(t);
    normals_ = pseudo_normals(surface);
    hierarchy_ = TriangleHierarchy(corners_, TriangleHierarchy::Bounds::boxes_and_slabs);
    build_lists();
    if (options.balanced) {
        tree_.balance([&](std::size_t c) {
            const std::size_t first = tree_.cell(c).first_child;
            list_from_hierarchy(first, first + 8);
        });
    }
}

void SurfaceDistanceTree::build_lists() {
    offsets_ = {0};
    // Level by level (cells are appended breadth-first, so [begin, end) is one level): split a
    // cell while its edge exceeds its distance to the surface (§1.3). Only triangles whose boxes
    // meet its triple can be that near, since the triple holds every point within one edge. The
    // levels above the deepest (few cells, with long lists) are split and listed in the triangle
    // hierarchy; the deepest bins every triangle into the triples it meets and writes only the
    // lists short enough to keep (binning the two or three deepest levels as well built 1.1 to
    // 1.4 times slower on icospheres of 1280 to 327680 triangles). The tests do not depend on
    // the thread count, so neither does the tree.
    for (std::size_t begin = 0, end = tree_.size(); begin < end; begin = end, end = tree_.size()) {
        if (tree_.cell(begin).level == tree_.max_depth()) {
            bin_lists(begin, end);
            break;
        }
        list_from_hierarchy(begin, end);
        std::vector<std::uint8_t> near(end - begin, 0);
        parallel_for(
            near.size(), [&](std::size_t i) { near[i] = is_near(begin + i); }, expensive_grain);
        bool split = false;
        for (std::size_t c = begin; c < end; ++c) {
            if (!near[c - begin]) continue;
            tree_.split(c);
            split = true;
        }
        if (!split) break;
    }
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

bool SurfaceDistanceTree::is_near(std::size_t c) const {
    const Box3 b = tree_.box(c);
    const double h = tree_.edge(tree_.cell(c).level);
    // The same triangles as its list, those whose boxes meet the triple (for the root, the
    // others are farther than h), less those whose boxes are h or more from the cell, which
    // nearer_than_edge rules out: a node's box is no farther than the boxes inside it,
    // so a node that far holds none nearer.
    const Box3 triple = tree_.triple(c).inflated(triple_slack * h);
    return hierarchy_.any_of(
        [&](const Box3& box) { return box.overlaps(triple) && std::sqrt(distance2(box, b)) < h; },
        [&](std::uint32_t t) {
            return nearer_than_edge(corners_[t], hierarchy_.box(t), normals_.face[t], b, h);
        });
}

void SurfaceDistanceTree::bin_lists(std::size_t begin, std::size_t end) {
    const std::span<const Box3> bounds = hierarchy_.boxes();
    const int l = tree_.cell(begin).level;
    const std::uint32_t g = std::uint32_t{1} << l;
    const double h = tree_.edge(l), slack = triple_slack * h, inverse_h = 1.0 / h;
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
    auto index_near = [&](double x) {
        return static_cast<std::uint32_t>(std::clamp(std::floor(x), 0.0, static_cast<double>(g)));
    };
    Bricks bricks(tree_, begin, end);
    // f(brick, mask) for each brick holding cells whose triples the box of
    // triangle t meets, the mask naming those cells (the root lists every triangle).
    auto for_each_brick = [&](std::uint32_t t, auto&& f) {
        if (begin == 0) {
            f(*bricks.at(tree_.cell(0)), std::uint64_t{1});
            return;
        }
        std::uint32_t from[3], to[3];
        for (int a = 0; a < 3; ++a) {
            // The first triple reaching up to the box's low end and the first starting past its
            // high end, guessed from the edge and settled by the exact extents.
            const double low = bounds[t].lo[a], high = bounds[t].hi[a];
            std::uint32_t i = index_near((low - root.lo[a]) * inverse_h - 2.0);
            while (i > 0 && hi[a][i - 1] >= low) --i;
            while (i < g && hi[a][i] < low) ++i;
            std::uint32_t j = index_near((high - root.lo[a]) * inverse_h + 2.0);
            while (j > 0 && lo[a][j - 1] > high) --j;
            while (j < g && lo[a][j] <= high) ++j;
            if (i >= j) return;
            from[a] = i;
            to[a] = j;
        }
        for (std::uint32_t bz = from[2] / 4; bz <= (to[2] - 1) / 4; ++bz)
            for (std::uint32_t by = from[1] / 4; by <= (to[1] - 1) / 4; ++by)
                for (std::uint32_t bx = from[0] / 4; bx <= (to[0] - 1) / 4; ++bx) {
                    Bricks::Brick* brick = bricks.find(bx, by, bz);
                    if (brick == nullptr) continue;
                    const std::uint32_t corner[3] = {4 * bx, 4 * by, 4 * bz};
                    std::uint32_t inside_from[3], inside_to[3];
                    for (int a = 0; a < 3; ++a) {
                        inside_from[a] = std::max(from[a], corner[a]) - corner[a];
                        inside_to[a] = std::min(to[a], corner[a] + 4) - corner[a];
                    }
                    const std::uint64_t m = block_mask(inside_from, inside_to) & brick->present;
                    if (m != 0) f(*brick, m);
                }
    };
    // The counting sort in parts of the triangles, one a thread: each part counts its
    // triangles into each cell's list, and writes them after the parts before it, so every list
    // holds its triangles in increasing order whatever the number of parts.
    const auto n = static_cast<std::uint32_t>(corners_.size());
    const std::size_t parts = static_cast<std::size_t>(std::max(1, thread_count()));
    // count[p][brick][position]: part p's triangles in the list of that cell, then where part p
    // writes the next of them.
    std::vector<std::vector<std::array<std::uint32_t, 64>>> count(
        parts, std::vector<std::array<std::uint32_t, 64>>(bricks.size()));
    // visit(part's counts of the brick, brick, mask, t) for each brick of each triangle t, the
    // parts on all threads.
    auto each_part = [&](auto&& visit) {
        parallel_for(
            parts,
            [&](std::size_t p) {
                const auto first = static_cast<std::uint32_t>(n * p / parts),
                           last = static_cast<std::uint32_t>(n * (p + 1) / parts);
                for (std::uint32_t t = first; t < last; ++t) {
                    for_each_brick(t, [&](Bricks::Brick& brick, std::uint64_t m) {
                        visit(count[p][bricks.index(brick)], brick, m, t);
                    });
                }
            },
            1);
    };
    each_part(
        [](std::array<std::uint32_t, 64>& c, const Bricks::Brick&, std::uint64_t m, std::uint32_t) {
            for (std::uint64_t k = m; k != 0; k &= k - 1) ++c[std::countr_zero(k)];
        });
    // The lists short enough to keep are placed in cell order; the others are never written.
    SLC_ASSERT(offsets_.size() == begin + 1 && end == tree_.size(), "lists follow cell order");
    listed_.resize(tree_.size(), 0);
    for (std::size_t c = begin; c < end; ++c) {
        const Octree::Cell& cell = tree_.cell(c);
        Bricks::Brick& brick = *bricks.at(cell);
        const std::size_t i = bricks.index(brick);
        const unsigned b = Bricks::bit(cell.coords[0], cell.coords[1], cell.coords[2]);
        std::uint64_t m = 0;
        for (std::size_t p = 0; p < parts; ++p) m += count[p][i][b];
        const bool stored = m <= longest_scanned_list;
        SLC_ASSERT(!stored || offsets_.back() + m <= 0xffffffffu, "lists fit 32-bit offsets");
        if (stored) brick.stored |= std::uint64_t{1} << b;
        std::uint32_t at = offsets_.back();  // where its list starts
        for (std::size_t p = 0; p < parts; ++p) std::swap(at, count[p][i][b]), at += count[p][i][b];
        offsets_.push_back(offsets_.back() + (stored ? static_cast<std::uint32_t>(m) : 0));
        listed_[c] = stored ? 1 : 0;
    }
    // Second pass: each part's triangles to the kept lists.
    triangles_.resize(offsets_.back());
    each_part([&](std::array<std::uint32_t, 64>& c, const Bricks::Brick& brick, std::uint64_t m,
                  std::uint32_t t) {
        for (std::uint64_t k = m & brick.stored; k != 0; k &= k - 1)
            triangles_[c[std::countr_zero(k)]++] = t;
    });
}

template class ClimbingQuery<SurfaceDistanceTree, TriangleKernel>;

int SurfaceDistanceTree::default_depth(const Surface& surface, const Box3& domain) {
    double total = 0.0;
    for (std::size_t t = 0; t < surface.size(); ++t) {
        const Triangle3 tri = surface.triangle(t);
        total += distance(tri.a, tri.b) + distance(tri.b, tri.c) + distance(tri.c, tri.a);
    }
    const double mean = total / (3.0 * static_cast<double>(surface.size()));
    // Cells four to eight mean edges wide. Near the surface a cell's triple then meets far more
    // triangles than a list may hold, so queries there finish in the triangle hierarchy, as
    // they did a level deeper (cells two to four edges wide, triples of 100 to 400 triangles):
    // that level built in 1.2 to 1.9 times the time and answered no faster
    // (bench/surface_distance_bench.cpp; docs/notes/performance.md).
    const int level =
        static_cast<int>(std::ceil(std::log2(domain.width() / std::max(8.0 * mean, 1e-300))));
    const int deepest = Octree::max_resolvable_depth(domain);
    return std::clamp(level, std::min(2, deepest), std::min(10, deepest));
}

}  // namespace slc
