// Tests of the surface measures on the built-in shapes, against exact values where the shape
// has them (boxes) and known topology (spheres, tori, unions), and of the pseudo-normal sign.
#include "slc/geometry/surface.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "slc/core/parallel.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/geometry/validate_surface.hpp"

namespace slc {
namespace {

/// Rounding in sums of N terms of size O(1): far above N·2^-53 for the sizes here.
constexpr double sum_rounding = 1e-12;

TEST(Surface, BoxMeasuresAreExact) {
    const Surface s = box_surface({-1, -0.5, 0}, {2, 0.5, 0.25}, 4);
    EXPECT_EQ(s.size(), 12u * 16u);
    EXPECT_NEAR(area(s), 2 * (3 * 1 + 3 * 0.25 + 1 * 0.25), sum_rounding);
    EXPECT_NEAR(volume(s), 3 * 1 * 0.25, sum_rounding);
    EXPECT_EQ(euler_characteristic(s), 2);
    EXPECT_EQ(genus(s), 0);
    EXPECT_EQ(component_count(s), 1u);
    EXPECT_TRUE(prepare_surface(s).notes.empty());
}

TEST(Surface, SphereIsAValidGenusZeroSurfaceConvergingToTheSphere) {
    const double r = 0.7;
    double previous_gap = INFINITY;
    for (int level = 0; level <= 4; ++level) {
        const Surface s = sphere({0.1, 0.2, 0.3}, r, level);
        EXPECT_EQ(s.size(), 20u << (2 * level));
        EXPECT_EQ(euler_characteristic(s), 2);
        EXPECT_EQ(genus(s), 0);
        // Inscribed: less area and volume than the sphere, the gap shrinking fourfold a level
        // once the triangles are near-uniform (second order in the edge length).
        const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
        const double gap = exact - volume(s);
        EXPECT_GT(gap, 0.0);
        EXPECT_LT(area(s), 4 * std::numbers::pi * r * r);
        if (level == 4) {
            EXPECT_NEAR(previous_gap / gap, 4.0, 0.2);
        }
        previous_gap = gap;
        EXPECT_TRUE(prepare_surface(s).notes.empty());
    }
}

TEST(Surface, TorusHasGenusOne) {
    const Surface s = torus({0, 0, 0.5}, 1.0, 0.3, 24, 12);
    EXPECT_EQ(euler_characteristic(s), 0);
    EXPECT_EQ(genus(s), 1);
    EXPECT_GT(volume(s), 0.0);
    EXPECT_LT(volume(s), 2 * std::numbers::pi * std::numbers::pi * 1.0 * 0.09);
    EXPECT_TRUE(prepare_surface(s).notes.empty());
}

TEST(Surface, UnionCountsComponents) {
    const Surface s =
        join({sphere({0, 0, 0}, 1, 1), sphere({3, 0, 0}, 1, 1), torus({0, 5, 0}, 1, 0.2, 8, 5)});
    EXPECT_EQ(component_count(s), 3u);
    EXPECT_EQ(euler_characteristic(s), 4);
    EXPECT_EQ(genus(s), 1);
    const auto label = component_labels(s);
    EXPECT_EQ(label.front(), 0u);
    EXPECT_EQ(label.back(), 2u);
}

TEST(Surface, AdjacencyAndNormalsAreTheSameOnAnyThreadCount) {
    // A torus and two spheres of 10⁴ triangles: the half-edge buckets pair every edge's two
    // half-edges, the neighbours are mutual, and the vertex pseudo-normals alone equal those of
    // pseudo_normals, to the last bit, on one thread and on several.
    const Surface s = join(
        {torus({0, 0, 0}, 1.0, 0.3, 80, 40), sphere({3, 0, 0}, 1, 4), sphere({0, 3, 0}, 0.5, 4)});
    set_thread_count(1);
    const HalfEdgeBuckets one = half_edges_by_lower_vertex(s);
    const auto neighbours_one = triangle_neighbours(s);
    const VertexCorners corners_one = vertex_corners(s);
    const std::vector<Vec3> normals_one = pseudo_normals(s).vertex;
    ASSERT_EQ(one.halves.size(), 3 * s.size());
    for (std::size_t v = 0; v + 1 < one.start.size(); ++v) {
        ASSERT_EQ((one.start[v + 1] - one.start[v]) % 2, 0u);
        for (std::uint32_t i = one.start[v]; i < one.start[v + 1]; i += 2)
            EXPECT_EQ(one.halves[i].first, one.halves[i + 1].first);
    }
    for (std::size_t t = 0; t < s.size(); ++t)
        for (const std::uint32_t u : neighbours_one[t]) {
            const auto& back = neighbours_one[u];
            EXPECT_NE(std::find(back.begin(), back.end(), t), back.end());
        }
    for (int threads : {2, 3}) {
        set_thread_count(threads);
        const HalfEdgeBuckets many = half_edges_by_lower_vertex(s);
        EXPECT_EQ(one.start, many.start);
        EXPECT_EQ(one.halves, many.halves);
        EXPECT_EQ(neighbours_one, triangle_neighbours(s));
        EXPECT_EQ(corners_one.start, vertex_corners(s).start);
        EXPECT_EQ(corners_one.corners, vertex_corners(s).corners);
        const std::vector<Vec3> normals = vertex_pseudo_normals(s);
        ASSERT_EQ(normals.size(), normals_one.size());
        for (std::size_t v = 0; v < normals.size(); ++v) {
            EXPECT_EQ(normals[v].x, normals_one[v].x);
            EXPECT_EQ(normals[v].y, normals_one[v].y);
            EXPECT_EQ(normals[v].z, normals_one[v].z);
        }
    }
    set_thread_count(0);
}

TEST(Surface, WindingNumberIsOneInsideAndZeroOutside) {
    const Surface s = torus({0, 0, 0}, 1.0, 0.3, 16, 8);
    EXPECT_NEAR(winding_number(s, {1, 0, 0}), 1.0, sum_rounding);
    EXPECT_NEAR(winding_number(s, {0, 0, 0}), 0.0, sum_rounding);
    EXPECT_NEAR(winding_number(s, {5, 1, 2}), 0.0, sum_rounding);
}

TEST(Surface, BruteForceSignAgreesWithWindingNumberNearEdgesAndCorners) {
    // Points close to the box's corners and edges, where a face normal alone gets the sign
    // wrong; the winding number is the orientation-free oracle.
    const Surface s = box_surface({0, 0, 0}, {1, 1, 1}, 1);
    const PseudoNormals normals = pseudo_normals(s);
    std::mt19937 rng(11);
    std::normal_distribution<double> jitter(0.0, 1e-3);
    for (int trial = 0; trial < 4000; ++trial) {
        const Vec3 corner = s.vertices[static_cast<std::size_t>(trial) % s.vertices.size()];
        Vec3 x = corner + Vec3{jitter(rng), jitter(rng), jitter(rng)};
        if (trial % 2 == 1) x.x = 0.5 + jitter(rng);  // near an edge along x
        const SurfacePoint p = closest_point_brute_force(s, normals, x);
        const bool inside = winding_number(s, x) > 0.5;
        ASSERT_EQ(p.distance < 0.0, inside) << "trial " << trial;
        // Exact distance of a point to the unit cube.
        const Vec3 q{std::clamp(x.x, 0.0, 1.0), std::clamp(x.y, 0.0, 1.0),
                     std::clamp(x.z, 0.0, 1.0)};
        const double outside = distance(x, q);
        const double depth = std::min({x.x, x.y, x.z, 1 - x.x, 1 - x.y, 1 - x.z});
        ASSERT_NEAR(std::abs(p.distance), inside ? depth : outside, sum_rounding);
    }
}

}  // namespace
}  // namespace slc
