// Tests of the surface geometry module: normals and mean curvature against spheres and tori
// (exact values, observed orders), a randomly jittered sphere, invariance under scaling, the
// smoothing, vertex rings and areas.
#include "slc/geometry_modules/surface_geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "slc/core/error.hpp"
#include "slc/geometry/surface_shapes.hpp"

namespace slc {
namespace {

struct Errors {
    double normal = 0.0;     ///< largest |N − exact|
    double curvature = 0.0;  ///< largest |C − exact|
    double h = 0.0;          ///< mean edge length
};

double mean_edge(const Surface& s) {
    double sum = 0.0;
    for (std::size_t t = 0; t < s.size(); ++t) {
        const Triangle3 tri = s.triangle(t);
        sum += distance(tri.a, tri.b) + distance(tri.b, tri.c) + distance(tri.c, tri.a);
    }
    return sum / (3.0 * static_cast<double>(s.size()));
}

/// Errors on the sphere of radius r about c: N = (x − c)/r, C = −2/r.
Errors sphere_errors(const Surface& s, Vec3 c, double r, const SurfaceGeometryOptions& o = {}) {
    const SurfaceGeometry g = surface_geometry(s, o);
    Errors e{.h = mean_edge(s)};
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
        e.normal = std::max(e.normal, norm(g.normals[i] - (s.vertices[i] - c) / r));
        e.curvature = std::max(e.curvature, std::abs(g.curvature[i] + 2.0 / r));
    }
    return e;
}

TEST(SurfaceGeometry, SphereConvergesAtSecondOrder) {
    const Vec3 c{0.1, -0.2, 0.3};
    const double r = 0.7;
    std::vector<Errors> e;
    for (int n = 2; n <= 5; ++n) e.push_back(sphere_errors(sphere(c, r, n), c, r));
    for (std::size_t i = 1; i < e.size(); ++i) {
        const double scale = std::log(e[i - 1].h / e[i].h);
        const double normal_order = std::log(e[i - 1].normal / e[i].normal) / scale;
        const double curvature_order = std::log(e[i - 1].curvature / e[i].curvature) / scale;
        std::printf("h %.4f  normal %.2e (order %.2f)  curvature %.2e (order %.2f)\n", e[i].h,
                    e[i].normal, normal_order, e[i].curvature, curvature_order);
        EXPECT_GT(normal_order, 1.8);
        EXPECT_GT(curvature_order, 1.5);
    }
    EXPECT_LT(e.back().curvature, 2e-3 * 2.0 / r);
}

TEST(SurfaceGeometry, TorusCurvatureConverges) {
    // C = −(1/r + cos v/(R + r cos v)) at tube angle v, for the outward normal.
    const double big = 0.6, small = 0.25;
    std::vector<Errors> e;
    for (int n : {16, 32, 64}) {
        const Surface s = torus({}, big, small, 2 * n, n);
        const SurfaceGeometry g = surface_geometry(s);
        Errors err{.h = mean_edge(s)};
        for (std::size_t i = 0; i < s.vertices.size(); ++i) {
            const Vec3 p = s.vertices[i];
            const double rho = std::hypot(p.x, p.y);
            const Vec3 centre{big * p.x / rho, big * p.y / rho, 0.0};
            const Vec3 normal = (p - centre) / small;
            const double cos_v = (rho - big) / small;
            const double exact = -(1.0 / small + cos_v / (big + small * cos_v));
            err.normal = std::max(err.normal, norm(g.normals[i] - normal));
            err.curvature = std::max(err.curvature, std::abs(g.curvature[i] - exact));
        }
        e.push_back(err);
    }
    for (std::size_t i = 1; i < e.size(); ++i) {
        const double scale = std::log(e[i - 1].h / e[i].h);
        const double order = std::log(e[i - 1].curvature / e[i].curvature) / scale;
        std::printf("h %.4f  normal %.2e  curvature %.2e (order %.2f)\n", e[i].h, e[i].normal,
                    e[i].curvature, order);
        EXPECT_GT(order, 1.5);
    }
    // |C| runs from 5.6 to 6.9: 1% of it at 64 × 128 quads.
    EXPECT_LT(e.back().curvature, 0.05);
    EXPECT_LT(e.back().normal, 5e-3);
}

TEST(SurfaceGeometry, JitteredSphereConverges) {
    // Vertices slid along the sphere by up to 20% of an edge: the fit stays within a few
    // percent of −2/r and shrinks as h² (measured 1.94).
    const double r = 1.0;
    std::vector<double> errors, hs;
    for (int n = 3; n <= 5; ++n) {
        Surface s = sphere({}, r, n);
        const double h = mean_edge(s);
        std::mt19937 random(7);
        std::uniform_real_distribution<double> jitter(-0.2 * h, 0.2 * h);
        for (Vec3& v : s.vertices) {
            const Vec3 moved{v.x + jitter(random), v.y + jitter(random), v.z + jitter(random)};
            v = r * moved / norm(moved);
        }
        errors.push_back(sphere_errors(s, {}, r).curvature);
        hs.push_back(h);
    }
    const double order =
        std::log(errors.front() / errors.back()) / std::log(hs.front() / hs.back());
    std::printf("jittered: curvature errors %.3f %.3f %.3f, order %.2f\n", errors[0], errors[1],
                errors[2], order);
    EXPECT_GT(order, 1.5);
    EXPECT_LT(errors.back(), 0.01 * 2.0 / r);
}

TEST(SurfaceGeometry, ScalesAsOneOverLength) {
    const Surface s = sphere({}, 1.0, 3);
    Surface big = s;
    for (Vec3& v : big.vertices) v = 1000.0 * v + Vec3{5e3, -2e3, 1e3};
    const SurfaceGeometry g = surface_geometry(s), gb = surface_geometry(big);
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
        EXPECT_NEAR(gb.curvature[i] * 1000.0, g.curvature[i], 1e-8);
        EXPECT_NEAR(norm(gb.normals[i] - g.normals[i]), 0.0, 1e-8);
    }
}

TEST(SurfaceGeometry, SmoothingKeepsAConstantAndAveragesNoise) {
    const double r = 0.5;
    const Surface s = sphere({}, r, 4);
    const Errors plain = sphere_errors(s, {}, r);
    const Errors smooth = sphere_errors(s, {}, r, {.smoothing = 4.0 * plain.h});
    EXPECT_LT(smooth.curvature, plain.curvature + 1e-12);
    // Noise on a vertex spreads over its neighbours: one bumped vertex's error falls.
    Surface bumped = s;
    bumped.vertices[17] = 1.01 * bumped.vertices[17];
    const double raw = surface_geometry(bumped).curvature[17];
    const double averaged = surface_geometry(bumped, {.smoothing = 3.0 * plain.h}).curvature[17];
    EXPECT_LT(std::abs(averaged + 2.0 / r), 0.5 * std::abs(raw + 2.0 / r));
    EXPECT_THROW(surface_geometry(s, {.smoothing = -1.0}), InvalidInput);
}

TEST(SurfaceGeometry, RingsAndAreas) {
    const Surface ico = sphere({}, 1.0, 0);
    const VertexRings rings = vertex_rings(ico);
    for (std::size_t i = 0; i < ico.vertices.size(); ++i) {
        EXPECT_EQ(rings.of(i).size(), 5u);
        EXPECT_TRUE(std::is_sorted(rings.of(i).begin(), rings.of(i).end()));
    }
    const Surface t = torus({}, 1.0, 0.3, 12, 8);
    const std::vector<double> w = vertex_areas(t);
    double sum = 0.0;
    for (double a : w) sum += a;
    EXPECT_NEAR(sum, area(t), 1e-12 * area(t));
    const std::vector<double> ones(t.vertices.size(), 1.0);
    EXPECT_NEAR(area_mean(t, ones), 1.0, 1e-14);
}

TEST(SurfaceGeometry, NormalsOnlyWhenAsked) {
    const SurfaceGeometry g = surface_geometry(sphere({}, 1.0, 2), {.curvature = false});
    EXPECT_TRUE(g.curvature.empty());
    EXPECT_EQ(g.normals.size(), sphere({}, 1.0, 2).vertices.size());
}

}  // namespace
}  // namespace slc
