// The laws moved by a potential solved on the curves: two-phase Mullins–Sekerka and one-phase
// Hele-Shaw.
#include "slc/velocity/potential_laws.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "slc/core/error.hpp"
#include "slc/potential/boundary_integral.hpp"

namespace slc {
namespace {

/// Multiplies mode ξ of the samples of curve c by 1/(1 + (kλ)²), kλ = k_rate ξ³: the filter of the
/// stiff modes (docs/algorithms/potential.md).
void filter_stiff_modes(const SmoothCurves& s, std::size_t c, std::span<double> v, double k_rate) {
    filter_modes(s, c, v, [&](double xi) {
        const double g = k_rate * xi * xi * xi;
        return 1.0 / (1.0 + g * g);
    });
}

/// The speeds v at the samples, their stiff modes filtered for a step of kλ = k_rate ξ³ (none
/// when k_rate = 0), at the vertices.
std::vector<double> vertex_speeds(const SmoothCurves& s, std::vector<double> v, double k_rate) {
    std::vector<double> speeds;
    speeds.reserve(s.vertex_offsets.back());
    for (std::size_t c = 0; c < s.curve_count(); ++c) {
        const std::span<double> vc(v.data() + s.offsets[c], s.count(c));
        if (k_rate > 0.0) filter_stiff_modes(s, c, vc, k_rate);
        const std::vector<double> at = interpolate_at_vertices(s, c, vc);
        speeds.insert(speeds.end(), at.begin(), at.end());
    }
    return speeds;
}

/// u = V N at the vertices, N the smooth curves' normal.
std::vector<Vec2> normal_velocities(const SmoothCurves& s, const std::vector<double>& v) {
    std::vector<Vec2> u(v.size());
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = v[i] * s.vertex_normal[i];
    return u;
}

}  // namespace

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

std::vector<double> MullinsSekerka::flux_jump(const SmoothCurves& s,
                                              const std::vector<double>& mu) const {
    // V = D_out ∂u_out/∂N − D_in ∂u_in/∂N = (D_out − D_in) K'μ − (D_out + D_in) μ/2.
    std::vector<double> v(mu.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = -0.5 * (d_out_ + d_in_) * mu[i];
    if (d_out_ != d_in_) {
        const std::vector<double> kmu = adjoint_double_layer(s, mu, {}, summation_);
        for (std::size_t i = 0; i < v.size(); ++i) v[i] += (d_out_ - d_in_) * kmu[i];
    }
    return v;
}

std::vector<double> MullinsSekerka::normal_speeds(const SmoothCurves& s, double k) const {
    std::vector<double> f(s.x.size());
    for (std::size_t i = 0; i < f.size(); ++i) f[i] = -sigma_ * s.curvature[i];
    const SingleLayerSystem system(s, {}, summation_);
    const std::vector<double> f_all[] = {std::move(f)};
    std::vector<double> v = flux_jump(s, system.solve(f_all).front().density);
    if (k > 0.0) limit_vanishing(s, system, k, v);
    return vertex_speeds(s, std::move(v), k * sigma_ * (d_in_ + d_out_));
}

void MullinsSekerka::limit_vanishing(const SmoothCurves& s, const SingleLayerSystem& system,
                                     double k, std::vector<double>& v) const {
    // A curve whose rate of area dA_c/dt = ∫_c V ds would, held for the step, move a circle of its
    // area inward by more than its radius (−k dA_c/dt > 2A_c) vanishes within the step; held for
    // the whole step, its rate would hand the others far more than it has, and its own shape, a
    // speck of a few cells, is no longer resolved. The others receive what it has, A_c over the
    // step: its boundary value is shifted by a constant β_c (the potential is linear in its
    // boundary values: V + Σ β_c W_c, W_c the response to 1 on curve c) until its rate is
    // −A_c/k. Its own curve is then moved inward at one speed, by three times the radius of a
    // circle of its area: the corrector averages that with the predicted curves' velocity, where
    // the particle is gone, so the step ends with it vanished, not a speck that lingers.
    const std::vector<double>& area = s.area;
    const std::vector<double> rate = curve_integrals(s, v);
    std::vector<std::size_t> vanishing;
    for (std::size_t c = 0; c < s.curve_count(); ++c)
        if (-k * rate[c] * (area[c] > 0 ? 1.0 : -1.0) > 2.0 * std::abs(area[c]))
            vanishing.push_back(c);
    if (vanishing.empty()) return;
    std::vector<std::vector<double>> unit(vanishing.size(), std::vector<double>(s.x.size(), 0.0));
    for (std::size_t i = 0; i < vanishing.size(); ++i)
        for (std::size_t j = s.offsets[vanishing[i]]; j < s.offsets[vanishing[i] + 1]; ++j)
            unit[i][j] = 1.0;
    std::vector<std::vector<double>> w, w_rates;  // W_c, and ∫ W_c ds over each curve
    for (const SingleLayerSolution& u : system.solve(unit)) {
        w.push_back(flux_jump(s, u.density));
        w_rates.push_back(curve_integrals(s, w.back()));
    }
    // Σ_c β_c ∫_{c'} W_c ds = −A_{c'}/k − ∫_{c'} V ds for each vanishing c'.
    auto given = [&](std::size_t c) { return -area[c] / k; };
    const std::size_t n = vanishing.size();
    std::vector<double> a(n * n), b(n);
    for (std::size_t i = 0; i < n; ++i) {
        b[i] = given(vanishing[i]) - rate[vanishing[i]];
        for (std::size_t j = 0; j < n; ++j) a[i * n + j] = w_rates[j][vanishing[i]];
    }
    const std::optional<std::vector<double>> solved = solve_dense(a, b);
    if (!solved)
        throw NumericalFailure(
            "velocity 'mullins-sekerka': vanishing particles' fluxes are not independent; "
            "raise the steps N");
    const std::vector<double>& beta = *solved;
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < v.size(); ++i) v[i] += beta[j] * w[j][i];
    // Its own speed moves it inward by 3R, R = √(|A|/π) (not by its rate over its length: the
    // spline through a speck of a few cells can loop, its length several times the speck's).
    for (std::size_t c : vanishing)
        std::fill(
            v.begin() + static_cast<std::ptrdiff_t>(s.offsets[c]),
            v.begin() + static_cast<std::ptrdiff_t>(s.offsets[c + 1]),
            -std::copysign(3.0 * std::sqrt(std::abs(area[c]) / std::numbers::pi), area[c]) / k);
}

std::vector<Vec2> MullinsSekerka::velocities(double, const Interface& curves,
                                             const VertexGeometry& geometry) const {
    if (curves.empty()) return {};
    const SmoothCurves s = smooth_curves(curves);
    return normal_velocities(s, normal_speeds(s, geometry.step));
}

HeleShaw::HeleShaw(double sigma, double q, Vec2 source) : sigma_(sigma), q_(q), source_(source) {
    if (!(sigma > 0.0) || !std::isfinite(sigma))
        throw InvalidInput(
            fmt::format("velocity 'hele-shaw': sigma must be positive, got {}", sigma));
    if (!std::isfinite(q) || !std::isfinite(source.x) || !std::isfinite(source.y))
        throw InvalidInput("velocity 'hele-shaw': q, sx and sy must be finite");
}

Invariants HeleShaw::invariants() const {
    if (q_ == 0.0) return {.keeps_area = true, .shortens = true, .keeps_region_areas = true};
    return {.area_rate = q_, .keeps_region_areas = true, .area_source = source_};
}

std::vector<double> HeleShaw::normal_speeds(const Interface& curves, double k) const {
    if (curves.empty()) return {};
    return normal_speeds(curves, smooth_curves(curves), k);
}

std::vector<double> HeleShaw::normal_speeds(const Interface& curves, const SmoothCurves& s,
                                            double k) const {
    const std::vector<std::size_t> region = curve_regions(curves);
    // The source's potential G_s = −(Q/2π) log|x − source| in the region holding it: p = p_h + G_s
    // with p_h harmonic, p_h = −σC − G_s on that region's curves.
    std::optional<std::size_t> fed;
    if (q_ != 0.0) {
        fed = region_containing(curves, region, source_);
        if (!fed)
            throw InvalidInput(fmt::format(
                "velocity 'hele-shaw': the source ({}, {}) lies inside no region of the curves",
                source_.x, source_.y));
    }
    std::vector<double> f(s.x.size()), source_flux(s.x.size(), 0.0);
    for (std::size_t c = 0; c < s.curve_count(); ++c) {
        for (std::size_t i = s.offsets[c]; i < s.offsets[c + 1]; ++i) {
            f[i] = -sigma_ * s.curvature[i];
            if (fed && region[c] == *fed) {
                const Vec2 d = s.x[i] - source_;
                f[i] += q_ / (2.0 * std::numbers::pi) * std::log(norm(d));
                // −∂G_s/∂N = (Q/2π) (x − source)·N / |x − source|².
                source_flux[i] = q_ / (2.0 * std::numbers::pi) * dot(d, s.normal[i]) / norm2(d);
            }
        }
    }
    const std::vector<double> f_all[] = {std::move(f)};
    const std::vector<double> mu =
        SingleLayerSystem(s, region, summation_).solve(f_all).front().density;
    // V = −∂p/∂N = −(K'μ + μ/2) − ∂G_s/∂N.
    const std::vector<double> kmu = adjoint_double_layer(s, mu, region, summation_);
    std::vector<double> v(mu.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = -(kmu[i] + 0.5 * mu[i]) + source_flux[i];
    return vertex_speeds(s, std::move(v), k * sigma_);
}

std::vector<Vec2> HeleShaw::velocities(double, const Interface& curves,
                                       const VertexGeometry& geometry) const {
    if (curves.empty()) return {};
    const SmoothCurves s = smooth_curves(curves);
    return normal_velocities(s, normal_speeds(curves, s, geometry.step));
}

}  // namespace slc
