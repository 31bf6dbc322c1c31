// The working polygons of refinement (paper §2.2) as doubly linked vertices, the uniform grid of
// their segments for exact crossing tests, and the evaluation counter of G.
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "slc/core/error.hpp"
#include "slc/geometry/predicates.hpp"
#include "slc/geometry/segment.hpp"
#include "stages.hpp"

namespace slc::contouring {

Chain::Chain(std::vector<Vec2> vertices, std::span<const std::uint32_t> successor,
             std::span<const std::uint32_t> triangle)
    : points(std::move(vertices)),
      next(successor.begin(), successor.end()),
      prev(points.size()),
      home(triangle.begin(), triangle.end()),
      mid_value(points.size(), std::numeric_limits<double>::quiet_NaN()),
      frozen(points.size(), 0),
      unbound(points.size(), 0),
      alive(points.size(), 1),
      curve(points.size(), std::numeric_limits<std::uint32_t>::max()),
      lengths(points.size()) {
    for (std::uint32_t i = 0; i < next.size(); ++i) {
        prev[next[i]] = i;
        lengths[i] = distance(points[i], points[next[i]]);
    }
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        if (curve[i] != std::numeric_limits<std::uint32_t>::max()) continue;
        const auto c = static_cast<std::uint32_t>(curve_size.size());
        std::size_t size = 0;
        for (std::uint32_t j = i; curve[j] != c; j = next[j], ++size) curve[j] = c;
        curve_size.push_back(size);
    }
}

std::uint32_t Chain::insert_after(std::uint32_t u, Vec2 w) {
    const auto n = static_cast<std::uint32_t>(points.size());
    const std::uint32_t v = next[u];
    points.push_back(w);
    next.push_back(v);
    prev.push_back(u);
    home.push_back(home[u]);
    mid_value.push_back(std::numeric_limits<double>::quiet_NaN());
    frozen.push_back(0);
    unbound.push_back(unbound[u]);
    alive.push_back(1);
    curve.push_back(curve[u]);
    lengths.push_back(distance(w, points[v]));
    lengths[u] = distance(points[u], w);
    next[u] = n;
    prev[v] = n;
    mid_value[u] = std::numeric_limits<double>::quiet_NaN();
    frozen[u] = 0;
    ++curve_size[curve[u]];
    return n;
}

void Chain::remove(std::uint32_t x) {
    const std::uint32_t a = prev[x], b = next[x];
    if (length(x) > length(a)) home[a] = home[x];
    unbound[a] = unbound[a] | unbound[x];
    next[a] = b;
    prev[b] = a;
    lengths[a] = distance(points[a], points[b]);
    alive[x] = 0;
    mid_value[a] = std::numeric_limits<double>::quiet_NaN();
    frozen[a] = 0;
    --curve_size[curve[x]];
}

Interface Chain::to_interface() const {
    std::vector<std::vector<Vec2>> curves;
    std::vector<std::uint8_t> seen(points.size(), 0);
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        if (!alive[i] || seen[i]) continue;
        std::vector<Vec2> c;
        for (std::uint32_t j = i; !seen[j]; j = next[j]) {
            seen[j] = 1;
            c.push_back(points[j]);
        }
        curves.push_back(std::move(c));
    }
    return Interface(curves);
}

SegmentGrid::SegmentGrid(const Chain& chain, double cell)
    : chain_(chain), cell_(cell), origin_(chain.points.empty() ? Vec2{} : chain.points[0]) {
    SLC_ASSERT(cell > 0.0, "grid cells have a positive size");
    // Cells are about twice the mean segment, so most segments lie in one to four cells.
    heads_.assign(std::bit_ceil(std::max<std::size_t>(2 * chain.points.size(), 16)), none);
    entries_.reserve(2 * chain.points.size());
    for (std::uint32_t i = 0; i < chain.points.size(); ++i)
        if (chain.alive[i]) insert(i);
}

std::uint64_t SegmentGrid::key(std::int64_t ix, std::int64_t iy) const {
    constexpr std::int64_t bias = std::int64_t{1} << 31;
    return (static_cast<std::uint64_t>(ix + bias) << 32) | static_cast<std::uint64_t>(iy + bias);
}

std::uint32_t SegmentGrid::bucket(std::uint64_t key) const {
    // Fibonacci hashing: the high bits of the product mix both coordinates.
    const std::uint64_t h = key * 0x9e3779b97f4a7c15ull;
    return static_cast<std::uint32_t>(h >> 32) & static_cast<std::uint32_t>(heads_.size() - 1);
}

void SegmentGrid::add(std::uint64_t key, std::uint32_t u, std::uint32_t v) {
    if (entries_.size() >= heads_.size()) {  // keep buckets short: double and rethread
        heads_.assign(2 * heads_.size(), none);
        for (std::uint32_t e = 0; e < entries_.size(); ++e) {
            const std::uint32_t b = bucket(entries_[e].key);
            entries_[e].next = heads_[b];
            heads_[b] = e;
        }
    }
    const std::uint32_t b = bucket(key);
    entries_.push_back({key, u, v, heads_[b]});
    heads_[b] = static_cast<std::uint32_t>(entries_.size() - 1);
}

std::array<std::int64_t, 4> SegmentGrid::cell_range(const Box& b) const {
    // Cell indices are clamped far outside any domain: only extreme inputs would reach the clamp,
    // and then cells merely hold more segments.
    constexpr double limit = 1e9;
    auto index = [&](double x, double o) {
        return static_cast<std::int64_t>(std::floor(std::clamp((x - o) / cell_, -limit, limit)));
    };
    return {index(b.lo.x, origin_.x), index(b.lo.y, origin_.y), index(b.hi.x, origin_.x),
            index(b.hi.y, origin_.y)};
}

void SegmentGrid::insert(std::uint32_t u) {
    const auto [x0, y0, x1, y1] = cell_range(bounding_box(chain_.segment(u)));
    for (std::int64_t iy = y0; iy <= y1; ++iy)
        for (std::int64_t ix = x0; ix <= x1; ++ix) add(key(ix, iy), u, chain_.next[u]);
}

bool SegmentGrid::crosses(Segment s, std::span<const std::uint32_t> skip) const {
    return any_in_cells(bounding_box(s), [&](std::uint32_t u) {
        return std::find(skip.begin(), skip.end(), u) == skip.end() &&
               segments_intersect(s, chain_.segment(u));
    });
}

std::pair<double, std::uint32_t> SegmentGrid::first_hit_segment(Vec2 o, Vec2 d, double reach,
                                                                std::uint32_t skip) const {
    std::pair<double, std::uint32_t> best{std::numeric_limits<double>::infinity(), none};
    if (!(reach > 0.0) || !std::isfinite(reach)) return best;
    any_in_cells(bounding_box(Segment{o, o + reach * d}), [&](std::uint32_t u) {
        if (u == skip) return false;
        // o + t d = a + r (b − a), solved by cross products.
        const Segment s = chain_.segment(u);
        const Vec2 e = s.b - s.a, w = s.a - o;
        const double den = cross(d, e);
        if (den == 0.0) return false;
        const double t = cross(w, e) / den, r = cross(w, d) / den;
        if (t > 0.0 && t <= reach && r >= 0.0 && r <= 1.0 && t < best.first) best = {t, u};
        return false;
    });
    return best;
}

}  // namespace slc::contouring
