/// @file
/// Built-in implicit surfaces for contouring in space (`slc contour --function NAME`): a sphere,
/// a torus (non-convex, genus one) and a Cassini-type peanut (a function that is not a distance,
/// with a narrow waist), each in [−1, 1]³, negative inside.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "slc/core/vec3.hpp"

namespace slc {

/// A function G of space whose zero set is a closed surface, negative inside.
struct ImplicitSurface {
    std::string name;               ///< as given to implicit_surface()
    std::string description;        ///< one line, with its parameters
    std::function<double(Vec3)> g;  ///< G
    /// The exact signed distance to the zero set, where known (empty otherwise): the error of a
    /// contour is measured with it.
    std::function<double(Vec3)> distance;
    /// G is that distance itself (1-Lipschitz): its contour may settle far points
    /// (SurfaceContourOptions::distance_slack 0).
    bool g_is_distance = false;
};

/// The names implicit_surface() knows, in order.
std::vector<std::string> implicit_surface_names();

/// The built-in surface of that name; InvalidInput naming the known ones otherwise.
ImplicitSurface implicit_surface(const std::string& name);

}  // namespace slc
