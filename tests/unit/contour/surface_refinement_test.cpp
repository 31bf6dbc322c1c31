// refine_surface on surfaces made by hand: what the stage decides where the contour of a grid
// would not reach.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "slc/geometry/validate_surface.hpp"
#include "surface_stages.hpp"

namespace slc {
namespace {

/// The signed distance of the cube [−½, ½]³.
double cube_distance(Vec3 x) {
    const Vec3 q{std::abs(x.x) - 0.5, std::abs(x.y) - 0.5, std::abs(x.z) - 0.5};
    const Vec3 outside{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
    return norm(outside) + std::min(std::max({q.x, q.y, q.z}), 0.0);
}

/// The cube with each corner cut off by a triangle through the points at distance `cut` from it
/// along its three edges; each face an octagon, fanned into triangles. Every vertex lies on the
/// cube's edges and every edge in one of its faces, so G is 0 at every vertex and midpoint; only
/// the corner triangles' centroids lie inside, at cut/3 from the faces.
Surface chamfered_cube(double cut) {
    Surface s;
    auto corner_points = [&](int sx, int sy, int sz) {
        const Vec3 c{0.5 * sx, 0.5 * sy, 0.5 * sz};
        const std::uint32_t first = static_cast<std::uint32_t>(s.vertices.size());
        s.vertices.push_back(c - Vec3{cut * sx, 0.0, 0.0});
        s.vertices.push_back(c - Vec3{0.0, cut * sy, 0.0});
        s.vertices.push_back(c - Vec3{0.0, 0.0, cut * sz});
        return first;
    };
    auto add_facing = [&](TriangleIndices t, Vec3 outward) {
        const Vec3 a = s.vertices[t[0]];
        if (dot(cross(s.vertices[t[1]] - a, s.vertices[t[2]] - a), outward) < 0.0)
            std::swap(t[1], t[2]);
        s.triangles.push_back(t);
    };
    for (int sx : {-1, 1})
        for (int sy : {-1, 1})
            for (int sz : {-1, 1}) {
                const std::uint32_t v = corner_points(sx, sy, sz);
                add_facing({v, v + 1, v + 2}, Vec3{1.0 * sx, 1.0 * sy, 1.0 * sz});
            }
    for (int axis = 0; axis < 3; ++axis) {
        for (int side : {-1, 1}) {
            // The face's octagon: its points in order of angle about the face's centre.
            std::vector<std::uint32_t> ring;
            for (std::uint32_t v = 0; v < s.vertices.size(); ++v) {
                const double coordinate = axis == 0   ? s.vertices[v].x
                                          : axis == 1 ? s.vertices[v].y
                                                      : s.vertices[v].z;
                if (coordinate == 0.5 * side) ring.push_back(v);
            }
            auto angle = [&](std::uint32_t v) {
                const Vec3 p = s.vertices[v];
                return axis == 0   ? std::atan2(p.z, p.y)
                       : axis == 1 ? std::atan2(p.x, p.z)
                                   : std::atan2(p.y, p.x);
            };
            std::sort(ring.begin(), ring.end(),
                      [&](std::uint32_t a, std::uint32_t b) { return angle(a) < angle(b); });
            Vec3 outward{};
            (axis == 0 ? outward.x : axis == 1 ? outward.y : outward.z) = side;
            for (std::size_t k = 1; k + 1 < ring.size(); ++k)
                add_facing({ring[0], ring[k], ring[k + 1]}, outward);
        }
    }
    return s;
}

TEST(SurfaceRefinement, ACentroidTheMidpointsCannotSeeIsEvaluated) {
    // Every vertex and midpoint of the chamfered cube is a root, so a rule that judged triangles
    // by their midpoints (or a quadratic through them) would call it converged; the corner
    // triangles' centroids lie cut/3 inside, and the first pass finds that and splits each corner
    // triangle's longest edge (or refuses to).
    const double cut = 0.15;
    Surface s = chamfered_cube(cut);
    ASSERT_TRUE(prepare_surface(s).notes.empty());
    ASSERT_EQ(euler_characteristic(s), 2);
    const auto cube = [](std::span<const Vec3> x, std::span<double> v) {
        for (std::size_t i = 0; i < x.size(); ++i) v[i] = cube_distance(x[i]);
    };
    std::size_t count = 0;
    const contouring::SpaceEvaluator g(cube, count);
    const contouring::SurfaceRefinement r =
        contouring::refine_surface(s, g, 0.01, {}, 1, 1, 1'000'000, false);
    EXPECT_NEAR(r.residual, cut / 3.0, 1e-12);
    EXPECT_EQ(r.converged, 0u);
    EXPECT_GE(r.splits + r.rejected, 8u);  // each corner's longest edge, split or refused
    EXPECT_TRUE(prepare_surface(s).notes.empty());
    EXPECT_EQ(euler_characteristic(s), 2);
}

}  // namespace
}  // namespace slc
