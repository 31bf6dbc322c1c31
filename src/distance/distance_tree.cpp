// DistanceTree: building the tree and its segment lists, its start grid, and its part of the
// climbing query (climbing_query_impl.hpp), instantiated here.
#include "slc/distance/distance_tree.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>
#include <numeric>

#include "climbing_query_impl.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

/// A level of the tree is built on all worker threads when its cells list at least this many
/// segments in all: below, starting the threads costs more than the work.
constexpr std::size_t min_parallel_work = 4096;

/// True if the closed segment meets the closed box (separating-axis test: bounding boxes, then
/// the segment's line against the box corners).
bool meets(Segment s, const Box& b) {
    if (std::max(s.a.x, s.b.x) < b.lo.x || std::min(s.a.x, s.b.x) > b.hi.x ||
        std::max(s.a.y, s.b.y) < b.lo.y || std::min(s.a.y, s.b.y) > b.hi.y) {
        return false;
    }
    const Vec2 d = s.b - s.a;
    const double c0 = cross(d, b.lo - s.a);
    const double c1 = cross(d, Vec2{b.hi.x, b.lo.y} - s.a);
    const double c2 = cross(d, b.hi - s.a);
    const double c3 = cross(d, Vec2{b.lo.x, b.hi.y} - s.a);
    const bool all_left = c0 > 0 && c1 > 0 && c2 > 0 && c3 > 0;
    const bool all_right = c0 < 0 && c1 < 0 && c2 < 0 && c3 < 0;
    return !all_left && !all_right;
}

/// Euclidean distance between a segment and a box: zero if they meet, else attained at a vertex
/// of one of the two convex sets.
double distance(Segment s, const Box& b) {
    if (meets(s, b)) return 0.0;
    double d2 = std::min(norm2(b.clamp(s.a) - s.a), norm2(b.clamp(s.b) - s.b));
    const Vec2 corners[4] = {b.lo, {b.hi.x, b.lo.y}, b.hi, {b.lo.x, b.hi.y}};
    for (Vec2 q : corners) d2 = std::min(d2, closest_point(s, q).distance2);
    return std::sqrt(d2);
}

}  // namespace

DistanceTree::DistanceTree(const Interface& curves, Box domain, Options options)
    : curves_(&curves), tree_(domain, options.depth) {
    if (curves.empty()) throw InvalidInput("distance tree: the interface is empty");
    segment_ends_.reserve(curves.size());
    for (std::size_t i = 0; i < curves.size(); ++i) segment_ends_.push_back(curves.segment(i));
    hierarchy_ = SegmentHierarchy(segment_ends_);
    build_lists();
    build_start_grid();
    if (options.triangulate) {
        mesh_ = triangulate(tree_);
        vertex_nearest_ = closest_points(mesh_.vertices);
    }
}

void DistanceTree::build_lists() {
    // Bounding boxes decide membership: a segment whose box meets a triple is listed even if
    // the segment itself passes by a corner, which only lengthens a list, never drops a segment.
    std::vector<Box> bounds(segment_ends_.size());
    for (std::size_t s = 0; s < segment_ends_.size(); ++s)
        bounds[s] = bounding_box(segment_ends_[s]);
    // The segments of parent's list whose boxes meet child k's triple, written to out; returns
    // their number.
    auto filter = [&](std::size_t parent, std::uint32_t k, std::uint32_t* out) {
        const Box t = tree_.triple(k).inflated(triple_slack * tree_.edge(tree_.cell(k).level));
        std::uint32_t n = 0;
        for (std::uint32_t s : cell_segments(parent))
            if (bounds[s].overlaps(t)) out[n++] = s;
        return n;
    };
    // Lists are appended in cell order (children are created, and listed, together), so the
    // one array segments_ with offsets_ is built directly: the root lists every segment.
    segments_.resize(segment_ends_.size());
    std::iota(segments_.data(), segments_.data() + segments_.size(), 0u);
    offsets_ = {0, static_cast<std::uint32_t>(segments_.size())};

    // Cells are appended breadth-first, so [begin, end) below is one whole level, and the tree
    // grows level by level: split a cell while its edge exceeds its distance to Γ (§1.3, Eq. 6).
    // Only segments on the cell's list can be that near, since the triple holds every point
    // within one edge. The tests, and the children's lists, are computed on all worker threads
    // (each child's list into its own stretch of a scratch array, then packed in cell order), so
    // the tree and its lists are those of a sequential pass, whatever the thread count.
    // Uninitialized, and grown only when a level needs more: a child's stretch is as long as
    // its parent's list but its list is usually far shorter, and untouched pages cost nothing.
    std::unique_ptr<std::uint32_t[]> scratch;
    std::size_t scratch_size = 0;
    for (std::size_t begin = 0, end = tree_.size(); begin < end; begin = end, end = tree_.size()) {
        const std::size_t level_work = offsets_[end] - offsets_[begin];
        const std::size_t min_iterations = level_work >= min_parallel_work ? 1 : end - begin + 1;
        std::vector<std::uint8_t> near(end - begin, 0);
        parallel_for(
            end - begin,
            [&](std::size_t i) {
                const std::size_t c = begin + i;
                const int level = tree_.cell(c).level;
                if (level == tree_.max_depth()) return;
                const Box b = tree_.box(c);
                const double h = tree_.edge(level);
                for (std::uint32_t s : cell_segments(c)) {
                    if (distance(segment_ends_[s], b) < h) {
                        near[i] = 1;
                        return;
                    }
                }
            },
            min_iterations);
        // Children, each with the start of its scratch stretch (four per parent, each as long
        // as the parent's list).
        std::vector<std::pair<std::uint32_t, std::size_t>> children;
        std::size_t stretch = 0;
        for (std::size_t c = begin; c < end; ++c) {
            if (!near[c - begin]) continue;
            const std::uint32_t first = tree_.split(c);
            const std::size_t length = offsets_[c + 1] - offsets_[c];
            for (std::uint32_t k = 0; k < 4; ++k, stretch += length)
                children.emplace_back(first + k, stretch);
        }
        if (children.empty()) break;
        if (stretch > scratch_size) {
            scratch_size = std::max(stretch, 2 * scratch_size);
            scratch.reset(new std::uint32_t[scratch_size]);
        }
        std::vector<std::uint32_t> count(children.size());
        parallel_for(
            children.size(),
            [&](std::size_t j) {
                const auto [k, at] = children[j];
                count[j] = filter(tree_.cell(k).parent, k, scratch.get() + at);
            },
            min_iterations);
        const std::size_t listed = segments_.size();
        for (std::uint32_t n : count) offsets_.push_back(offsets_.back() + n);
        segments_.resize(offsets_.back());
        parallel_for(
            children.size(),
            [&](std::size_t j) {
                std::copy_n(scratch.get() + children[j].second, count[j],
                            segments_.data() + offsets_[children[j].first]);
            },
            min_iterations);
        SLC_ASSERT(offsets_[children.front().first] == listed, "lists follow the cell order");
    }
    tree_.balance([&](std::size_t c) {
        const std::uint32_t first = tree_.cell(c).first_child;
        SLC_ASSERT(offsets_.size() == std::size_t{first} + 1, "lists follow the cell order");
        for (std::uint32_t k = first; k < first + 4; ++k) {
            const std::size_t at = segments_.size();
            segments_.resize(at + offsets_[c + 1] - offsets_[c]);
            const std::uint32_t n = filter(c, k, segments_.data() + at);
            segments_.resize(at + n);
            offsets_.push_back(static_cast<std::uint32_t>(segments_.size()));
        }
    });
}

void DistanceTree::Lists::resize(std::size_t n) {
    if (n > capacity_) {
        const std::size_t capacity = std::max(n, 2 * size_);
        void* grown = std::realloc(data_, capacity * sizeof(std::uint32_t));
        if (grown == nullptr) throw std::bad_alloc();
        data_ = static_cast<std::uint32_t*>(grown);
        capacity_ = capacity;
    }
    size_ = n;
}

void DistanceTree::build_start_grid() {
    first_child_.resize(tree_.size());
    for (std::size_t c = 0; c < tree_.size(); ++c) first_child_[c] = tree_.cell(c).first_child;
    // Two levels above the deepest, at most 2^8 blocks a side (256 KiB): the descent from a
    // block to its leaf is then at most two steps. Each cell at the start level, or a leaf above
    // it, fills its own blocks.
    start_level_ = std::clamp(tree_.depth() - 2, 0, 8);
    const std::uint32_t n = 1u << start_level_;
    start_grid_.resize(std::size_t{n} * n);
    std::vector<std::uint32_t> todo{0};
    while (!todo.empty()) {
        const std::uint32_t c = todo.back();
        todo.pop_back();
        const Quadtree::Cell& cell = tree_.cell(c);
        if (cell.level < start_level_ && !tree_.is_leaf(c)) {
            for (std::uint32_t k = 0; k < 4; ++k) todo.push_back(cell.first_child + k);
            continue;
        }
        const int up = start_level_ - cell.level;
        const std::uint32_t x0 = cell.coords[0] << up, y0 = cell.coords[1] << up, w = 1u << up;
        for (std::uint32_t gy = y0; gy < y0 + w; ++gy)
            std::fill_n(start_grid_.begin() + std::size_t{gy} * n + x0, w, c);
    }
}

std::uint32_t DistanceTree::leaf_at(Vec2 x) const {
    const Quadtree::LatticePoint q = tree_.lattice_point(x);
    const int depth = tree_.depth();
    const int shift = depth - start_level_;
    std::uint32_t c =
        start_grid_[(q[1] >> shift) * (std::uint64_t{1} << start_level_) + (q[0] >> shift)];
    // Quadtree::descend over the compact child array: one bit of each coordinate per level.
    int bit = depth - tree_.cell(c).level - 1;
    for (std::uint32_t child = first_child_[c]; child != Quadtree::no_cell;
         child = first_child_[c], --bit) {
        c = child + static_cast<std::uint32_t>((q[0] >> bit) & 1u) +
            2u * static_cast<std::uint32_t>((q[1] >> bit) & 1u);
    }
    return c;
}

bool DistanceTree::is_listed(std::size_t c) const {
    return offsets_[c + 1] - offsets_[c] <= longest_scanned_list;
}

ClosestPoint DistanceTree::signed_point(const NearestSegment& best, Vec2 x) const {
    const double d = std::sqrt(best.distance2);
    ClosestPoint result{0.0, best.point, best.segment, best.t};
    result.distance = d == 0.0 ? 0.0 : side_of(*curves_, best.segment, best.t, x) * d;
    return result;
}

template class ClimbingQuery<DistanceTree, SegmentKernel>;

int DistanceTree::default_depth(const Interface& curves, const Box& domain) {
    const double mean = length(curves) / static_cast<double>(curves.size());
    const int level =
        static_cast<int>(std::ceil(std::log2(domain.width() / std::max(mean, 1e-300))));
    const int deepest = Quadtree::max_resolvable_depth(domain);
    return std::clamp(level, std::min(2, deepest), std::min(16, deepest));
}

}  // namespace slc
