// The start of a user's run is the user's shape (internal to evolve, written once for curves and
// surfaces): the contour that a step at rest makes of it must have its components and holes (a
// surface's handles), and no vertex of the given shape may lie farther from it than a finest
// cell. A part thinner than the cells that the contours lose is refused before the first step,
// named by its place, rather than a run that ends `ok` without it.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/space.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/distance/surface_distance_tree.hpp"
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
    ShapeTopology t{curves.curve_count(), 0};
    for (std::size_t c = 0; c < curves.curve_count(); ++c)
        if (signed_area(curves.curve(c)) < 0.0) ++t.holes;
    return t;
}
inline ShapeTopology shape_topology(const Surface& s) { return {component_count(s), genus(s)}; }

inline std::span<const Vec2> shape_vertices(const Interface& curves) { return curves.points(); }
inline std::span<const Vec3> shape_vertices(const Surface& s) { return s.vertices; }

inline std::string describe(const ShapeTopology& t, int dim) {
    return fmt::format(
        "{} {} with {} {}", t.components, t.components == 1 ? "component" : "components", t.holes,
        dim == 2 ? (t.holes == 1 ? "hole" : "holes") : (t.holes == 1 ? "handle" : "handles"));
}

/// Throws NumericalFailure when `read`, the contour a step at rest makes of `given` at depth K
/// with thin_depth levels of thin cells (finest cell `cell` at K), has other components or holes
/// than `given`, or leaves a vertex of `given` farther than `cell` from it; the message names the
/// vertex farthest from it and the settings that resolve finer parts.
template <int dim>
void check_start(const ShapeOf<dim>& given, const ShapeOf<dim>& read, const RegionOf<dim>& domain,
                 int depth, int thin_depth, double cell) {
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
    if (want == got && farthest <= cell) return;
    const char* what = dim == 2 ? "curves" : "surface";
    const std::string cells = thin_depth > 0
                                  ? fmt::format("cells {:.3g}, thin cells down to {:.3g}", cell,
                                                std::ldexp(cell, -thin_depth))
                                  : fmt::format("cells {:.3g}, no thin cells", cell);
    const std::string where = farthest > 0.01 * cell
                                  ? fmt::format(", and the part near {} lies {:.3g} from them",
                                                point_text6(points[far]), farthest)
                                  : std::string();
    throw NumericalFailure(fmt::format(
        "the contours at K = {} ({}) do not keep the {} as given: {} became {}{}; a part is "
        "thinner than they resolve: raise --thin-depth (now {}) or -K",
        depth, cells, what, describe(want, dim), describe(got, dim), where, thin_depth));
}

}  // namespace slc::detail
