// Tests of the triangle hierarchy against scans of every triangle: the nearest-triangle search
// (the same triangle and distance, to the bit, wherever the point is: deep inside closed
// surfaces, far from tilted flat faces and right at them) and the pairs of triangles
// whose boxes meet (each once, on one thread or two).
#include "slc/geometry/triangle_hierarchy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "slc/core/parallel.hpp"
#include "slc/geometry/surface_shapes.hpp"

namespace slc {
namespace {

std::vector<Triangle3> corners_of(const Surface& s) {
    std::vector<Triangle3> out;
    for (std::size_t t = 0; t < s.size(); ++t) out.push_back(s.triangle(t));
    return out;
}

NearestFacet scan(std::span<const Triangle3> triangles, Vec3 x) {
    NearestFacet best;
    for (std::size_t t = 0; t < triangles.size(); ++t)
        best.offer(static_cast<std::uint32_t>(t), closest_point(triangles[t], x));
    return best;
}

TEST(TriangleHierarchy, NearestIsTheScansEverywhereAndDeepInsideClosedSurfaces) {
    // Deep inside a closed surface every patch's box reaches towards the point, so boxes alone
    // prune almost nothing there; the slabs across the patches' normals must prune without
    // losing the nearest triangle or a tie's least index (the centre of the sphere ties every
    // triangle to rounding).
    const Vec3 centre{0.03, -0.02, 0.01};
    struct Case {
        std::string name;
        Surface surface;
        std::vector<Vec3> deep;  // points far inside
    };
    std::vector<Case> cases{
        {"sphere", sphere(centre, 0.6, 5), {centre}},
        {"torus", torus({}, 0.6, 0.25, 96, 32), {}},
        {"box", box_surface({-0.5, -0.4, -0.3}, {0.6, 0.5, 0.4}, 6), {}},
    };
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0), angle(0.0, 6.283185307179586);
    for (int k = 0; k < 200; ++k) {
        cases[0].deep.push_back(centre + 0.1 * Vec3{u(rng), u(rng), u(rng)});
        const double a = angle(rng);  // near the torus's core circle
        cases[1].deep.push_back(Vec3{0.6 * std::cos(a), 0.6 * std::sin(a), 0.0} +
                                0.05 * Vec3{u(rng), u(rng), u(rng)});
        cases[2].deep.push_back(Vec3{0.05, 0.05, 0.05} + 0.2 * Vec3{u(rng), u(rng), u(rng)});
    }
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const std::vector<Triangle3> triangles = corners_of(c.surface);
        const TriangleHierarchy boxes(triangles);
        const TriangleHierarchy slabs(triangles, TriangleHierarchy::Bounds::boxes_and_slabs);
        std::vector<Vec3> points = c.deep;
        for (int k = 0; k < 300; ++k) points.push_back(1.5 * Vec3{u(rng), u(rng), u(rng)});
        for (const Vec3 x : points) {
            const NearestFacet slow = scan(triangles, x);
            for (const TriangleHierarchy* h : {&boxes, &slabs}) {
                NearestFacet fast;
                h->nearest(triangles, x, fast);
                ASSERT_EQ(fast.triangle, slow.triangle) << x.x << " " << x.y << " " << x.z;
                ASSERT_EQ(fast.distance2, slow.distance2);
            }
        }
    }
}

TEST(TriangleHierarchy, NearestIsTheScansBesideAndFarFromTiltedFlatFaces) {
    // A flat face turned off the axes: its patches' boxes reach towards a point seen from afar,
    // and the bound from each node's box and slab together prunes them. It must still keep the
    // nearest triangle and a tie's least index: points far off and right at the faces, on
    // edges and corners (ties), and a hair's breadth off them on both sides.
    Surface s = box_surface({-0.5, -0.4, -0.3}, {0.6, 0.5, 0.4}, 8);
    const double c = std::cos(0.7), d = std::sin(0.7), e = std::cos(0.4), f = std::sin(0.4);
    for (Vec3& v : s.vertices) {
        v = Vec3{c * v.x - d * v.y, d * v.x + c * v.y, v.z};
        v = Vec3{v.x, e * v.y - f * v.z, f * v.y + e * v.z};
    }
    const std::vector<Triangle3> triangles = corners_of(s);
    const TriangleHierarchy slabs(triangles, TriangleHierarchy::Bounds::boxes_and_slabs);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.0, 1.0);
    std::vector<Vec3> points;
    for (int k = 0; k < 300; ++k) {
        const Vec3 dir{u(rng), u(rng), u(rng)};
        points.push_back((2.0 + 30.0 * w(rng)) * dir);  // far off
    }
    for (std::size_t t = 0; t < triangles.size(); t += 7) {
        const Triangle3& tri = triangles[t];
        const Vec3 n = cross(tri.b - tri.a, tri.c - tri.a);
        const Vec3 unit_n = (1.0 / norm(n)) * n;
        const double a = w(rng), b = w(rng) * (1.0 - a);
        const Vec3 on = tri.a + a * (tri.b - tri.a) + b * (tri.c - tri.a);
        for (const Vec3 x : {on, tri.a, 0.5 * (tri.a + tri.b)})
            for (const double h : {0.0, 1e-13, -1e-13, 1e-9, -1e-9, 0.3, -0.2})
                points.push_back(x + h * unit_n);
    }
    for (const Vec3 x : points) {
        const NearestFacet slow = scan(triangles, x);
        NearestFacet fast;
        slabs.nearest(triangles, x, fast);
        ASSERT_EQ(fast.triangle, slow.triangle) << x.x << " " << x.y << " " << x.z;
        ASSERT_EQ(fast.distance2, slow.distance2);
    }
}

TEST(TriangleHierarchy, OverlappingPairsAreTheScansEachOnce) {
    // A surface (boxes meeting their neighbours'), the same with triangles scattered among it,
    // and a heap of triangles in one spot (boxes meeting nearly all).
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto scattered = [&](std::vector<Triangle3> ts, int count, double size) {
        for (int k = 0; k < count; ++k) {
            const Vec3 c{u(rng), u(rng), u(rng)};
            ts.push_back({c, c + size * Vec3{u(rng), u(rng), u(rng)},
                          c + size * Vec3{u(rng), u(rng), u(rng)}});
        }
        return ts;
    };
    const std::vector<Triangle3> sphere_triangles = corners_of(sphere({0.1, 0, 0}, 0.8, 3));
    for (const auto& triangles :
         {sphere_triangles, scattered(sphere_triangles, 300, 0.3), scattered({}, 200, 0.02)}) {
        std::vector<std::pair<std::uint32_t, std::uint32_t>> want;
        for (std::uint32_t i = 0; i < triangles.size(); ++i)
            for (std::uint32_t j = i + 1; j < triangles.size(); ++j)
                if (bounding_box(triangles[i]).overlaps(bounding_box(triangles[j])))
                    want.emplace_back(i, j);
        const TriangleHierarchy h(triangles);
        for (int threads : {1, 2}) {
            set_thread_count(threads);
            std::mutex m;
            std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
            h.for_each_overlapping_pair([&](std::uint32_t a, std::uint32_t b) {
                const std::lock_guard lock(m);
                got.emplace_back(std::min(a, b), std::max(a, b));
            });
            std::sort(got.begin(), got.end());
            EXPECT_EQ(got, want) << threads << " threads, " << triangles.size() << " triangles";
        }
        set_thread_count(0);
    }
}

}  // namespace
}  // namespace slc
