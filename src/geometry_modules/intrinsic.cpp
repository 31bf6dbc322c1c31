// The intrinsic geometry module: Eqs. (7) and (8) of paper §3.1.
#include "slc/geometry_modules/intrinsic.hpp"

#include "slc/core/parallel.hpp"

namespace slc {

VertexGeometry intrinsic_geometry(const Interface& curves) {
    const std::size_t n = curves.size();
    // Unit tangent of each segment i (from vertex i to next(i)) and its length.
    std::vector<Vec2> tangent(n);
    const std::vector<double> length = segment_lengths(curves, "intrinsic geometry");
    for (std::size_t i = 0; i < n; ++i) {
        const Segment s = curves.segment(i);
        tangent[i] = (s.b - s.a) / length[i];
    }
    VertexGeometry g{std::vector<Vec2>(n), std::vector<double>(n)};
    // δx_i: the left-right average of the two segments' difference quotients, Eq. 7.
    std::vector<double> dx_norm(n);
    parallel_for(n, [&](std::size_t i) {
        const Vec2 dx = 0.5 * (tangent[i] + tangent[curves.prev(i)]);
        dx_norm[i] = norm(dx);
        g.normals[i] = dx_norm[i] > 0.0 ? -perp(dx) / dx_norm[i] : -perp(tangent[i]);
    });
    // C_i = −N_i^⊥ · δN_i / |δx_i|, Eq. 8 with our sign.
    parallel_for(n, [&](std::size_t i) {
        const std::size_t a = curves.prev(i), b = curves.next(i);
        const Vec2 dn = 0.5 * ((g.normals[b] - g.normals[i]) / length[i] +
                               (g.normals[i] - g.normals[a]) / length[a]);
        g.curvature[i] = -dot(perp(g.normals[i]), dn) / dx_norm[i];
    });
    return g;
}

}  // namespace slc
