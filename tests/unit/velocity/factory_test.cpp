// Tests of make_velocity: every built-in law by name with its defaults, parameters by name, and the
// messages for an unknown law, an unknown or missing parameter and a non-finite value.
#include "slc/velocity/factory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "slc/core/error.hpp"
#include "slc/geometry/shapes.hpp"

namespace slc {
namespace {

/// The message of the InvalidInput that f throws, or "" if it throws none.
template <class F>
std::string invalid_input_message(F&& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

TEST(MakeVelocity, BuildsEveryLawOfTheCatalogByName) {
    const auto& catalog = velocity_catalog();
    ASSERT_EQ(catalog.size(), 9u);
    for (const auto& info : catalog) {
        VelocityParams params;
        for (const auto& p : info.parameters)
            if (p.required) params[p.name] = 1.0;
        const auto law = make_velocity(info.name, params);
        EXPECT_EQ(law->name(), info.name);
    }
    EXPECT_TRUE(make_velocity("rotation")->is_field());
    EXPECT_TRUE(make_velocity("vortex")->is_field());
    // Curvature from the arclength module (stable at any step), normals alone from the
    // intrinsic one, unless told otherwise.
    EXPECT_EQ(make_velocity("curvature")->needs().resolved_module(), GeometryModule::arclength);
    EXPECT_EQ(make_velocity("volume-preserving-curvature")->needs().resolved_module(),
              GeometryModule::arclength);
    EXPECT_EQ(make_velocity("unit-normal")->needs().resolved_module(), GeometryModule::intrinsic);
    EXPECT_EQ(make_velocity("curvature", {}, GeometryModule::intrinsic)->needs().module,
              GeometryModule::intrinsic);
    EXPECT_TRUE(make_velocity("unit-normal")->is_normal_law());
    EXPECT_TRUE(make_velocity("anisotropic")->is_normal_law());
    EXPECT_FALSE(make_velocity("curvature")->is_normal_law());
    EXPECT_FALSE(make_velocity("rotation")->is_normal_law());
}

TEST(MakeVelocity, PassesParametersByName) {
    const std::vector<Vec2> at = {{1.0, 2.0}};
    const auto rotation = make_velocity("rotation", {{"omega", 3.0}, {"cx", 1.0}, {"cy", 1.0}});
    EXPECT_EQ(field_velocities(*rotation, 0.0, at)[0], (Vec2{-3.0, 0.0}));
    EXPECT_EQ(field_velocities(*make_velocity("rotation"), 0.0, at)[0], (Vec2{-2.0, 1.0}));
    const auto translation = make_velocity("translation", {{"ux", 0.5}, {"uy", -2.0}});
    EXPECT_EQ(field_velocities(*translation, 7.0, at)[0], (Vec2{0.5, -2.0}));
    // vortex period: the flow stops at t = T/2.
    const auto vortex = make_velocity("vortex", {{"period", 2.0}});
    EXPECT_NEAR(norm(field_velocities(*vortex, 1.0, std::vector<Vec2>{{0.3, 0.6}})[0]), 0.0, 1e-15);
    // unit-normal speed on a regular polygon: radial.
    const Interface curves({shapes::circle({}, 0.5, 32)});
    const auto u = vertex_velocities(*make_velocity("unit-normal", {{"speed", -2.0}}), 0.0, curves);
    EXPECT_NEAR(norm(u[0] - Vec2{-2.0, 0.0}), 0.0, 1e-12);
}

TEST(MakeVelocity, AnisotropicEpsDefaultsToFiveOverMSquaredMinusOne) {
    // Vertex 0 of the regular polygon has θ = 0: v = R + ε.
    const Interface curves({shapes::circle({}, 0.5, 32)});
    auto speed_at_theta0 = [&](const VelocityParams& p) {
        return vertex_velocities(*make_velocity("anisotropic", p), 0.0, curves)[0].x;
    };
    EXPECT_NEAR(speed_at_theta0({}), -1.0 + 5.0 / 15.0, 1e-12);
    EXPECT_NEAR(speed_at_theta0({{"m", 3.0}}), -1.0 + 5.0 / 8.0, 1e-12);
    EXPECT_NEAR(speed_at_theta0({{"m", 3.0}, {"eps", 0.1}, {"R", 2.0}}), 2.1, 1e-12);
    EXPECT_NE(invalid_input_message([] {
                  make_velocity("anisotropic", {{"m", 1.0}});
              }).find("eps"),
              std::string::npos);
}

TEST(MakeVelocity, UnknownNameListsTheKnownLaws) {
    EXPECT_EQ(
        invalid_input_message([] { make_velocity("x"); }),
        "unknown velocity 'x'; known: rotation, translation, unit-normal, anisotropic, curvature, "
        "volume-preserving-curvature, mullins-sekerka, hele-shaw, vortex");
}

TEST(MakeVelocity, UnknownParameterListsTheLawsParameters) {
    EXPECT_EQ(invalid_input_message([] {
                  make_velocity("rotation", {{"omgea", 2.0}});
              }),
              "velocity 'rotation' has no parameter 'omgea'; its parameters: omega, cx, cy");
    EXPECT_EQ(invalid_input_message([] {
                  make_velocity("curvature", {{"speed", 2.0}});
              }),
              "velocity 'curvature' has no parameter 'speed'; its parameters: none");
}

TEST(MakeVelocity, RejectsMissingRequiredAndNonFiniteValues) {
    EXPECT_NE(invalid_input_message([] {
                  make_velocity("translation", {{"ux", 1.0}});
              }).find("uy"),
              std::string::npos);
    EXPECT_NE(invalid_input_message([] {
                  make_velocity("unit-normal", {{"speed", std::nan("")}});
              }).find("speed"),
              std::string::npos);
    EXPECT_NE(invalid_input_message([] {
                  make_velocity("vortex", {{"period", -1.0}});
              }).find("period"),
              std::string::npos);
}

}  // namespace
}  // namespace slc
