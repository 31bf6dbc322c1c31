/// @file
/// Space<dim>: what differs between curves in the plane (dim = 2) and surfaces in space (dim = 3),
/// DESIGN §8, so that code written once as `template <int dim>` (the 2^d tree of paper §1.3 and
/// §2.1, the velocity laws of §3, the step of §4) names its types and constants through it, as
/// deal.II's GeometryInfo<dim> does. The point and box types are core's; the interface and its
/// vertex geometry are only declared here and defined in geometry and geometry_modules, so core
/// depends on nothing.
#pragma once

#include "slc/core/box.hpp"
#include "slc/core/box3.hpp"
#include "slc/core/vec2.hpp"
#include "slc/core/vec3.hpp"

namespace slc {

class Interface;
struct Surface;
struct VertexGeometry;
struct SurfaceGeometry;

/// The types and constants of dimension dim (2 or 3): the point, the domain (a square or a cube),
/// the interface (curves or a surface), the geometry at the interface's vertices, and the deepest
/// level a tree over the domain supports.
template <int dim>
struct Space;

/// Curves in the plane.
template <>
struct Space<2> {
    using Point = Vec2;               ///< a point
    using Region = Box;               ///< the domain, a tree cell
    using Shape = Interface;          ///< the interface (complete in slc/geometry/interface.hpp)
    using Geometry = VertexGeometry;  ///< normals and curvature at the vertices
    /// Deepest tree level: the triangulation's vertex keys hold two coordinates of level + 1 bits
    /// in 32 bits each.
    static constexpr int max_tree_depth = 30;
};

/// Surfaces in space.
template <>
struct Space<3> {
    using Point = Vec3;                ///< a point
    using Region = Box3;               ///< the domain, a tree cell
    using Shape = Surface;             ///< the interface (complete in slc/geometry/surface.hpp)
    using Geometry = SurfaceGeometry;  ///< normals and mean curvature at the vertices
    /// Deepest tree level: three 21-bit coordinates fit a 64-bit key.
    static constexpr int max_tree_depth = 21;
};

/// The names of Space<dim> as templates of dim, so that templates over dim read
/// `PointOf<dim>` where they would write `typename Space<dim>::Point`.
template <int dim>
using PointOf = typename Space<dim>::Point;
template <int dim>
using RegionOf = typename Space<dim>::Region;  ///< (see PointOf)
template <int dim>
using ShapeOf = typename Space<dim>::Shape;  ///< (see PointOf)
template <int dim>
using GeometryOf = typename Space<dim>::Geometry;  ///< (see PointOf)

}  // namespace slc
