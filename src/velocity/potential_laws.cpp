// The laws moved by a potential solved on the curves: two-phase Mullins–Sekerka.
#include "slc/velocity/potential_laws.hpp"

#include <fmt/format.h>

#include <cmath>

#include "slc/core/error.hpp"
#include "slc/potential/boundary_integral.hpp"

namespace slc {

MullinsSekerka::MullinsSekerka(double sigma, double d_in, double d_out)
    : sigma_(sigma), d_in_(d_in), d_out_(d_out) {
    for (const auto& [what, value] : {std::pair{"sigma", sigma}, {"din", d_in}, {"dout", d_out}}) {
        if (!(value > 0.0) || !std::isfinite(value))
            throw InvalidInput(fmt::format(
                "velocity 'mullins-sekerka': {} must be positive, got {}", what, value));
    }
}

std::vector<double> MullinsSekerka::normal_speeds(const Interface& curves, double k) const {
    if (curves.empty()) return {};
    return normal_speeds(smooth_curves(curves), k);
}

std::vector<double> MullinsSekerka::normal_speeds(const SmoothCurves& s, double k) const {
    std::vector<double> f(s.x.size());
    for (std::size_t i = 0; i < f.size(); ++i) f[i] = -sigma_ * s.curvature[i];
    const std::vector<double> mu = solve_single_layer(s, f).density;
    // V = D_out ∂u_out/∂N − D_in ∂u_in/∂N = (D_out − D_in) K'μ − (D_out + D_in) μ/2.
    std::vector<double> v(mu.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = -0.5 * (d_out_ + d_in_) * mu[i];
    if (d_out_ != d_in_) {
        const std::vector<double> kmu = adjoint_double_layer(s, mu);
        for (std::size_t i = 0; i < v.size(); ++i) v[i] += (d_out_ - d_in_) * kmu[i];
    }
    const double rate = sigma_ * (d_in_ + d_out_);
    std::vector<double> speeds;
    speeds.reserve(s.vertex_offsets.back());
    for (std::size_t c = 0; c < s.curve_count(); ++c) {
        const std::span<double> vc(v.data() + s.offsets[c], s.count(c));
        if (k > 0.0)
            filter_modes(s, c, vc,
                         [&](double xi) { return 1.0 / (1.0 + k * rate * xi * xi * xi); });
        const std::vector<double> at = interpolate_at_vertices(s, c, vc);
        speeds.insert(speeds.end(), at.begin(), at.end());
    }
    return speeds;
}

std::vector<Vec2> MullinsSekerka::velocities(double, const Interface& curves,
                                             const VertexGeometry& geometry) const {
    if (curves.empty()) return {};
    const SmoothCurves s = smooth_curves(curves);
    const std::vector<double> v = normal_speeds(s, geometry.step);
    std::vector<Vec2> u(v.size());
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = v[i] * s.vertex_normal[i];
    return u;
}

}  // namespace slc
