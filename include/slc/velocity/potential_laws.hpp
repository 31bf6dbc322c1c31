/// @file
/// Laws that move curves by a potential solved on them (paper §4.7's motivation: crystal growth
/// is nonlocal, "the normal velocity at each point depends on all of Γ(t)"): the potential is
/// harmonic off the curves with the curvature as its boundary values, and the curves move by its
/// normal derivatives (slc/potential/boundary_integral.hpp; docs/algorithms/potential.md).
///
/// These laws are stiff: mode m of a circle of radius R decays at a rate ∝ σm³/R³. Within a
/// step of size k (VertexGeometry::step) mode ξ of V (in arc length) is multiplied by
/// 1/(1 + (kλ(ξ))²), λ(ξ) the law's decay rate of a flat interface: explicit, the step would
/// amplify modes with kλ > 2; so filtered, it holds them (stiffness() sets a user's steps).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "slc/potential/boundary_integral.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc {

/// `mullins-sekerka`: two-phase Mullins–Sekerka (coarsening by diffusion, Ostwald ripening).
/// Δu = 0 inside and outside the curves, u = −σC on them, u bounded at infinity; the normal
/// speed is the jump of the flux, V = D_out ∂u_out/∂N − D_in ∂u_in/∂N. The total area is kept
/// and the length falls; small particles shrink and vanish while large ones grow. A circle's
/// mode m decays at σ(D_in + D_out) m(m² − 1)/R³. A particle that would vanish well within a
/// step is given the flux that makes it vanish at the step's end, no more (docs/algorithms/
/// potential.md).
class MullinsSekerka final : public VelocityLaw {
public:
    /// sigma: σ > 0, the surface tension; d_in, d_out > 0: the diffusion coefficients inside and
    /// outside. Throws InvalidInput otherwise.
    explicit MullinsSekerka(double sigma = 1.0, double d_in = 1.0, double d_out = 1.0);
    std::string name() const override { return "mullins-sekerka"; }
    /// No module's normals or curvature: the law fits smooth curves itself.
    GeometryNeeds needs() const override { return {.smooth = true}; }
    /// The total area is kept; the length only falls (the gradient flow of length).
    bool preserves_area() const override { return true; }
    Invariants invariants() const override { return {.keeps_area = true, .shortens = true}; }
    /// σ(D_in + D_out)|C|³: the decay rate of a circle's modes of wavelength about its radius.
    double stiffness(double curvature) const override {
        return sigma_ * (d_in_ + d_out_) * std::pow(std::abs(curvature), 3);
    }
    /// The vertex velocities V·N, N the smooth curves' normal.
    std::vector<Vec2> velocities(double t, const Interface& curves,
                                 const VertexGeometry& geometry) const override;
    /// V at the vertices, the law's normal speed, for a step of size k (0: none).
    std::vector<double> normal_speeds(const Interface& curves, double k) const;
    /// How the boundary integral operators are summed (dense up to 3,000 samples and fast
    /// beyond unless set): for benchmarks and tests of the summation.
    void set_summation(Summation how) { summation_ = how; }

private:
    std::vector<double> normal_speeds(const SmoothCurves& s, double k) const;
    /// V at the samples from the single layer's density μ.
    std::vector<double> flux_jump(const SmoothCurves& s, const std::vector<double>& mu) const;
    /// Within a step of k, a curve that would vanish well within it vanishes at its end.
    /// system: the single layer of s, already factored.
    void limit_vanishing(const SmoothCurves& s, const SingleLayerSystem& system, double k,
                         std::vector<double>& v) const;

    double sigma_, d_in_, d_out_;
    Summation summation_ = Summation::automatic;
};

/// `hele-shaw`: one-phase Hele-Shaw flow with surface tension (a viscous drop between two close
/// plates, pressure-driven). Δp = 0 inside each region the curves enclose, p = −σC on its
/// boundary, V = −∂p/∂N: each region keeps its area and its length falls, relaxing to a circle;
/// a circle's mode m decays at σ m(m² − 1)/R³. With an injection rate Q ≠ 0 at the source
/// (sx, sy), inside one region, that region's area grows at Q: p gains −(Q/2π) log|x − source|.
class HeleShaw final : public VelocityLaw {
public:
    /// sigma > 0: the surface tension; q: the injection rate (area per unit time, either sign);
    /// source: where it is injected. Throws InvalidInput unless sigma > 0 and all are finite.
    explicit HeleShaw(double sigma = 1.0, double q = 0.0, Vec2 source = {});
    std::string name() const override { return "hele-shaw"; }
    /// No module's normals or curvature: the law fits smooth curves itself.
    GeometryNeeds needs() const override { return {.smooth = true}; }
    /// The area is known exactly: kept, or growing at Q.
    bool preserves_area() const override { return true; }
    Invariants invariants() const override;
    /// σ|C|³: the decay rate of a circle's modes of wavelength about its radius.
    double stiffness(double curvature) const override {
        return sigma_ * std::pow(std::abs(curvature), 3);
    }
    /// The vertex velocities V·N, N the smooth curves' normal.
    std::vector<Vec2> velocities(double t, const Interface& curves,
                                 const VertexGeometry& geometry) const override;
    /// V at the vertices, the law's normal speed, for a step of size k (0: none). Throws
    /// InvalidInput when Q ≠ 0 and the source lies in no region or on a curve.
    std::vector<double> normal_speeds(const Interface& curves, double k) const;
    /// How the boundary integral operators are summed (dense up to 3,000 samples and fast
    /// beyond unless set): for benchmarks and tests of the summation.
    void set_summation(Summation how) { summation_ = how; }

private:
    std::vector<double> normal_speeds(const Interface& curves, const SmoothCurves& s,
                                      double k) const;

    double sigma_, q_;
    Vec2 source_;
    Summation summation_ = Summation::automatic;
};

}  // namespace slc
