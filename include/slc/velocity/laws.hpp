/// @file
/// The built-in velocity laws of the paper's examples (§4.4–4.7 and the single vortex of LeVeque
/// and Rider–Kothe), each a VelocityLaw. Their names and parameters on the command line are in
/// factory.hpp.
#pragma once

#include <cmath>
#include <numbers>

#include "slc/velocity/velocity.hpp"

namespace slc {

/// `rotation`: rigid counterclockwise rotation u = ω (−(y − cy), x − cx) about centre (§4.4).
class Rotation final : public FlowFieldLaw {
public:
    /// omega: angular velocity ω in radians per unit time (counterclockwise when positive);
    /// centre: the fixed point (cx, cy).
    explicit Rotation(double omega = 1.0, Vec2 centre = {}) : omega_(omega), centre_(centre) {}
    std::string name() const override { return "rotation"; }
    Invariants invariants() const override { return {.keeps_area = true, .rigid = true}; }
    /// The field at each point, as the base's sample().
    void sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const override;

private:
    double omega_;
    Vec2 centre_;
};

/// `translation`: the constant velocity u = (ux, uy).
class Translation final : public FlowFieldLaw {
public:
    /// u: the velocity of every point, length per unit time.
    explicit Translation(Vec2 u) : u_(u) {}
    std::string name() const override { return "translation"; }
    Invariants invariants() const override { return {.keeps_area = true, .rigid = true}; }
    /// The field at each point, as the base's sample().
    void sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const override;

private:
    Vec2 u_;
};

/// `vortex`: LeVeque's time-reversed single vortex on [0, 1]², period T:
/// u = sin²(πx) sin(2πy) cos(πt/T), v = −sin²(πy) sin(2πx) cos(πt/T). Divergence free; the
/// flow reverses at t = T/2 and returns every point to its start at t = T.
class SingleVortex final : public FlowFieldLaw {
public:
    /// Throws InvalidInput unless period > 0.
    explicit SingleVortex(double period = 8.0);
    std::string name() const override { return "vortex"; }
    Invariants invariants() const override { return {.keeps_area = true}; }
    /// The field at each point, as the base's sample().
    void sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const override;

private:
    double period_;
};

/// `unit-normal`: constant normal speed, u = s·N (§4.5.1–4.5.2); s > 0 grows the curve.
/// A normal law: at the vertices with the intrinsic module's normals unless told otherwise (the
/// paper's choice for first-order geometric laws), off the curve with the distance field's.
class NormalSpeed final : public NormalLaw {
public:
    /// speed: s, length per unit time (negative shrinks the curve); module: where vertex normals
    /// come from.
    explicit NormalSpeed(double speed = 1.0, std::optional<GeometryModule> module = std::nullopt)
        : NormalLaw(module), speed_(speed) {}
    std::string name() const override { return "unit-normal"; }
    /// No motion at speed 0; a growing curve at speed > 0.
    Invariants invariants() const override {
        if (speed_ == 0.0) return {.keeps_area = true, .rigid = true};
        return {.cannot_vanish = speed_ > 0.0};
    }
    /// The normal speed at each point with its normal, as the base's normal_speeds().
    void normal_speeds(double t, std::span<const Vec2> points, std::span<const Vec2> normals,
                       std::span<double> out) const override;

private:
    double speed_;
};

/// `anisotropic`: u = v(θ)·N with v = R + ε cos(m(θ − α)), θ the normal angle,
/// N = (cos θ, sin θ), α the tilt of the anisotropy's axes (§4.5.3, Equation 12, with α = 0;
/// the paper's Wulff-shape runs use R = −1 and ε = 5/(m² − 1), and tilt them by 10° and 180°/m).
class AnisotropicNormalSpeed final : public NormalLaw {
public:
    /// r: R, the isotropic part of the speed; m: the number of lobes of cos(mθ); eps: ε, their
    /// amplitude; tilt: α, radians; module: where vertex normals come from.
    AnisotropicNormalSpeed(double r, double m, double eps, double tilt = 0.0,
                           std::optional<GeometryModule> module = std::nullopt)
        : NormalLaw(module), r_(r), m_(m), eps_(eps), tilt_(tilt) {}
    std::string name() const override { return "anisotropic"; }
    /// Growing in every direction when R > |ε|.
    Invariants invariants() const override { return {.cannot_vanish = r_ > std::abs(eps_)}; }
    /// The normal speed at each point with its normal, as the base's normal_speeds().
    void normal_speeds(double t, std::span<const Vec2> points, std::span<const Vec2> normals,
                       std::span<double> out) const override;

private:
    double r_, m_, eps_, tilt_;
};

/// `curvature`: motion by curvature u = C·N (§4.6), which shrinks a circle as R(t)² = R(0)² − 2t.
/// Normals and curvature from the arclength module unless told otherwise (stable at any step;
/// the paper used the embedded module, which its named problems keep).
class CurvatureFlow final : public VelocityLaw {
public:
    /// module: where N and C come from; unset: GeometryNeeds::resolved_module().
    explicit CurvatureFlow(std::optional<GeometryModule> module = std::nullopt) : module_(module) {}
    std::string name() const override { return "curvature"; }
    /// dA/dt = −2π per counterclockwise curve, +2π per hole (the turning of each curve).
    Invariants invariants() const override {
        return {
            .cannot_split = true, .shortens = true, .area_rate_per_curve = -2.0 * std::numbers::pi};
    }
    GeometryNeeds needs() const override {
        return {.normals = true, .curvature = true, .module = module_};
    }
    /// The vertex velocities, as the base's velocities().
    std::vector<Vec2> velocities(double t, const Interface& curves,
                                 const VertexGeometry& geometry) const override;

private:
    std::optional<GeometryModule> module_;
};

/// `volume-preserving-curvature`: the nonlocal law u = (C − C̄)·N, C̄ the arc-length mean of C
/// over all components of Γ (§4.7, Equation 13). The mean normal speed is zero, so the enclosed
/// area is conserved; small components give their area to large ones. Arclength module by
/// default, as for CurvatureFlow.
class VolumePreservingCurvatureFlow final : public VelocityLaw {
public:
    /// module: where N and C come from; unset: GeometryNeeds::resolved_module().
    explicit VolumePreservingCurvatureFlow(std::optional<GeometryModule> module = std::nullopt)
        : module_(module) {}
    std::string name() const override { return "volume-preserving-curvature"; }
    bool preserves_area() const override { return true; }
    /// Keeps the area and shortens the curves: the gradient flow of length at fixed area.
    Invariants invariants() const override { return {.keeps_area = true, .shortens = true}; }
    GeometryNeeds needs() const override {
        return {.normals = true, .curvature = true, .module = module_};
    }
    /// The vertex velocities, as the base's velocities().
    std::vector<Vec2> velocities(double t, const Interface& curves,
                                 const VertexGeometry& geometry) const override;

private:
    std::optional<GeometryModule> module_;
};

}  // namespace slc
