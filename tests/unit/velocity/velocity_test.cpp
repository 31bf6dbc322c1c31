// Tests of the velocity-law interface: adapters for a user's field, local and nonlocal laws, the
// geometry handed to a law, and the errors for a non-finite velocity, a wrong count, a missing
// distance tree and sampling a law that is not a field.
#include "slc/velocity/velocity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "slc/core/error.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry_modules/intrinsic.hpp"

namespace slc {
namespace {

const Interface& circle() {
    static const Interface curves({shapes::circle({0.1, 0.0}, 0.5, 40)});
    return curves;
}

TEST(FieldLaw, IsSampledAnywhereAndAtTheVertices) {
    const auto law = field_law("shear", [](double t, Vec2 x) { return Vec2{t * x.y, 0.0}; });
    EXPECT_TRUE(law->is_field());
    EXPECT_EQ(law->name(), "shear");
    const auto u = field_velocities(*law, 2.0, std::vector<Vec2>{{3.0, 0.5}});
    EXPECT_EQ(u[0], (Vec2{1.0, 0.0}));
    const auto v = vertex_velocities(*law, 2.0, circle());
    for (std::size_t i = 0; i < v.size(); ++i)
        EXPECT_EQ(v[i], (Vec2{2.0 * circle().point(i).y, 0.0}));
}

TEST(LocalLaw, SeesTheGeometryItAskedFor) {
    // A law that asks for curvature without naming a module gets the arclength module's (the
    // intrinsic one is unstable for curvature flow at small k/h²).
    const auto law =
        local_law("double-normal", {.normals = true, .curvature = true},
                  [](double, const VertexState& s) { return (2.0 - s.curvature) * s.normal; });
    const auto u = vertex_velocities(*law, 0.0, circle());
    const VertexGeometry g = arclength_geometry(circle(), 0.0);
    for (std::size_t i = 0; i < u.size(); ++i)
        EXPECT_EQ(u[i], (2.0 - g.curvature[i]) * g.normals[i]);
    EXPECT_FALSE(law->is_field());
    EXPECT_THROW(field_velocities(*law, 0.0, circle().points()), InvalidInput);
}

TEST(CurveLaw, SeesTheWholeCurve) {
    // A nonlocal law: every vertex moves towards the centroid of all vertices.
    const auto law =
        curve_law("to-centroid", {}, [](double, const Interface& curves, const VertexGeometry& g) {
            EXPECT_TRUE(g.normals.empty());
            Vec2 c;
            for (const Vec2 p : curves.points()) c += p / static_cast<double>(curves.size());
            std::vector<Vec2> u;
            for (const Vec2 p : curves.points()) u.push_back(c - p);
            return u;
        });
    const auto u = vertex_velocities(*law, 0.0, circle());
    EXPECT_NEAR(u[0].x, -0.5, 1e-12);
}

TEST(VertexVelocities, NamesTheLawTimeAndVertexOfANonFiniteVelocity) {
    const auto law = local_law("blows-up", {}, [](double, const VertexState& s) {
        return s.index == 3 ? Vec2{std::numeric_limits<double>::quiet_NaN(), 0.0} : Vec2{};
    });
    try {
        vertex_velocities(*law, 0.25, circle());
        FAIL() << "expected NumericalFailure";
    } catch (const NumericalFailure& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'blows-up'"), std::string::npos) << what;
        EXPECT_NE(what.find("t = 0.25"), std::string::npos) << what;
        EXPECT_NE(what.find("vertex 3"), std::string::npos) << what;
    }
    const auto field = field_law("infinite", [](double, Vec2) {
        return Vec2{0.0, std::numeric_limits<double>::infinity()};
    });
    EXPECT_THROW(field_velocities(*field, 1.0, std::vector<Vec2>{{0.0, 0.0}}), NumericalFailure);
}

TEST(VertexVelocities, RejectsAWrongNumberOfVelocities) {
    const auto law = curve_law("short", {}, [](double, const Interface&, const VertexGeometry&) {
        return std::vector<Vec2>(3);
    });
    EXPECT_THROW(vertex_velocities(*law, 0.0, circle()), InvalidInput);
}

TEST(VertexVelocities, EmbeddedGeometryNeedsATreeOfTheSameCurves) {
    const auto law =
        local_law("embedded-normal", {.normals = true, .module = GeometryModule::embedded},
                  [](double, const VertexState& s) { return s.normal; });
    EXPECT_THROW(vertex_velocities(*law, 0.0, circle()), InvalidInput);
    const Interface other({shapes::circle({}, 0.3, 30)});
    const DistanceTree other_tree(other, Box::centered_square(1.0),
                                  {.depth = 6, .triangulate = false});
    EXPECT_THROW(vertex_velocities(*law, 0.0, circle(), {.tree = &other_tree}), InvalidInput);
    // With a tree of the same curves: E = 3 at M = 64 on a 1000-gon (segments h/10 long) gives
    // the circle's radial normal to O(h³) ≈ 1e-4 (see the geometry module's tests).
    const Interface fine({shapes::circle({0.1, 0.0}, 0.5, 1000)});
    const DistanceTree tree(fine, Box::centered_square(1.0), {.depth = 7, .triangulate = false});
    const auto u = vertex_velocities(*law, 0.0, fine, {.tree = &tree, .embedded = {.mesh = 64}});
    constexpr double normal_tolerance = 1e-3;
    for (std::size_t i = 0; i < u.size(); ++i)
        EXPECT_NEAR(norm(u[i] - (fine.point(i) - Vec2{0.1, 0.0}) / 0.5), 0.0, normal_tolerance);
}

}  // namespace
}  // namespace slc
