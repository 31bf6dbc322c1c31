// A program that uses slc as a library user would: contours the signed distance of a circle
// and checks it against the exact answer. Built by scripts/test against an install
// (find_package) and from the source tree (add_subdirectory).
#include <cmath>
#include <cstdio>
#include <slc/slc.hpp>

int main() {
    const slc::Interface circle({slc::shapes::circle({0.1, -0.2}, 0.7, 256)});
    const slc::Box domain = slc::Box::centered_square(1.0);
    const slc::DistanceTree tree(circle, domain, {.depth = 7, .triangulate = false});
    auto distance = [&](std::span<const slc::Vec2> xs, std::span<double> out) {
        for (std::size_t i = 0; i < xs.size(); ++i) out[i] = tree.closest_point(xs[i]).distance;
    };
    const slc::ContourResult c = slc::contour(distance, domain, {.depth = 5});
    const double r = std::sqrt(slc::area(c.curves) / 3.141592653589793);
    std::printf("contour: %zu segments, equivalent radius %.6f (exact 0.7)\n", c.curves.size(), r);
    return c.curves.curve_count() == 1 && std::abs(r - 0.7) < 1e-2 ? 0 : 1;
}
