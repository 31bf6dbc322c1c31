// The start of a user's run is the user's shape (internal to evolve, written once for curves and
// surfaces): the contour that a step at rest makes of it must have its components and holes (a
// surface's handles), and no vertex of the given shape may lie farther from it than a finest
// cell. Where a part is thinner than the cells resolve, the thin cells go deeper; a part that the
// deepest still loses is refused before the first step, named by its place, rather than a run
// that ends `ok` without it.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/space.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/evolve/guards.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/surface.hpp"
#include "step_common.hpp"

namespace slc::detail {

/// Components, and holes (curves: the clockwise ones) or handles (a surface's genus).
struct ShapeTopology {
    std::size_t components = 0;
    long long holes = 0;
    bool operator==(const ShapeTopology&) const = default;
};

inline ShapeTopology shape_topology(const Interface& curves) {
    return {curves.curve_count(), static_cast<long long>(region_parts(curves).holes)};
}
inline ShapeTopology shape_topology(const Surface& s) { return {component_count(s), genus(s)}; }

inline std::span<const Vec2> shape_vertices(const Interface& curves) { return curves.points(); }
inline std::span<const Vec3> shape_vertices(const Surface& s) { return s.vertices; }

inline std::string describe(const ShapeTopology& t, int dim) {
    return fmt::format(
        "{} {} with {} {}", t.components, t.components == 1 ? "component" : "components", t.holes,
        dim == 2 ? (t.holes == 1 ? "hole" : "holes") : (t.holes == 1 ? "handle" : "handles"));
}

/// Why `read`, the contour a step at rest makes of `given`, is not `given`, or nothing: other
/// components or holes, or a vertex of `given` farther than `cell` (the finest cell at K) from
/// it; the reason names the counts and the vertex farthest from it.
template <int dim>
std::optional<std::string> start_mismatch(const ShapeOf<dim>& given, const ShapeOf<dim>& read,
                                          const RegionOf<dim>& domain, double cell) {
    const ShapeTopology want = shape_topology(given), got = shape_topology(read);
    const auto points = shape_vertices(given);
    std::size_t far = 0;
    double farthest = 0.0;
    if (!read.empty()) {
        using Tree = std::conditional_t<dim == 2, DistanceTree, SurfaceDistanceTree>;
        typename Tree::Options o;
        o.depth = Tree::default_depth(read, domain);
        if constexpr (dim == 2) o.triangulate = false;
        const Tree tree(read, domain, o);
        const std::vector<double> d = tree.signed_distances(points);
        for (std::size_t i = 0; i < d.size(); ++i) {
            if (std::abs(d[i]) > farthest) {
                farthest = std::abs(d[i]);
                far = i;
            }
        }
    }
    if (want == got && farthest <= cell) return std::nullopt;
    const std::string where = farthest > 0.01 * cell
                                  ? fmt::format(", and the part near {} lies {:.3g} from them",
                                                point_text6(points[far]), farthest)
                                  : std::string();
    return fmt::format("{} became {}{}", describe(want, dim), describe(got, dim), where);
}

/// The start of a user's run: the contour at rest of `given` (read(thin), at depth K with thin
/// levels of thin cells) that keeps it (start_mismatch), at the options' thin depth or, where a
/// part is thinner than that resolves, two levels deeper at a time up to setting_range's most.
/// Returns the depth and the contour; throws NumericalFailure naming the part and the settings
/// when the deepest does not keep it either.
template <int dim, class Read>
std::pair<int, ShapeOf<dim>> start_as_given(const ShapeOf<dim>& given, const RegionOf<dim>& domain,
                                            int depth, int thin_depth, double cell, Read read) {
    int thin = thin_depth;
    for (;;) {
        ShapeOf<dim> contour = read(thin);
        const std::optional<std::string> why = start_mismatch<dim>(given, contour, domain, cell);
        if (!why) return {thin, std::move(contour)};
        if (thin < setting_range::thin_depth.hi && thin_depth > 0) {
            thin = std::min(thin + 2, setting_range::thin_depth.hi);
            continue;
        }
        const std::string cells = thin > 0 ? fmt::format("cells {:.3g}, thin cells down to {:.3g}",
                                                         cell, std::ldexp(cell, -thin))
                                           : fmt::format("cells {:.3g}, no thin cells", cell);
        const std::string raise =
            thin < setting_range::thin_depth.hi
                ? fmt::format("raise --thin-depth (now {}) or -K", thin)
                : fmt::format("raise -K (--thin-depth is at its most, {})", thin);
        throw NumericalFailure(fmt::format(
            "the contours at K = {} ({}) do not keep the {} as given: {}; a part is thinner than "
            "they resolve: {}",
            depth, cells, dim == 2 ? "curves" : "surface", *why, raise));
    }
}

}  // namespace slc::detail
