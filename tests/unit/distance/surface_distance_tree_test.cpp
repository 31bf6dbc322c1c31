// Tests of the surface distance tree against brute force and against orientation-free oracles
// (the winding number; the exact distance to a box), of its splitting rule, and of the
// nearest-point extension.
#include "slc/distance/surface_distance_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/surface_extension.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/geometry/validate_surface.hpp"

namespace slc {
namespace {

/// Relative agreement of two computations of one distance by the same kernel on possibly
/// different (equally near) triangles: a few roundings of O(1) quantities.
constexpr double rounding = 1e-12;

struct Case {
    std::string name;
    Surface surface;
};

std::vector<Case> cases() {
    return {
        {"box", box_surface({-0.6, -0.4, -0.5}, {0.5, 0.7, 0.3}, 1)},
        {"slab", box_surface({-0.8, -0.8, -0.005}, {0.8, 0.8, 0.005}, 3)},
        {"two spheres", join({sphere({-0.5, 0, 0}, 0.4, 3), sphere({0.45, 0.1, 0.05}, 0.5, 2)})},
        {"torus", torus({0.05, 0, 0}, 0.8, 0.25, 40, 16)},
        {"Enright sphere", enright_sphere(3)},
    };
}

/// Query points of every kind: uniform in and beyond the domain, near and on vertices, edges and
/// faces, and far away.
std::vector<Vec3> query_points(const Surface& s, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.5, 1.5), far(-40.0, 40.0), t01(0.0, 1.0);
    std::normal_distribution<double> tiny(0.0, 1e-7), small(0.0, 1e-2);
    std::uniform_int_distribution<std::size_t> triangle(0, s.size() - 1);
    std::vector<Vec3> xs;
    for (int k = 0; k < 400; ++k) xs.push_back({u(rng), u(rng), u(rng)});
    for (int k = 0; k < 20; ++k) xs.push_back({far(rng), far(rng), far(rng)});
    for (int k = 0; k < 150; ++k) {
        const Triangle3 t = s.triangle(triangle(rng));
        const double a = t01(rng), b = t01(rng) * (1 - a);
        const Vec3 on_face = t.a + a * (t.b - t.a) + b * (t.c - t.a);
        const Vec3 on_edge = t.a + a * (t.b - t.a);
        xs.push_back(t.a);
        xs.push_back(t.a + Vec3{tiny(rng), tiny(rng), tiny(rng)});
        xs.push_back(on_edge + Vec3{tiny(rng), tiny(rng), tiny(rng)});
        xs.push_back(on_face);
        xs.push_back(on_face + Vec3{small(rng), small(rng), small(rng)});
    }
    return xs;
}

TEST(SurfaceDistanceTree, AgreesWithBruteForceOnSeveralSurfaces) {
    const Box3 domain = Box3::centered_cube(1.2);
    for (const Case& c : cases()) {
        const Surface s = prepare_surface(c.surface).surface;
        const PseudoNormals normals = pseudo_normals(s);
        for (const int depth : {2, 4, 6}) {
            SCOPED_TRACE(c.name + ", depth " + std::to_string(depth));
            const SurfaceDistanceTree tree(s, domain, {.depth = depth});
            std::mt19937 rng(static_cast<unsigned>(depth));
            double worst = 0.0;
            for (const Vec3 x : query_points(s, rng)) {
                const SurfacePoint fast = tree.closest_point(x);
                const SurfacePoint slow = closest_point_brute_force(s, normals, x);
                const double scale = std::max(1.0, std::abs(slow.distance));
                worst = std::max(worst, std::abs(fast.distance - slow.distance) / scale);
                ASSERT_NEAR(fast.distance, slow.distance, rounding * scale)
                    << "at (" << x.x << ", " << x.y << ", " << x.z << ")";
                ASSERT_LT(distance(fast.point, slow.point), 1e-9 * scale);
                // The nearest point lies at the distance found.
                ASSERT_NEAR(distance(x, fast.point), std::abs(fast.distance), rounding * scale);
            }
            std::ostringstream worst_text;
            worst_text << worst;
            RecordProperty(c.name + " depth " + std::to_string(depth) + " worst relative gap",
                           worst_text.str());
        }
    }
}

TEST(SurfaceDistanceTree, SignAgreesWithTheWindingNumber) {
    const Box3 domain = Box3::centered_cube(1.2);
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const Surface s = prepare_surface(c.surface).surface;
        const SurfaceDistanceTree tree(s, domain, {.depth = 5});
        std::mt19937 rng(17);
        for (const Vec3 x : query_points(s, rng)) {
            const double f = tree.closest_point(x).distance;
            // The winding number is ±1 or 0 away from the surface; on it, either sign is right.
            if (std::abs(f) < 1e-9) continue;
            ASSERT_EQ(f<0.0, winding_number(s, x)> 0.5)
                << "at (" << x.x << ", " << x.y << ", " << x.z << ")";
        }
    }
}

TEST(SurfaceDistanceTree, ExactOnABoxNearItsEdgesAndCorners) {
    const Vec3 lo{-0.5, -0.3, -0.2}, hi{0.4, 0.6, 0.25};
    const Surface s = box_surface(lo, hi, 2);
    const SurfaceDistanceTree tree(s, Box3::centered_cube(1.0), {.depth = 6});
    std::mt19937 rng(23);
    std::normal_distribution<double> jitter(0.0, 1e-4);
    std::uniform_real_distribution<double> t01(0.0, 1.0);
    for (int k = 0; k < 20000; ++k) {
        // A corner of the box, or a point along one of its edges, jittered.
        Vec3 x{(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z};
        const int along = (k >> 3) % 4;  // 3: a corner
        if (along == 0) x.x = lo.x + t01(rng) * (hi.x - lo.x);
        if (along == 1) x.y = lo.y + t01(rng) * (hi.y - lo.y);
        if (along == 2) x.z = lo.z + t01(rng) * (hi.z - lo.z);
        x += Vec3{jitter(rng), jitter(rng), jitter(rng)};
        const Vec3 q{std::clamp(x.x, lo.x, hi.x), std::clamp(x.y, lo.y, hi.y),
                     std::clamp(x.z, lo.z, hi.z)};
        const bool inside = q == x;
        const double depth =
            std::min({x.x - lo.x, x.y - lo.y, x.z - lo.z, hi.x - x.x, hi.y - x.y, hi.z - x.z});
        const double want = inside ? -depth : distance(x, q);
        const SurfacePoint p = tree.closest_point(x);
        ASSERT_NEAR(p.distance, want, rounding) << "k " << k;
        if (std::abs(want) > 1e-12) {
            ASSERT_EQ(p.distance < 0.0, inside) << "k " << k;
        }
    }
}

TEST(SurfaceDistanceTree, LeavesAboveTheDeepestLevelAreFartherThanTheirEdge) {
    const Surface s = torus({0, 0, 0}, 0.7, 0.2, 24, 10);
    const PseudoNormals normals = pseudo_normals(s);
    const SurfaceDistanceTree tree(s, Box3::centered_cube(1.0), {.depth = 5});
    const Octree& t = tree.tree();
    int checked = 0;
    for (std::uint32_t c : t.leaves()) {
        const int level = t.cell(c).level;
        if (level == t.max_depth()) continue;
        // Unsplit: every listed triangle's lower bound is at least the edge h, so it is at
        // least h (1 + √3/2) from the centre; an unlisted one misses the triple, so it is more
        // than 1.5 h away. Either way the cell is farther than h from the surface (§1.3).
        const double h = t.edge(level);
        const double d =
            std::abs(closest_point_brute_force(s, normals, t.box(c).center()).distance);
        ASSERT_GE(d, 1.5 * h * (1 - rounding));
        ++checked;
    }
    EXPECT_GT(checked, 100);
    // And every cell's list is exactly the triangles whose boxes meet its triple, grown by the
    // tree's slack of 1e-12 of an edge against rounding; cells keep lists of at most 48 (the
    // longest a query scans), the others none.
    int unlisted = 0;
    for (std::size_t c = 0; c < t.size(); c += 7) {
        std::vector<std::uint32_t> want;
        const Box3 triple = t.triple(c).inflated(1e-12 * t.edge(t.cell(c).level));
        for (std::uint32_t k = 0; k < s.size(); ++k)
            if (bounding_box(s.triangle(k)).overlaps(triple)) want.push_back(k);
        const auto got = tree.cell_triangles(c);
        ASSERT_EQ(tree.is_listed(c), want.size() <= 48) << "cell " << c;
        if (!tree.is_listed(c)) {
            EXPECT_TRUE(got.empty()) << "cell " << c;
            ++unlisted;
            continue;
        }
        ASSERT_TRUE(std::equal(got.begin(), got.end(), want.begin(), want.end())) << "cell " << c;
    }
    EXPECT_GT(unlisted, 0);
}

TEST(SurfaceDistanceTree, CellsAndListsDoNotDependOnThreadCount) {
    // 20480 triangles at depth 7: every stage of the build (coarse cells, the binned level, the
    // filtered levels) has enough work for every worker thread.
    const Surface s = sphere({0.01, -0.02, 0.03}, 0.6, 5);
    set_thread_count(1);
    const SurfaceDistanceTree one(s, Box3::centered_cube(1.0), {.depth = 7});
    set_thread_count(2);
    const SurfaceDistanceTree two(s, Box3::centered_cube(1.0), {.depth = 7});
    set_thread_count(0);
    ASSERT_EQ(one.tree().size(), two.tree().size());
    for (std::size_t c = 0; c < one.tree().size(); ++c) {
        ASSERT_EQ(one.tree().cell(c).first_child, two.tree().cell(c).first_child) << "cell " << c;
        ASSERT_EQ(one.is_listed(c), two.is_listed(c)) << "cell " << c;
        const auto a = one.cell_triangles(c), b = two.cell_triangles(c);
        ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "cell " << c;
    }
}

TEST(SurfaceDistanceTree, BalancedTreeListsItsNewCellsAndAgreesWithBruteForce) {
    // The split rule grades the tree by itself almost everywhere; around this box's edges and
    // corners at depth 6 it does not.
    const Surface s = prepare_surface(box_surface({-0.6, -0.4, -0.5}, {0.5, 0.7, 0.3}, 1)).surface;
    const PseudoNormals normals = pseudo_normals(s);
    const Box3 domain = Box3::centered_cube(1.2);
    const SurfaceDistanceTree plain(s, domain, {.depth = 6});
    const SurfaceDistanceTree tree(s, domain, {.depth = 6, .balanced = true});
    const Octree& t = tree.tree();
    ASSERT_FALSE(plain.tree().is_balanced());  // so that balancing had work to do
    EXPECT_TRUE(t.is_balanced());
    EXPECT_GT(t.size(), plain.tree().size());
    // The cells balancing made keep lists as the others do.
    for (std::size_t c = plain.tree().size(); c < t.size(); ++c) {
        std::vector<std::uint32_t> want;
        const Box3 triple = t.triple(c).inflated(1e-12 * t.edge(t.cell(c).level));
        for (std::uint32_t k = 0; k < s.size(); ++k)
            if (bounding_box(s.triangle(k)).overlaps(triple)) want.push_back(k);
        ASSERT_EQ(tree.is_listed(c), want.size() <= 48) << "cell " << c;
        const auto got = tree.cell_triangles(c);
        if (!tree.is_listed(c)) continue;
        ASSERT_TRUE(std::equal(got.begin(), got.end(), want.begin(), want.end())) << "cell " << c;
    }
    std::mt19937 rng(29);
    for (const Vec3 x : query_points(s, rng)) {
        const SurfacePoint fast = tree.closest_point(x);
        const SurfacePoint slow = closest_point_brute_force(s, normals, x);
        ASSERT_NEAR(fast.distance, slow.distance, rounding * std::max(1.0, std::abs(slow.distance)))
            << "at (" << x.x << ", " << x.y << ", " << x.z << ")";
    }
}

TEST(SurfaceDistanceTree, RefusesEmptySurfacesAndBadDomains) {
    EXPECT_THROW(SurfaceDistanceTree(Surface{}, Box3::centered_cube(1), {}), InvalidInput);
    const Surface s = sphere({0, 0, 0}, 0.5, 1);
    EXPECT_THROW(SurfaceDistanceTree(s, Box3{{0, 0, 0}, {1, 1, 2}}, {}), InvalidInput);
    EXPECT_THROW(SurfaceDistanceTree(s, Box3::centered_cube(1), {.depth = 40}), InvalidInput);
    // Cells four to eight mean edges wide: 4 mean edge < h <= 8 mean edge; never above level 2.
    EXPECT_EQ(SurfaceDistanceTree::default_depth(s, Box3::centered_cube(1)), 2);
    for (const int level : {2, 3, 5, 6}) {
        const Surface fine = sphere({0, 0, 0}, 0.5, level);
        double total = 0.0;
        for (std::size_t t = 0; t < fine.size(); ++t) {
            const Triangle3 tri = fine.triangle(t);
            total += distance(tri.a, tri.b) + distance(tri.b, tri.c) + distance(tri.c, tri.a);
        }
        const double mean = total / (3.0 * static_cast<double>(fine.size()));
        const int depth = SurfaceDistanceTree::default_depth(fine, Box3::centered_cube(1));
        const double h = std::ldexp(2.0, -depth);
        if (depth > 2) {  // level 2 is the floor
            EXPECT_LT(4 * mean, h);
        }
        EXPECT_LE(h, 8 * mean);
    }
}

TEST(SurfaceExtension, InterpolatesVertexValuesAtTheNearestPoint) {
    const Surface s = torus({0, 0, 0}, 0.7, 0.2, 24, 10);
    const SurfaceDistanceTree tree(s, Box3::centered_cube(1.0), {.depth = 5});
    // A linear function of position is reproduced at the nearest point exactly (to rounding),
    // since the nearest point is a barycentric combination of corners.
    std::vector<double> values;
    for (const Vec3 v : s.vertices) values.push_back(2 * v.x - v.y + 3 * v.z + 1);
    std::vector<Vec3> xs;
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < 2000; ++k) xs.push_back({u(rng), u(rng), u(rng)});
    const std::vector<double> w = nearest_point_extension<double>(tree, values, xs);
    for (std::size_t i = 0; i < xs.size(); ++i) {
        const Vec3 p = tree.closest_point(xs[i]).point;
        ASSERT_NEAR(w[i], 2 * p.x - p.y + 3 * p.z + 1, rounding);
    }
    EXPECT_THROW(nearest_point_extension<double>(tree, std::vector<double>(3, 0.0), xs),
                 InvalidInput);
}

}  // namespace
}  // namespace slc
