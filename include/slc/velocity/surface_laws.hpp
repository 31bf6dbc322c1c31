/// @file
/// The built-in velocity laws of surfaces (DESIGN §8; the 3D counterparts of laws.hpp): rigid
/// rotation about an axis and translation, Enright's deformation field, constant and anisotropic
/// normal speed, mean curvature flow and its volume-preserving form (paper Eq. 13 in space).
/// Translation and the curvature flows are the templates of laws.hpp at dim = 3.
#pragma once

#include <cmath>
#include <optional>

#include "slc/velocity/laws.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc {

/// `rotation`: rigid rotation u = ω a × (x − c) about the axis a through c, counterclockwise seen
/// from the tip of a.
class SurfaceRotation final : public SurfaceFlowFieldLaw {
public:
    /// omega: ω, radians per unit time; axis: a, any non-zero vector (scaled to unit length);
    /// centre: c, a point of the axis. Throws InvalidInput for a zero or non-finite axis.
    explicit SurfaceRotation(double omega = 1.0, Vec3 axis = {0.0, 0.0, 1.0}, Vec3 centre = {});
    std::string name() const override { return "rotation"; }
    Invariants invariants() const override { return {.keeps_area = true, .rigid = true}; }
    /// The field at each point, as the base's sample().
    void sample(double t, std::span<const Vec3> points, std::span<Vec3> out) const override;

private:
    double omega_;
    Vec3 axis_, centre_;
};

/// `translation` of surfaces: the constant velocity u = (ux, uy, uz).
using SurfaceTranslation = BasicTranslation<3>;

/// `enright`: LeVeque's deformation field on the unit cube as used by Enright, Fedkiw, Ferziger
/// and Mitchell (J. Comput. Phys. 183, 2002), period T:
/// u = 2 sin²(πx) sin(2πy) sin(2πz) c, v = −sin(2πx) sin²(πy) sin(2πz) c,
/// w = −sin(2πx) sin(2πy) sin²(πz) c, c = cos(πt/T). Divergence free; it reverses at T/2 and
/// returns every point to its start at T.
class EnrightField final : public BasicReversingFlow<3> {
public:
    /// Throws InvalidInput unless period > 0.
    explicit EnrightField(double period = 3.0) : BasicReversingFlow<3>("enright", period) {}
    std::string name() const override { return "enright"; }
    /// A smooth divergence-free flow: it keeps the volume and cannot tear the surface.
    Invariants invariants() const override { return {.keeps_area = true, .cannot_split = true}; }
    /// The field at each point, as the base's sample().
    void sample(double t, std::span<const Vec3> points, std::span<Vec3> out) const override;
};

/// `unit-normal`: constant normal speed u = s·N (laws.hpp).
using SurfaceNormalSpeed = BasicNormalSpeed<3>;

/// `anisotropic`: u = v(N)·N with v = R + ε (n_x⁴ + n_y⁴ + n_z⁴ − 3/5), a cubic anisotropy
/// whose mean over directions is R: fastest along the axes for ε > 0.
class SurfaceAnisotropicNormalSpeed final : public SurfaceNormalLaw {
public:
    /// r: R, the isotropic part; eps: ε, the amplitude of the cubic part.
    SurfaceAnisotropicNormalSpeed(double r, double eps) : r_(r), eps_(eps) {}
    std::string name() const override { return "anisotropic"; }
    /// Growing in every direction when R exceeds the anisotropy's range, shrinking when −R
    /// does: the cubic part lies in [−4/15, 2/5].
    Invariants invariants() const override {
        return {.cannot_vanish = r_ - 0.4 * std::abs(eps_) > 0.0,
                .cannot_grow = r_ + 0.4 * std::abs(eps_) < 0.0};
    }
    /// The normal speed at each point with its normal, as the base's normal_speeds().
    void normal_speeds(double t, std::span<const Vec3> points, std::span<const Vec3> normals,
                       std::span<double> out) const override;
    /// |V| ≤ |R| + 2/5 |ε|: the cubic part lies in [−4/15, 2/5].
    std::optional<double> speed_bound() const override {
        return std::abs(r_) + 0.4 * std::abs(eps_);
    }

private:
    double r_, eps_;
};

/// `curvature`: motion by mean curvature u = C·N.
using SurfaceMeanCurvatureFlow = BasicCurvatureFlow<3>;
/// `volume-preserving-curvature`: u = (C − C̄)·N, C̄ the area mean of C over the whole surface
/// (paper Eq. 13 in space): the enclosed volume is kept, the area falls.
using SurfaceVolumePreservingFlow = BasicVolumePreservingFlow<3>;

}  // namespace slc
