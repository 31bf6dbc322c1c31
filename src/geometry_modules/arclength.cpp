// The arclength geometry module: circumcircle curvature (a corner's turn over its half
// segments) averaged along the curve.
#include "slc/geometry_modules/arclength.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

/// The cubic B-spline (four unit boxes convolved) at r: support |r| < 2, variance 1/3, and a
/// nonnegative Fourier transform, sinc⁴.
double cubic_bspline(double r) {
    r = std::abs(r);
    if (r >= 2.0) return 0.0;
    if (r >= 1.0) {
        const double d = 2.0 - r;
        return d * d * d / 6.0;
    }
    return 2.0 / 3.0 - r * r + 0.5 * r * r * r;
}

/// G_σ f: f averaged along each curve with the weights B(s/w) ds, B the cubic B-spline and
/// w = √3 σ, so that the weights' standard deviation in arc length is σ (see the header).
/// length[i] is the length of segment i, from vertex i to next(i); ds[j] the arc length of
/// vertex j (vertex_arc_lengths).
std::vector<double> average_along(const Interface& curves, const std::vector<double>& length,
                                  const std::vector<double>& ds, const std::vector<double>& f,
                                  double width) {
    const std::size_t total = f.size();
    std::vector<double> out(total);
    const double scale = 1.0 / (std::sqrt(3.0) * width);
    parallel_for(total, [&](std::size_t i) {
        const std::size_t c = curves.curve_of(i);
        const std::size_t first = curves.offsets()[c], n = curves.offsets()[c + 1] - first;
        double weights = cubic_bspline(0.0) * ds[i];
        double sum = weights * f[i];
        // Forward over at most ⌊n/2⌋ vertices, backward over at most ⌊(n−1)/2⌋: every other
        // vertex of the curve at most once. r = s/w, s the arc length from vertex i.
        double r = 0.0;
        for (std::size_t j = i, step = 1; step <= n / 2; ++step) {
            r += scale * length[j];
            j = j + 1 == first + n ? first : j + 1;
            if (r >= 2.0) break;
            const double w = cubic_bspline(r) * ds[j];
            weights += w;
            sum += w * f[j];
        }
        r = 0.0;
        for (std::size_t j = i, step = 1; step <= (n - 1) / 2; ++step) {
            j = j == first ? first + n - 1 : j - 1;
            r += scale * length[j];
            if (r >= 2.0) break;
            const double w = cubic_bspline(r) * ds[j];
            weights += w;
            sum += w * f[j];
        }
        out[i] = sum / weights;
    });
    return out;
}

}  // namespace

std::vector<double> average_along_curves(const Interface& curves, const std::vector<double>& f,
                                         double width) {
    const std::vector<double> length = segment_lengths(curves, "average along curves");
    return average_along(curves, length, vertex_arc_lengths(curves), f, width);
}

VertexGeometry arclength_geometry(const Interface& curves, double width) {
    if (!(width >= 0.0) || !std::isfinite(width)) {
        throw InvalidInput(fmt::format(
            "arclength geometry: the averaging width must be finite and >= 0, got {}", width));
    }
    const std::size_t n = curves.size();
    const std::vector<double> length = segment_lengths(curves, "arclength geometry");
    VertexGeometry g{std::vector<Vec2>(n), std::vector<double>(n)};
    parallel_for(n, [&](std::size_t i) {
        const std::size_t a = curves.prev(i);
        const Vec2 u = curves.point(i) - curves.point(a);
        const Vec2 v = curves.point(curves.next(i)) - curves.point(i);
        const Vec2 tangent_in = u / length[a];
        const Vec2 tangent_out = v / length[i];
        const Vec2 sum = tangent_in + tangent_out;
        const double sum_norm = norm(sum);
        g.normals[i] = sum_norm > 0.0 ? -perp(sum) / sum_norm : -perp(tangent_out);
        g.curvature[i] = vertex_curvature(u, v);
    });
    if (width > 0.0) {
        const std::vector<double> ds = vertex_arc_lengths(curves);
        const std::vector<double> once = average_along(curves, length, ds, g.curvature, width);
        const std::vector<double> twice = average_along(curves, length, ds, once, width);
        for (std::size_t i = 0; i < n; ++i) g.curvature[i] = 2.0 * once[i] - twice[i];
    }
    return g;
}

}  // namespace slc
