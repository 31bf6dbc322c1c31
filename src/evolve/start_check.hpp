// The start of a user's run is the user's shape (internal to evolve, written once for curves and
// surfaces): the contour that a step at rest makes of it must have its components and holes (a
// surface's handles), no vertex of the given shape may lie farther from it than a finest cell,
// and its area or volume must be the given shape's within what eps allows. Where a part is thinner
// than the cells resolve, the thin cells go deeper; a part that the deepest still loses is refused
// before the first step, named by its place, rather than a run that ends `ok` without it.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <limits>
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
#include "slc/evolve/keeping_topology.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/surface.hpp"
#include "step_common.hpp"

namespace slc::detail {

/// The area the curves enclose, or the volume the surface does.
inline double shape_measure(const Interface& curves) { return area(curves); }
inline double shape_measure(const Surface& s) { return volume(s); }

inline std::span<const Vec2> shape_vertices(const Interface& curves) { return curves.points(); }
inline std::span<const Vec3> shape_vertices(const Surface& s) { return s.vertices; }

/// What the start must keep of the given shape beyond its topology: no vertex of it farther
/// than `cell` (the finest cell at K) from the contour, and the area (curves) or volume
/// (surface) the contour encloses within `tolerance` of `measure`, the given shape's as a step
/// reads it (arcs or patches included).
struct StartTolerance {
    double cell = 0.0;
    double measure = 0.0;
    double tolerance = 0.0;
};

/// The measure's tolerance for a shape of length or area `size` contoured with `contour`: 2 ε L
/// when refinement runs until converged (a contour within ε of the shape everywhere moves the
/// measure by at most ε L); with a cap on the passes (P, or the two passes of the curvature laws)
/// ε is not the contour's promise, and only the topology and the vertices are checked.
template <class Options>
double start_measure_tolerance(const Options& contour, double size) {
    if (contour.refine_passes != Options::until_converged)
        return std::numeric_limits<double>::infinity();
    return 2.0 * contour.resolved_eps() * size;
}

/// How the contour a step at rest makes of the given shape is not that shape.
struct StartMismatch {
    std::string why;       ///< the counts, the vertex farthest from the contour, or the measures
    double measure = 0.0;  ///< the area or volume the contour encloses
    /// Only the area or volume differs: refinement, run until converged, left the contours
    /// farther than ε (its safeguards refuse splits at creases), not a part thinner than a cell.
    bool measure_only = false;
};

/// Why `read`, the contour a step at rest makes of `given`, is not `given`, or nothing: other
/// components or holes, a vertex of `given` farther than a cell from it, or another area or
/// volume.
template <int dim>
std::optional<StartMismatch> start_mismatch(const ShapeOf<dim>& given, const ShapeOf<dim>& read,
                                            const RegionOf<dim>& domain,
                                            const StartTolerance& keep) {
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
    const double measure = shape_measure(read);
    const bool shape_kept = want == got && farthest <= keep.cell;
    if (shape_kept && std::abs(measure - keep.measure) <= keep.tolerance) return std::nullopt;
    if (shape_kept) {
        return StartMismatch{
            fmt::format("the {} {:.6g} became {:.6g} ({:+.3g}%; eps allows {:.3g})",
                        dim == 2 ? "area" : "volume", keep.measure, measure,
                        100.0 * (measure / keep.measure - 1.0), keep.tolerance),
            measure, true};
    }
    const std::string where = farthest > 0.01 * keep.cell
                                  ? fmt::format(", and the part near {} lies {:.3g} from them",
                                                point_text6(points[far]), farthest)
                                  : std::string();
    return StartMismatch{
        fmt::format("{} became {}{}", describe(want, dim), describe(got, dim), where), measure,
        false};
}

/// The start of a user's run: the contour at rest of `given` (read(thin), at depth K with thin
/// levels of thin cells) that keeps it (start_mismatch), at the options' thin depth or another in
/// thin_depth_search's order, going no deeper once a depth's contour misses the shape's measure
/// by what the depth before missed it (the thin cells change nothing: the part is thinner than
/// any). Returns the depth and the contour; throws NumericalFailure naming the part and the
/// settings when none keeps it.
template <int dim, class Read>
std::pair<int, ShapeOf<dim>> start_as_given(const ShapeOf<dim>& given, const RegionOf<dim>& domain,
                                            int depth, int thin_depth, const StartTolerance& keep,
                                            Read read) {
    std::optional<ShapeOf<dim>> kept;
    std::optional<StartMismatch> mismatch;  // at the deepest depth tried, from thin_depth down
    int thin = thin_depth;
    bool same = false;  // that depth's contour missed the measure by what the one before did
    const auto attempt = [&](int at) {
        ShapeOf<dim> contour = read(at);
        std::optional<StartMismatch> missed = start_mismatch<dim>(given, contour, domain, keep);
        if (!missed) {
            kept = std::move(contour);
            return ThinDepthTry::keeps;
        }
        if (at < thin_depth) return ThinDepthTry::differs;
        same = mismatch && mismatch->measure == missed->measure;
        thin = at;
        mismatch = std::move(missed);
        return same ? ThinDepthTry::stop_deeper : ThinDepthTry::differs;
    };
    if (const std::optional<int> found = thin_depth_search(thin_depth, attempt))
        return {*found, std::move(*kept)};
    const std::string cells = thin > 0 ? fmt::format("cells {:.3g}, thin cells down to {:.3g}",
                                                     keep.cell, std::ldexp(keep.cell, -thin))
                                       : fmt::format("cells {:.3g}, no thin cells", keep.cell);
    std::string advice;
    if (mismatch->measure_only) {
        advice = "refinement did not bring the contours within eps of it: raise -K";
    } else if (same) {
        // Deeper thin cells changed nothing: the part is thinner than any of them, as a part
        // that tapers to an edge or a point of no thickness is at every depth.
        advice = fmt::format(
            "a part is thinner than they resolve at any depth (thin cells {} levels deep split "
            "no more than {} did), as where it tapers to an edge or a point of no thickness: "
            "give it a thickness of at least {:.3g} there (the finest thin cell) or raise -K",
            thin, thin - 2, std::ldexp(keep.cell, -thin));
    } else {
        advice = "a part is thinner than they resolve: " +
                 (thin < setting_range::thin_depth.hi
                      ? fmt::format("raise --thin-depth (now {}) or -K", thin)
                      : fmt::format("raise -K (--thin-depth is at its most, {})", thin));
    }
    throw NumericalFailure(
        fmt::format("the contours at K = {} ({}) do not keep the {} as given: {}; {}", depth, cells,
                    dim == 2 ? "curves" : "surface", mismatch->why, advice));
}

}  // namespace slc::detail
