// Parts a step splits off (internal to evolve, written once for curves and surfaces): a
// component of the new interface beyond those of the old is measured by its thickness,
// d·(area or volume)/(length or area), a disc's or a ball's radius. One thinner than the finest
// cell may be a part the contours tore rather than one the law split off: the time loop
// (time_loop.hpp) then takes the step again with deeper thin cells.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <optional>
#include <vector>

#include "slc/core/space.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/surface.hpp"

namespace slc::detail {

/// A part of an interface: its thickness and the mean of its vertices.
template <int dim>
struct InterfacePart {
    double thickness = 0.0;
    PointOf<dim> where{};
};

/// Every component's thickness and place: each curve (a hole's area counted as positive), or
/// each connected set of a surface's triangles.
inline std::vector<InterfacePart<2>> interface_parts(const Interface& curves) {
    std::vector<InterfacePart<2>> parts(curves.curve_count());
    for (std::size_t c = 0; c < parts.size(); ++c) {
        const auto points = curves.curve(c);
        const double l = length(points);
        parts[c].thickness = l > 0.0 ? 2.0 * std::abs(signed_area(points)) / l : 0.0;
        Vec2 sum{0.0, 0.0};
        for (const Vec2& p : points) sum = sum + p;
        parts[c].where = (1.0 / static_cast<double>(points.size())) * sum;
    }
    return parts;
}

inline std::vector<InterfacePart<3>> interface_parts(const Surface& s) {
    const std::vector<std::uint32_t> label = component_labels(s);
    const std::size_t count =
        label.empty() ? 0 : *std::max_element(label.begin(), label.end()) + std::size_t{1};
    // Each component's volume (the divergence theorem, from its own first vertex), area, and
    // the sum of its triangles' corners.
    std::vector<double> v(count, 0.0), a(count, 0.0), corners(count, 0.0);
    std::vector<Vec3> origin(count), sum(count, Vec3{0.0, 0.0, 0.0});
    std::vector<std::uint8_t> seen(count, 0);
    for (std::size_t t = 0; t < s.size(); ++t) {
        const std::uint32_t c = label[t];
        const Triangle3 tri = s.triangle(t);
        if (!seen[c]) origin[c] = tri.a, seen[c] = 1;
        const Vec3 p = tri.a - origin[c], q = tri.b - origin[c], r = tri.c - origin[c];
        v[c] += dot(p, cross(q, r)) / 6.0;
        a[c] += area(tri);
        sum[c] = sum[c] + tri.a + tri.b + tri.c;
        corners[c] += 3.0;
    }
    std::vector<InterfacePart<3>> parts(count);
    for (std::size_t c = 0; c < count; ++c) {
        parts[c].thickness = a[c] > 0.0 ? 3.0 * std::abs(v[c]) / a[c] : 0.0;
        parts[c].where = (1.0 / corners[c]) * sum[c];
    }
    return parts;
}

/// When `after` has n > 0 more components than `before`: the n-th thinnest of its components,
/// taken for the thickest of the new ones (a split makes parts of a whole, and a part split off
/// is thinner than what it left), else nothing.
template <int dim>
std::optional<InterfacePart<dim>> thinnest_new_part(const ShapeOf<dim>& before,
                                                    const ShapeOf<dim>& after) {
    std::size_t old_count = 0;
    if constexpr (dim == 2) {
        old_count = before.curve_count();
        if (after.curve_count() <= old_count) return std::nullopt;
    } else {
        old_count = before.empty() ? 0 : component_count(before);
    }
    std::vector<InterfacePart<dim>> parts = interface_parts(after);
    if (parts.size() <= old_count) return std::nullopt;
    const std::size_t n = parts.size() - old_count;
    std::nth_element(parts.begin(), parts.begin() + static_cast<std::ptrdiff_t>(n - 1), parts.end(),
                     [](const auto& p, const auto& q) { return p.thickness < q.thickness; });
    return parts[n - 1];
}

}  // namespace slc::detail
