// The members of ClimbingQuery (slc/distance/climbing_query.hpp; paper §1.3), internal to the
// distance module: distance_tree.cpp and surface_distance_tree.cpp include this file after
// defining their trees' parts and instantiate the query there, so that the climb inlines the
// tree's leaf lookup, lists and kernel.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/climbing_query.hpp"

namespace slc {

/// What both trees' cell lists share. Relative growth of a triple before testing elements against
/// it: an element that misses the triple only by rounding still makes the list, which can only
/// lengthen a list, never make a query inexact.
inline constexpr double triple_slack = 1e-12;

/// Cells whose lists would be longer than this keep none: a query meeting one turns to the element
/// hierarchy, whose pruned descent beats a scan of so many elements.
inline constexpr std::size_t longest_scanned_list = 48;

template <class Tree, class Kernel>
typename Kernel::Nearest ClimbingQuery<Tree, Kernel>::nearest(Point x) const {
    const Tree& t = self();
    const std::span<const typename Kernel::Element> elements = t.elements();
    std::uint32_t c = t.leaf_at(x);
    typename Kernel::Nearest best;
    const bool plain = t.in_plain_range(x);
    for (;;) {
        if (!t.is_listed(c)) {
            // Queries come in batches of nearby points, so the nearest element of this thread's
            // last hierarchy search in the same tree is a near one to start from. It only prunes:
            // the answer is the same for any thread count.
            thread_local struct {
                const Tree* tree = nullptr;
                std::uint32_t element = 0;
            } last;
            const std::uint32_t hint = last.tree == &t ? last.element : Kernel::Hierarchy::no_hint;
            t.hierarchy().nearest(elements, x, best, hint);
            last = {&t, Kernel::element_of(best)};
            break;
        }
        for (std::uint32_t e : t.cell_list(c))
            best.offer(e, Kernel::closest_point(elements[e], x, plain));
        // Exact once the box of half-width m around x lies in the triple: every element nearer
        // than m meets the box, hence the triple, and so is on this list (§1.3).
        if (best.distance2 < std::numeric_limits<double>::infinity()) {
            const double m = std::sqrt(best.distance2);
            if (t.tree().triple(c).contains(Kernel::reach(x, m))) break;
        }
        if (c == 0) break;  // the root lists every element
        c = t.tree().cell(c).parent;
    }
    return best;
}

template <class Tree, class Kernel>
auto ClimbingQuery<Tree, Kernel>::closest_point(Point x) const -> Answer {
    return self().signed_point(nearest(x), x);
}

template <class Tree, class Kernel>
auto ClimbingQuery<Tree, Kernel>::nearest_point(Point x) const -> Answer {
    return Kernel::unsigned_point(nearest(x));
}

template <class Tree, class Kernel>
void ClimbingQuery<Tree, Kernel>::closest_points(std::span<const Point> xs,
                                                 std::span<Answer> out) const {
    SLC_ASSERT(xs.size() == out.size(), "one answer per query point");
    parallel_for(
        xs.size(), [&](std::size_t i) { out[i] = closest_point(xs[i]); }, expensive_grain);
}

template <class Tree, class Kernel>
auto ClimbingQuery<Tree, Kernel>::closest_points(std::span<const Point> xs) const
    -> std::vector<Answer> {
    std::vector<Answer> out(xs.size());
    closest_points(xs, out);
    return out;
}

template <class Tree, class Kernel>
std::vector<double> ClimbingQuery<Tree, Kernel>::signed_distances(std::span<const Point> xs) const {
    std::vector<double> out(xs.size());
    parallel_for(
        xs.size(), [&](std::size_t i) { out[i] = closest_point(xs[i]).distance; }, expensive_grain);
    return out;
}

}  // namespace slc
