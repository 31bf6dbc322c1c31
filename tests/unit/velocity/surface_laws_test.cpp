// Tests of the built-in laws of surfaces: rotation and translation fields, Enright's field
// (divergence free, reversed at T/2), normal speeds, mean curvature and its volume-preserving form
// at the vertices, and what each claims to keep.
#include "slc/velocity/surface_laws.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/geometry/surface_shapes.hpp"

namespace slc {
namespace {

using std::numbers::pi;

std::vector<Vec3> sample_at(const SurfaceVelocityLaw& law, double t, std::vector<Vec3> xs) {
    return field_velocities(law, t, xs);
}

TEST(SurfaceLaws, RotationAboutAnAxisThroughACentre) {
    const SurfaceRotation law(2.0, {0.0, 0.0, 3.0}, {1.0, 0.0, 0.0});
    const std::vector<Vec3> u = sample_at(law, 0.0, {{2.0, 0.0, 5.0}, {1.0, 1.0, -1.0}});
    EXPECT_NEAR(norm(u[0] - Vec3{0.0, 2.0, 0.0}), 0.0, 1e-15);
    EXPECT_NEAR(norm(u[1] - Vec3{-2.0, 0.0, 0.0}), 0.0, 1e-15);
    EXPECT_TRUE(law.invariants().rigid);
    EXPECT_THROW(SurfaceRotation(1.0, {0.0, 0.0, 0.0}), InvalidInput);
    const SurfaceTranslation shift({1.0, 2.0, 3.0});
    EXPECT_EQ(sample_at(shift, 7.0, {{5.0, 5.0, 5.0}})[0], (Vec3{1.0, 2.0, 3.0}));
}

TEST(SurfaceLaws, EnrightFieldIsDivergenceFreeAndReverses) {
    const EnrightField law(3.0);
    const double h = 1e-5;
    for (const Vec3 x : {Vec3{0.35, 0.35, 0.35}, Vec3{0.1, 0.7, 0.4}, Vec3{0.9, 0.2, 0.6}}) {
        const auto u = sample_at(law, 0.0,
                                 {x + Vec3{h, 0, 0}, x - Vec3{h, 0, 0}, x + Vec3{0, h, 0},
                                  x - Vec3{0, h, 0}, x + Vec3{0, 0, h}, x - Vec3{0, 0, h}});
        const double divergence = (u[0].x - u[1].x + u[2].y - u[3].y + u[4].z - u[5].z) / (2 * h);
        EXPECT_NEAR(divergence, 0.0, 1e-8);
        // cos(πt/T) changes sign about T/2.
        const Vec3 before = sample_at(law, 1.0, {x})[0], after = sample_at(law, 2.0, {x})[0];
        EXPECT_NEAR(norm(before + after), 0.0, 1e-14);
    }
    // u = 2 sin²(πx) sin(2πy) sin(2πz) at t = 0.
    const Vec3 u = sample_at(law, 0.0, {{0.5, 0.25, 0.25}})[0];
    EXPECT_NEAR(u.x, 2.0, 1e-14);
    EXPECT_THROW(EnrightField(0.0), InvalidInput);
}

TEST(SurfaceLaws, NormalSpeeds) {
    const Surface s = sphere({}, 0.5, 3);
    const std::vector<Vec3> u = vertex_velocities(SurfaceNormalSpeed(2.0), 0.0, s);
    for (std::size_t i = 0; i < u.size(); ++i)
        EXPECT_NEAR(norm(u[i] - 2.0 * s.vertices[i] / 0.5), 0.0, 1e-3);
    // The cubic anisotropy: R + ε (Σ n⁴ − 3/5), fastest along the axes for ε > 0.
    const SurfaceAnisotropicNormalSpeed faceted(1.0, 0.5);
    std::vector<double> v(2);
    const std::vector<Vec3> at{{1, 0, 0}, {1, 1, 1}};
    const std::vector<Vec3> n{{1, 0, 0}, Vec3{1, 1, 1} / std::sqrt(3.0)};
    faceted.normal_speeds(0.0, at, n, v);
    EXPECT_NEAR(v[0], 1.0 + 0.5 * 0.4, 1e-15);
    EXPECT_NEAR(v[1], 1.0 + 0.5 * (1.0 / 3.0 - 0.6), 1e-15);
    EXPECT_TRUE(faceted.invariants().cannot_vanish);
}

TEST(SurfaceLaws, MeanCurvatureAndItsVolumePreservingForm) {
    // On a sphere of radius R, u = −(2/R) N; the volume-preserving form is zero.
    const double r = 0.4;
    const Surface s = sphere({0.1, 0.0, 0.0}, r, 4);
    const std::vector<Vec3> u = vertex_velocities(SurfaceMeanCurvatureFlow(), 0.0, s);
    const std::vector<Vec3> w = vertex_velocities(SurfaceVolumePreservingFlow(), 0.0, s);
    double worst = 0.0, worst_w = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) {
        const Vec3 n = (s.vertices[i] - Vec3{0.1, 0.0, 0.0}) / r;
        worst = std::max(worst, norm(u[i] + (2.0 / r) * n));
        worst_w = std::max(worst_w, norm(w[i]));
    }
    EXPECT_LT(worst, 0.01 * 2.0 / r);
    EXPECT_LT(worst_w, 0.01 * 2.0 / r);
    // On two spheres, the small one shrinks and the large one grows: mean normal speed zero.
    const Surface two = join({sphere({-0.5, 0, 0}, 0.2, 3), sphere({0.4, 0, 0}, 0.4, 3)});
    const SurfaceGeometry g = surface_geometry(two, {.curvature = true});
    const std::vector<Vec3> v = vertex_velocities(SurfaceVolumePreservingFlow(), 0.0, two);
    std::vector<double> speed(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) speed[i] = dot(v[i], g.normals[i]);
    EXPECT_NEAR(area_mean(two, speed), 0.0, 1e-12);
    EXPECT_LT(speed.front(), 0.0);
    EXPECT_GT(speed.back(), 0.0);
    EXPECT_TRUE(SurfaceVolumePreservingFlow().preserves_area());
}

TEST(SurfaceLaws, CurvatureLawsNeedTheirGeometry) {
    const Surface s = sphere({}, 0.5, 2);
    EXPECT_THROW(SurfaceMeanCurvatureFlow().velocities(0.0, s, {}), InvalidInput);
    const auto nan_law = field_law("nan", [](double, Vec3) { return Vec3{NAN, 0.0, 0.0}; });
    EXPECT_THROW(vertex_velocities(*nan_law, 0.0, s), NumericalFailure);
    // A module is a choice for curves only.
    const auto with_module =
        local_law("m", {.normals = true, .module = GeometryModule::intrinsic},
                  [](double, const SurfaceVertexState& v) { return v.normal; });
    EXPECT_THROW(vertex_velocities(*with_module, 0.0, s), InvalidInput);
}

}  // namespace
}  // namespace slc
