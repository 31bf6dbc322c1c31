// The built-in implicit surfaces of `slc contour --function`.
#include "slc/contour/implicit_surfaces.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "slc/core/error.hpp"

namespace slc {

std::vector<std::string> implicit_surface_names() { return {"sphere", "torus", "cassini"}; }

ImplicitSurface implicit_surface(const std::string& name) {
    if (name == "sphere") {
        // Off the grid's planes, so that no tree point falls exactly on it.
        const Vec3 c{0.03, -0.02, 0.01};
        auto d = [c](Vec3 x) { return distance(x, c) - 0.6; };
        return {name, "sphere of radius 0.6 at (0.03, -0.02, 0.01)", d, d, true};
    }
    if (name == "torus") {
        auto d = [](Vec3 x) { return std::hypot(std::hypot(x.x, x.y) - 0.55, x.z) - 0.2; };
        return {name, "torus about the z axis, radii 0.55 and 0.2", d, d, true};
    }
    if (name == "cassini") {
        // |x − F1|² |x − F2|² = b⁴ with foci F = (±a, 0, 0): a peanut for b a little above a.
        constexpr double a = 0.5, b = 0.53;
        auto g = [](Vec3 x) {
            const double r = x.y * x.y + x.z * x.z;
            return ((x.x - a) * (x.x - a) + r) * ((x.x + a) * (x.x + a) + r) - b * b * b * b;
        };
        return {name,
                "Cassini surface |x - F1|^2 |x - F2|^2 = b^4, F = (+-0.5, 0, 0), b = 0.53",
                g,
                {},
                false};
    }
    throw InvalidInput(fmt::format("unknown function '{}'; known: {}", name,
                                   fmt::join(implicit_surface_names(), ", ")));
}

}  // namespace slc
