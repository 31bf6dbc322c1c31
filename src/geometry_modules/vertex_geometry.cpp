// Arc-length weights of the vertices and arc-length means over Γ (for the nonlocal law, paper
// Eq. 13, and for integrals of the curvature).
#include "slc/geometry_modules/vertex_geometry.hpp"

#include <fmt/format.h>

#include "slc/core/error.hpp"
#include "weighted_mean.hpp"

namespace slc {

std::vector<double> segment_lengths(const Interface& curves, std::string_view module) {
    std::vector<double> length(curves.size());
    for (std::size_t i = 0; i < curves.size(); ++i) {
        const Segment s = curves.segment(i);
        length[i] = distance(s.a, s.b);
        if (!(length[i] > 0.0)) {
            throw InvalidInput(fmt::format("{}: vertex {} ({}, {}) coincides with the next vertex",
                                           module, i, s.a.x, s.a.y));
        }
    }
    return length;
}

std::vector<double> vertex_arc_lengths(const Interface& curves) {
    std::vector<double> w(curves.size());
    for (std::size_t i = 0; i < curves.size(); ++i) {
        w[i] = 0.5 * (distance(curves.point(curves.prev(i)), curves.point(i)) +
                      distance(curves.point(i), curves.point(curves.next(i))));
    }
    return w;
}

double arc_length_mean(const Interface& curves, std::span<const double> g) {
    SLC_ASSERT(g.size() == curves.size() && !curves.empty(), "one value per vertex");
    return weighted_mean(g, vertex_arc_lengths(curves));
}

}  // namespace slc
