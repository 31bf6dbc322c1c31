/// @file
/// The built-in velocity laws of the paper's examples (§4.4–4.7 and the single vortex of LeVeque
/// and Rider–Kothe), each a VelocityLaw; translation and the curvature flows are written once for
/// curves and surfaces (surface_laws.hpp names their surface forms). Their names and parameters
/// on the command line are in factory.hpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>

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

/// `translation`: the constant velocity u, of curves (Translation) or of surfaces
/// (SurfaceTranslation).
template <int dim>
class BasicTranslation final : public BasicFlowFieldLaw<dim> {
public:
    /// u: the velocity of every point, length per unit time.
    explicit BasicTranslation(PointOf<dim> u) : u_(u) {}
    std::string name() const override { return "translation"; }
    Invariants invariants() const override { return {.keeps_area = true, .rigid = true}; }
    /// The field at each point, as the base's sample().
    void sample(double, std::span<const PointOf<dim>> points,
                std::span<PointOf<dim>> out) const override {
        std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(points.size()), u_);
    }

private:
    PointOf<dim> u_;
};
/// `translation` of curves: u = (ux, uy).
using Translation = BasicTranslation<2>;

/// The base of LeVeque's time-reversed flows u(t, x) = f(x) cos(πt/T) (SingleVortex,
/// EnrightField): the flow reverses at t = T/2 and returns every point to its start at t = T.
template <int dim>
class BasicReversingFlow : public BasicFlowFieldLaw<dim> {
protected:
    /// law: the law's name in messages; period: T. Throws InvalidInput unless period > 0.
    BasicReversingFlow(const char* law, double period);
    /// cos(πt/T), the factor of the flow at time t.
    double reversal(double t) const { return std::cos(std::numbers::pi * t / period_); }

private:
    double period_;
};

extern template class BasicReversingFlow<2>;
extern template class BasicReversingFlow<3>;

/// `vortex`: LeVeque's time-reversed single vortex on [0, 1]², period T:
/// u = sin²(πx) sin(2πy) cos(πt/T), v = −sin²(πy) sin(2πx) cos(πt/T). Divergence free; the
/// flow reverses at t = T/2 and returns every point to its start at t = T.
class SingleVortex final : public BasicReversingFlow<2> {
public:
    /// Throws InvalidInput unless period > 0.
    explicit SingleVortex(double period = 8.0) : BasicReversingFlow<2>("vortex", period) {}
    std::string name() const override { return "vortex"; }
    /// A smooth divergence-free flow: it keeps the area, and (a diffeomorphism) never splits a
    /// curve; a contour that parts a filament thinner than its cells breaks the law.
    Invariants invariants() const override { return {.keeps_area = true, .cannot_split = true}; }
    /// The field at each point, as the base's sample().
    void sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const override;
};

/// `unit-normal`: constant normal speed, u = s·N (§4.5.1–4.5.2); s > 0 grows the curve or
/// surface. A normal law: for curves at the vertices with the intrinsic module's normals unless
/// told otherwise (the paper's choice for first-order geometric laws); off the interface with the
/// distance field's.
template <int dim>
class BasicNormalSpeed final : public BasicNormalLaw<dim> {
public:
    using Point = PointOf<dim>;
    /// speed: s, length per unit time (negative shrinks); module: where a curve's vertex normals
    /// come from.
    explicit BasicNormalSpeed(double speed = 1.0,
                              std::optional<GeometryModule> module = std::nullopt)
        : BasicNormalLaw<dim>(module), speed_(speed) {}
    std::string name() const override { return "unit-normal"; }
    /// No motion at speed 0; growing at speed > 0 (the area or volume changing at s times the
    /// length or area), shrinking below.
    Invariants invariants() const override { return constant_speed_invariants<dim>(speed_); }
    /// s at each point, as the base's normal_speeds().
    void normal_speeds(double, std::span<const Point> points, std::span<const Point>,
                       std::span<double> out) const override {
        std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(points.size()), speed_);
    }
    std::optional<double> speed_bound() const override { return std::abs(speed_); }
    std::optional<double> constant_speed() const override { return speed_; }

private:
    double speed_;
};
using NormalSpeed = BasicNormalSpeed<2>;

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
    /// Growing in every direction when R > |ε|, shrinking when R < −|ε|.
    Invariants invariants() const override {
        return {.cannot_vanish = r_ > std::abs(eps_), .cannot_grow = r_ < -std::abs(eps_)};
    }
    /// The normal speed at each point with its normal, as the base's normal_speeds().
    void normal_speeds(double t, std::span<const Vec2> points, std::span<const Vec2> normals,
                       std::span<double> out) const override;
    /// |V| ≤ |R| + |ε|.
    std::optional<double> speed_bound() const override { return std::abs(r_) + std::abs(eps_); }

private:
    double r_, m_, eps_, tilt_;
};

/// The base of the laws that read the curvature at the vertices (the curvature flows, a speed
/// expression in C): they need the vertex normals and curvature, from the module the law names
/// for curves (unset: GeometryNeeds::resolved_module(), the arclength module, stable at any step;
/// the paper used the embedded module, which its named problems keep). Surfaces have one module:
/// leave it unset.
template <int dim>
class BasicCurvatureLaw : public BasicVelocityLaw<dim> {
public:
    /// module: where N and C come from.
    explicit BasicCurvatureLaw(std::optional<GeometryModule> module = std::nullopt)
        : module_(module) {}
    GeometryNeeds needs() const override {
        return {.normals = true, .curvature = true, .module = module_};
    }

protected:
    /// Throws InvalidInput unless geometry holds the normals and the curvature at every vertex
    /// of interface.
    void require_geometry(const ShapeOf<dim>& interface, const GeometryOf<dim>& geometry) const;

private:
    std::optional<GeometryModule> module_;
};

/// `curvature`: motion by curvature u = C·N (§4.6), C = −∇·N: for curves (CurvatureFlow) it
/// shrinks a circle as R(t)² = R(0)² − 2t; for surfaces (SurfaceMeanCurvatureFlow) C is the sum
/// of the principal curvatures, and a sphere shrinks as R(t)² = R(0)² − 4t.
template <int dim>
class BasicCurvatureFlow final : public BasicCurvatureLaw<dim> {
public:
    using BasicCurvatureLaw<dim>::BasicCurvatureLaw;
    std::string name() const override { return "curvature"; }
    /// Curves: dA/dt = −2π per counterclockwise curve, +2π per hole (the turning of each curve),
    /// and an embedded curve never splits. Surfaces: the area only falls (the flow is area's
    /// gradient flow); surfaces may pinch and split.
    Invariants invariants() const override {
        if constexpr (dim == 2) {
            return {.cannot_split = true,
                    .shortens = true,
                    .area_rate_per_curve = -2.0 * std::numbers::pi};
        } else {
            return {.shortens = true};
        }
    }
    /// The vertex velocities, as the base's velocities().
    std::vector<PointOf<dim>> velocities(double t, const ShapeOf<dim>& interface,
                                         const GeometryOf<dim>& geometry) const override;
};
/// Motion of curves by curvature.
using CurvatureFlow = BasicCurvatureFlow<2>;

/// `volume-preserving-curvature`: the nonlocal law u = (C − C̄)·N, C̄ the mean of C over all
/// components of Γ (§4.7, Equation 13), by arc length for curves and by area for surfaces. The
/// mean normal speed is zero, so the enclosed area (volume) is conserved; small components give
/// theirs to large ones. Arclength module for curves by default, as for CurvatureFlow.
template <int dim>
class BasicVolumePreservingFlow final : public BasicCurvatureLaw<dim> {
public:
    using BasicCurvatureLaw<dim>::BasicCurvatureLaw;
    std::string name() const override { return "volume-preserving-curvature"; }
    bool preserves_area() const override { return true; }
    /// Keeps the area and shortens the curves: the gradient flow of length at fixed area.
    Invariants invariants() const override { return {.keeps_area = true, .shortens = true}; }
    /// The vertex velocities, as the base's velocities().
    std::vector<PointOf<dim>> velocities(double t, const ShapeOf<dim>& interface,
                                         const GeometryOf<dim>& geometry) const override;
};
/// The volume-preserving curvature flow of curves.
using VolumePreservingCurvatureFlow = BasicVolumePreservingFlow<2>;

extern template class BasicCurvatureLaw<2>;
extern template class BasicCurvatureLaw<3>;
extern template class BasicCurvatureFlow<2>;
extern template class BasicCurvatureFlow<3>;
extern template class BasicVolumePreservingFlow<2>;
extern template class BasicVolumePreservingFlow<3>;

}  // namespace slc
