// Tests of surface validation: each kind of bad input refused with a message naming it, the
// self-intersection search against all pairs, and the orientation of nested components.
#include "slc/geometry/validate_surface.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "slc/core/error.hpp"
#include "slc/geometry/predicates.hpp"
#include "slc/geometry/surface_shapes.hpp"

namespace slc {
namespace {

/// The message prepare_surface throws for s, or "" if it accepts s.
std::string refusal(const Surface& s) {
    try {
        prepare_surface(s);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

Surface tetrahedron(Vec3 o) {
    Surface s;
    s.vertices = {o, o + Vec3{1, 0, 0}, o + Vec3{0, 1, 0}, o + Vec3{0, 0, 1}};
    s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return s;
}

TEST(PrepareSurface, AcceptsATetrahedron) {
    const PreparedSurface p = prepare_surface(tetrahedron({0, 0, 0}));
    EXPECT_TRUE(p.notes.empty());
    EXPECT_NEAR(volume(p.surface), 1.0 / 6.0, 1e-15);
}

TEST(PrepareSurface, RefusesEmptyAndBadCoordinatesAndIndices) {
    EXPECT_EQ(refusal(Surface{}), "surface has no triangles");
    Surface s = tetrahedron({0, 0, 0});
    s.vertices[2].y = NAN;
    EXPECT_EQ(refusal(s), "vertex 2 has a non-finite coordinate");
    s = tetrahedron({0, 0, 0});
    s.triangles[3][1] = 7;
    EXPECT_EQ(refusal(s), "triangle 3 refers to vertex 7, but there are 4");
}

TEST(PrepareSurface, RefusesDegenerateTriangles) {
    Surface s = tetrahedron({0, 0, 0});
    s.triangles[1] = {0, 1, 1};
    EXPECT_EQ(refusal(s), "triangle 1 is degenerate (zero area)");
    // A corner on the opposite edge: zero area with distinct corners.
    s = tetrahedron({0, 0, 0});
    s.vertices[3] = {0.5, 0.5, 0.0};
    EXPECT_NE(refusal(s).find("degenerate"), std::string::npos);
}

TEST(PrepareSurface, RefusesOpenNonManifoldAndInconsistentEdges) {
    Surface s = tetrahedron({0, 0, 0});
    s.triangles.pop_back();
    EXPECT_NE(refusal(s).find("open edge"), std::string::npos) << refusal(s);
    s = tetrahedron({0, 0, 0});
    std::swap(s.triangles[2][0], s.triangles[2][1]);
    EXPECT_NE(refusal(s).find("oriented inconsistently"), std::string::npos) << refusal(s);
    // A second tetrahedron hinged on edge (0, 1) of the first: four triangles on that edge.
    s = tetrahedron({0, 0, 0});
    s.vertices.push_back({0, -1, 0});
    s.vertices.push_back({0, 0, -1});
    for (TriangleIndices t : {TriangleIndices{0, 4, 1}, {0, 1, 5}, {0, 5, 4}, {1, 4, 5}})
        s.triangles.push_back(t);
    EXPECT_NE(refusal(s).find("non-manifold"), std::string::npos) << refusal(s);
}

TEST(PrepareSurface, RefusesANonManifoldVertex) {
    // Two tetrahedra touching at one corner: every edge is fine, the vertex is not.
    Surface a = tetrahedron({0, 0, 0});
    Surface b;
    b.vertices = {{0, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
    b.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    Surface s = join({a, b});
    // Make the touching corner one vertex.
    for (TriangleIndices& t : s.triangles)
        for (std::uint32_t& v : t)
            if (v == 4) v = 0;
    EXPECT_EQ(refusal(s),
              "vertex 0 is non-manifold: its 6 triangles do not form a single fan (triangle 0 is "
              "in one)");
}

TEST(PrepareSurface, RefusesIntersectingSpheresNamingTheTriangles) {
    const Surface s = join({sphere({0, 0, 0}, 1, 2), sphere({1.5, 0, 0}, 1, 2)});
    const std::string message = refusal(s);
    EXPECT_EQ(message.rfind("triangles ", 0), 0u) << message;
    EXPECT_NE(message.find(" intersect"), std::string::npos) << message;
    // Apart, they are fine; touching at a point is not.
    EXPECT_EQ(refusal(join({sphere({0, 0, 0}, 1, 2), sphere({2.5, 0, 0}, 1, 2)})), "");
    EXPECT_NE(
        refusal(join({box_surface({0, 0, 0}, {1, 1, 1}, 1), box_surface({1, 1, 1}, {2, 2, 2}, 1)})),
        "");
}

/// For each triangle i, the least j > i it meets among the pairs with a triangle flagged, by
/// testing every pair; sets *fan_met when two that share a corner meet.
std::vector<TriangleContact> contacts_of_all_pairs(const Surface& s,
                                                   const std::vector<std::uint8_t>& flags,
                                                   bool* fan_met) {
    std::vector<TriangleContact> want;
    for (std::uint32_t i = 0; i < s.size(); ++i) {
        for (std::uint32_t j = i + 1; j < s.size(); ++j) {
            if (!flags[i] && !flags[j]) continue;
            // Shared corners first, as triangles_overlap expects.
            TriangleIndices p = s.triangles[i], q = s.triangles[j];
            int shared = 0;
            for (int a = 0; a < 3; ++a)
                for (int b = shared; b < 3; ++b)
                    if (p[a] == q[b]) {
                        std::swap(p[shared], p[a]);
                        std::swap(q[shared], q[b]);
                        ++shared;
                        break;
                    }
            const Triangle3 ta{s.vertices[p[0]], s.vertices[p[1]], s.vertices[p[2]]};
            const Triangle3 tb{s.vertices[q[0]], s.vertices[q[1]], s.vertices[q[2]]};
            if (triangles_overlap(ta, tb, shared)) {
                want.push_back({i, j});
                *fan_met = *fan_met || shared > 0;
                break;
            }
        }
    }
    return want;
}

TEST(FindSelfIntersection, FindsAFanThatWindsTwice) {
    // Ten triangles around one vertex, each turning 72° about z and facing up, so that seen
    // from above each is positively oriented, but twice round: triangles j and j + 5 lie over
    // the same sector, and where their heights swap they cross.
    Surface s;
    s.vertices.push_back({0, 0, 0});
    const double z[10] = {0.3, -0.3, 0.2, -0.1, 0.25, -0.3, 0.3, -0.2, 0.1, -0.25};
    for (int j = 0; j < 10; ++j) {
        const double angle = 4.0 * std::acos(-1.0) * j / 10.0;
        s.vertices.push_back({std::cos(angle), std::sin(angle), z[j]});
    }
    for (std::uint32_t j = 0; j < 10; ++j) s.triangles.push_back({0, 1 + j, 1 + (j + 1) % 10});
    const std::vector<std::uint8_t> all(s.size(), 1);
    bool fan_met = false;
    const std::vector<TriangleContact> want = contacts_of_all_pairs(s, all, &fan_met);
    ASSERT_TRUE(fan_met);
    const std::vector<TriangleContact> got = find_self_intersections(s, all);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
        EXPECT_EQ(got[k].first, want[k].first);
        EXPECT_EQ(got[k].second, want[k].second);
    }
}

TEST(FindSelfIntersection, AgreesWithAllPairsOnJitteredSpheres) {
    // Every contact, not only the first: for each triangle the least later one it meets. The
    // seeds include folds of a vertex's fan, where triangles sharing a corner meet, beside fans
    // that the search settles without testing their pairs (a fan that is one sheet along its
    // normal) and, with the smaller jitter, folds that only just cross.
    int folded_fans = 0;
    for (unsigned seed = 1; seed <= 80; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        std::mt19937 rng(seed);
        Surface s = sphere({0, 0, 0}, 1, 2);
        // Large jitter of a few vertices folds the surface through itself, sometimes.
        std::normal_distribution<double> jitter(0.0, seed <= 40 ? 0.5 : 0.15);
        std::uniform_int_distribution<std::size_t> pick(0, s.vertices.size() - 1);
        for (int k = 0; k < 3; ++k)
            s.vertices[pick(rng)] += Vec3{jitter(rng), jitter(rng), jitter(rng)};
        bool degenerate = false;
        for (std::size_t t = 0; t < s.size(); ++t) degenerate |= is_degenerate(s.triangle(t));
        if (degenerate) continue;
        // For each triangle i, the least j > i it meets among the pairs with a triangle flagged
        // (all, a random third, three quarters: a search for each triangle below half, the
        // hierarchy against itself above), by testing every pair.
        std::vector<std::uint8_t> all(s.size(), 1), some(s.size(), 0), most(s.size(), 0);
        std::bernoulli_distribution third(1.0 / 3.0), three_quarters(0.75);
        for (auto& f : some) f = third(rng) ? 1 : 0;
        for (auto& f : most) f = three_quarters(rng) ? 1 : 0;
        bool fan_met = false;
        for (const auto* flags : {&all, &some, &most}) {
            const std::vector<TriangleContact> want = contacts_of_all_pairs(s, *flags, &fan_met);
            const std::vector<TriangleContact> got = find_self_intersections(s, *flags);
            ASSERT_EQ(got.size(), want.size());
            for (std::size_t k = 0; k < got.size(); ++k) {
                EXPECT_EQ(got[k].first, want[k].first);
                EXPECT_EQ(got[k].second, want[k].second);
            }
            const auto first =
                flags == &all ? find_self_intersection(s) : find_self_intersection(s, *flags);
            ASSERT_EQ(first.has_value(), !want.empty());
            if (first) {
                EXPECT_EQ(first->first, want.front().first);
                EXPECT_EQ(first->second, want.front().second);
            }
        }
        folded_fans += fan_met ? 1 : 0;
    }
    EXPECT_GE(folded_fans, 8);
}

TEST(PrepareSurface, OrientsNestedComponentsOutwardAndCavitiesInward) {
    Surface inward = sphere({0, 0, 0}, 1, 1);
    for (TriangleIndices& t : inward.triangles) std::swap(t[1], t[2]);
    PreparedSurface p = prepare_surface(inward);
    ASSERT_EQ(p.notes.size(), 1u);
    EXPECT_EQ(p.notes[0], "the surface was oriented inward; reversed its triangles");
    EXPECT_GT(volume(p.surface), 0.0);
    // A hollow ball: the inner sphere must point inward (into the cavity).
    const Surface hollow = join({sphere({0, 0, 0}, 2, 2), sphere({0, 0, 0}, 1, 2)});
    p = prepare_surface(hollow);
    ASSERT_EQ(p.notes.size(), 1u);
    EXPECT_NE(p.notes[0].find("component 1"), std::string::npos) << p.notes[0];
    const double shell = 4.0 / 3.0 * 3.141592653589793 * (8 - 1);
    EXPECT_NEAR(volume(p.surface), shell, 0.1 * shell);
    EXPECT_TRUE(prepare_surface(p.surface).notes.empty());
}

// Slabs 1e-17 and 1e-30 thick, and a tetrahedron 1e-120 wide whose triple products underflow
// (its floating-point volume is 0): the orientation is decided exactly, the same by the filter
// and by the exact sum, and an inward copy is reversed back.
TEST(PrepareSurface, DecidesTheOrientationOfThinAndTinySurfacesExactly) {
    Surface tiny = tetrahedron({0, 0, 0});
    for (Vec3& p : tiny.vertices) p = 1e-120 * p;
    EXPECT_EQ(volume(tiny), 0.0);  // underflowed
    for (Surface s : {box_surface({-0.3, -0.7, 0.0}, {0.9, 0.4, 1e-17}, 2),
                      box_surface({0.1, 0.2, 0.0}, {1.3, 1.1, 1e-30}, 3), tiny}) {
        EXPECT_EQ(volume_sign(s), 1);
        EXPECT_EQ(exact_volume_sign(s.vertices, s.triangles), 1);
        EXPECT_TRUE(prepare_surface(s).notes.empty());
        for (TriangleIndices& t : s.triangles) std::swap(t[1], t[2]);
        EXPECT_EQ(volume_sign(s), -1);
        EXPECT_EQ(exact_volume_sign(s.vertices, s.triangles), -1);
        const PreparedSurface p = prepare_surface(s);
        ASSERT_EQ(p.notes.size(), 1u);
        EXPECT_EQ(volume_sign(p.surface), 1);
    }
}

}  // namespace
}  // namespace slc
