/// @file
/// Nearest-point extension of values given at the vertices of a surface (velocities, usually)
/// to all of space (paper §1.3 with d = 3): W(x) = u(y*(x)), the vertex values of the nearest
/// triangle interpolated barycentrically at the nearest point y*. Every extended value is a
/// convex combination of vertex values (maximum principle). The 3D counterpart of extension.hpp.
#pragma once

#include <span>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/surface_distance_tree.hpp"

namespace slc {

/// The nearest-point extension at a point whose nearest point is p (signed or not): the values
/// at the corners of p's triangle weighted by p's barycentric weights. T is double, Vec3 or any
/// type with + and scaling by double. O(1).
template <class T>
T nearest_point_extension(const Surface& surface, std::span<const T> values,
                          const SurfacePoint& p) {
    const TriangleIndices& t = surface.triangles[p.triangle];
    return p.weights[0] * values[t[0]] + p.weights[1] * values[t[1]] + p.weights[2] * values[t[2]];
}

/// The nearest-point extension at arbitrary points: one nearest-point query each, in parallel.
/// values: one per surface vertex, else InvalidInput.
template <class T>
std::vector<T> nearest_point_extension(const SurfaceDistanceTree& tree, std::span<const T> values,
                                       std::span<const Vec3> xs) {
    if (values.size() != tree.surface().vertices.size()) {
        throw InvalidInput("nearest-point extension: need one value per surface vertex");
    }
    std::vector<T> out(xs.size());
    parallel_for(
        xs.size(),
        [&](std::size_t i) {
            out[i] = nearest_point_extension(tree.surface(), values, tree.nearest_point(xs[i]));
        },
        expensive_grain);
    return out;
}

}  // namespace slc
