// Tests of velocity laws typed as expressions, of curves and of surfaces: the values against the
// built-in laws they spell, the kind of law (normal, curvature, field) each expression makes,
// constants, errors with one line naming the expression, and values that do not depend on the
// thread count.
#include "slc/velocity/expression.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/geometry_modules/intrinsic.hpp"
#include "slc/geometry_modules/surface_geometry.hpp"
#include "slc/velocity/laws.hpp"
#include "slc/velocity/surface_laws.hpp"

namespace slc {
namespace {

using std::numbers::pi;

/// Rounding in a few operations on values of size ~1.
constexpr double rounding_tolerance = 1e-12;

/// The message of the InvalidInput f throws, or "" if it throws none.
template <class F>
std::string invalid_input_message(F f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

/// Sets the thread count for a scope and restores it.
struct Threads {
    explicit Threads(int n) : before(thread_count()) { set_thread_count(n); }
    ~Threads() { set_thread_count(before); }
    int before;
};

TEST(SpeedExpression, OneIsTheUnitNormalLaw) {
    const auto law = speed_expression_law("1");
    const NormalSpeed builtin(1.0);
    EXPECT_TRUE(law->is_normal_law());
    EXPECT_FALSE(law->needs().curvature);
    EXPECT_EQ(law->name(), "speed = 1");
    const Interface curves({shapes::circle({0.1, 0.2}, 0.7, 300)});
    EXPECT_EQ(vertex_velocities(*law, 0.0, curves), vertex_velocities(builtin, 0.0, curves));
}

TEST(SpeedExpression, ANumberIsAConstantSpeedWithTheUnitNormalLawsInvariants) {
    // An expression that reads no variable is one number: the step then stops at its predictor,
    // the guards check what unit-normal at that speed keeps, and the speed bounds G.
    const auto grow = surface_speed_expression_law("2 * s", {{"s", 0.25}});
    EXPECT_EQ(grow->constant_speed(), 0.5);
    EXPECT_EQ(grow->speed_bound(), 0.5);
    const Invariants kept = grow->invariants();
    EXPECT_TRUE(kept.cannot_vanish && !kept.cannot_grow);
    EXPECT_EQ(kept.volume_rate_per_area, 0.5);
    const auto shrink = speed_expression_law("-1");
    EXPECT_EQ(shrink->constant_speed(), -1.0);
    EXPECT_TRUE(shrink->invariants().cannot_grow);
    EXPECT_FALSE(shrink->invariants().volume_rate_per_area);
    for (const char* reads : {"x", "0 * t + 1", "1 + 0 * nz"}) {
        const auto law = surface_speed_expression_law(reads);
        EXPECT_FALSE(law->constant_speed()) << reads;
        EXPECT_FALSE(law->speed_bound()) << reads;
        EXPECT_FALSE(law->invariants().cannot_vanish) << reads;
    }
}

TEST(SpeedExpression, ReadsPointTimeAndNormal) {
    const auto law = speed_expression_law("x + 10*y + 100*t + 1000*nx + 10000*ny");
    const std::vector<Vec2> points = {{1, 2}, {-3, 0.5}};
    const std::vector<Vec2> normals = {{1, 0}, {0.6, -0.8}};
    std::vector<double> v(2);
    law->normal_speeds(0.5, points, normals, v);
    EXPECT_NEAR(v[0], 1 + 20 + 50 + 1000, rounding_tolerance);
    EXPECT_NEAR(v[1], -3 + 5 + 50 + 600 - 8000, rounding_tolerance);
}

TEST(SpeedExpression, MatchesTheAnisotropicLaw) {
    // v = R + ε cos(mθ), θ the normal angle, as the built-in anisotropic law.
    const auto law = speed_expression_law("R + e*cos(m*atan2(ny, nx))",
                                          {{"R", -1.0}, {"e", 1.0 / 3.0}, {"m", 4.0}});
    const AnisotropicNormalSpeed builtin(-1.0, 4.0, 1.0 / 3.0);
    const Interface curves({shapes::circle({}, 1.0, 500)});
    const auto a = vertex_velocities(*law, 0.0, curves),
               b = vertex_velocities(builtin, 0.0, curves);
    for (std::size_t i = 0; i < a.size(); ++i)
        EXPECT_NEAR(norm(a[i] - b[i]), 0.0, rounding_tolerance);
}

TEST(SpeedExpression, WithCurvatureAsksForItAndIsCurvatureFlow) {
    const auto law = speed_expression_law("C");
    EXPECT_FALSE(law->is_normal_law());
    EXPECT_TRUE(law->needs().curvature);
    EXPECT_TRUE(law->needs().normals);
    const CurvatureFlow builtin;
    const Interface curves({shapes::circle({}, 0.5, 200)});
    EXPECT_EQ(vertex_velocities(*law, 0.0, curves), vertex_velocities(builtin, 0.0, curves));
    // With a constant: a + C, the geometry module passed on.
    const auto shifted = speed_expression_law("a + C", {{"a", 0.5}}, GeometryModule::intrinsic);
    EXPECT_EQ(shifted->needs().module, GeometryModule::intrinsic);
    const auto u = vertex_velocities(*shifted, 0.0, curves);
    const VertexGeometry g = intrinsic_geometry(curves);
    for (std::size_t i = 0; i < u.size(); ++i)
        EXPECT_NEAR(norm(u[i] - (0.5 + g.curvature[i]) * g.normals[i]), 0.0, rounding_tolerance);
}

// A speed that falls as C grows moves backward in curvature, which is ill-posed: refused where
// it is evaluated, naming the slope and the place, for curves and surfaces alike. C^2 falls as
// C grows wherever C < 0, on every convex part.
TEST(SpeedExpression, BackwardInCurvatureIsRefused) {
    const Interface circle({shapes::circle({}, 0.5, 200)});
    const Surface ball = sphere({}, 0.5, 3);
    for (const char* text : {"a - C", "-C", "C^2", "a - 0.5 * C"}) {
        try {
            vertex_velocities(*speed_expression_law(text, {{"a", 0.5}}), 0.0, circle);
            ADD_FAILURE() << text << " was not refused";
        } catch (const InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find("falls as the curvature C grows"),
                      std::string::npos)
                << e.what();
        }
        EXPECT_THROW(
            vertex_velocities(*surface_speed_expression_law(text, {{"a", 0.5}}), 0.0, ball),
            InvalidInput)
            << text;
    }
    // Forward in C: accepted. C^3 has dv/dC = 3C^2 >= 0 everywhere.
    for (const char* text : {"a + C", "C", "C^3", "2 * C + x"}) {
        EXPECT_NO_THROW(vertex_velocities(*speed_expression_law(text, {{"a", 0.5}}), 0.0, circle))
            << text;
        EXPECT_NO_THROW(
            vertex_velocities(*surface_speed_expression_law(text, {{"a", 0.5}}), 0.0, ball))
            << text;
    }
}

TEST(FieldExpression, MinusYXIsTheRotation) {
    const auto law = field_expression_law("-y, x");
    EXPECT_TRUE(law->is_field());
    EXPECT_EQ(law->name(), "field = (-y, x)");
    const Rotation builtin;
    const Interface curves({shapes::propeller(400)});
    EXPECT_EQ(field_velocities(*law, 0.3, curves.points()),
              field_velocities(builtin, 0.3, curves.points()));
    EXPECT_EQ(vertex_velocities(*law, 0.3, curves), vertex_velocities(builtin, 0.3, curves));
}

TEST(FieldExpression, ReadsTimeConstantsAndFunctionsWithCommas) {
    const auto law = field_expression_law("max(x, y) * w, sin(_pi * t)", {{"w", 2.0}});
    const auto u = field_velocities(*law, 0.5, std::vector<Vec2>{{1, 3}, {-2, -4}});
    EXPECT_NEAR(u[0].x, 6.0, rounding_tolerance);
    EXPECT_NEAR(u[1].x, -4.0, rounding_tolerance);
    EXPECT_NEAR(u[0].y, std::sin(pi / 2), rounding_tolerance);
}

TEST(Expression, ValuesDoNotDependOnTheThreadCount) {
    const auto speed = speed_expression_law("sin(3*x)*cos(2*y) + nx*ny - t");
    const auto field = field_expression_law("exp(-x*x)*y, atan2(y, x)");
    std::vector<Vec2> points, normals;
    for (int i = 0; i < 20000; ++i) {  // many parallel_grain chunks
        const double a = 0.001 * i;
        points.push_back({std::cos(a) * (1 + 0.1 * a), std::sin(3 * a)});
        normals.push_back({std::cos(a), std::sin(a)});
    }
    std::vector<double> one(points.size()), many(points.size());
    std::vector<Vec2> u_one, u_many;
    {
        Threads threads(1);
        speed->normal_speeds(0.25, points, normals, one);
        u_one = field_velocities(*field, 0.25, points);
    }
    {
        Threads threads(4);
        speed->normal_speeds(0.25, points, normals, many);
        u_many = field_velocities(*field, 0.25, points);
    }
    EXPECT_EQ(one, many);
    EXPECT_EQ(u_one, u_many);
}

TEST(Expression, BadExpressionsThrowOneLineNamingThem) {
    struct Case {
        std::string expression;
        bool field;
        std::string expected;  // part of the message
    };
    const std::vector<Case> cases = {
        {"x +", false, "speed expression 'x +': unexpected end of expression"},
        {"z + 1", false, "unknown name 'z' at position 0 (the variables are x, y, t, C, nx, ny)"},
        {"", false, "speed expression is empty"},
        {"1, 2", false, "gives 2 values separated by commas; a normal speed is one"},
        {"sin(x", false, "missing parenthesis"},
        {"x", true, "field expression 'x': gives 1 value; a flow field needs two"},
        {"x, y, t", true, "gives 3 values"},
        {"C, x", true, "unknown name 'C' at position 0 (the variables are x, y, t)"},
        {"-y,\nx +", true, "field expression '-y, x +'"},
    };
    for (const Case& c : cases) {
        const std::string m = invalid_input_message([&] {
            if (c.field)
                field_expression_law(c.expression);
            else
                speed_expression_law(c.expression);
        });
        EXPECT_NE(m.find(c.expected), std::string::npos) << c.expression << ": " << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
}

TEST(Expression, BadConstantsThrow) {
    auto message = [](const VelocityParams& constants) {
        return invalid_input_message([&] { speed_expression_law("1", constants); });
    };
    EXPECT_NE(message({{"x", 1.0}}).find("the constant 'x' is a variable"), std::string::npos);
    EXPECT_NE(message({{"2a", 1.0}}).find("the constant '2a' is not a name"), std::string::npos);
    EXPECT_NE(message({{"sin", 1.0}}).find("is a function"), std::string::npos);
    EXPECT_NE(message({{"a", NAN}}).find("must be finite"), std::string::npos);
    // Constants the expression does not use are allowed, and named in an unknown-name message.
    EXPECT_NO_THROW(speed_expression_law("1", {{"unused", 3.0}}));
    EXPECT_NE(invalid_input_message([] {
                  speed_expression_law("b", {{"a", 1.0}});
              }).find("the constants a"),
              std::string::npos);
}

TEST(Expression, NonFiniteValuesAreNumericalFailures) {
    const auto law = speed_expression_law("1 / x");
    const Interface curves({{{0, -1}, {1, 0}, {0, 1}, {-1, 0}}});
    EXPECT_THROW(vertex_velocities(*law, 0.0, curves), NumericalFailure);
    const auto field = field_expression_law("sqrt(x), 0");
    EXPECT_THROW(field_velocities(*field, 0.0, std::vector<Vec2>{{-1, 0}}), NumericalFailure);
}

TEST(Expression, ConcurrentCallsOfOneLawAgree) {
    // Two threads calling the same law at once each get parsers of their own from its pool.
    const auto law = field_expression_law("x*x - y, t*x");
    std::vector<Vec2> points(5000);
    for (std::size_t i = 0; i < points.size(); ++i)
        points[i] = {0.001 * static_cast<double>(i), 1.0};
    const auto expected = field_velocities(*law, 2.0, points);
    std::vector<std::vector<Vec2>> got(4);
    Threads threads(1);  // each call on its own thread, not split further
#pragma omp parallel for num_threads(4)
    for (int k = 0; k < 4; ++k)
        got[static_cast<std::size_t>(k)] = field_velocities(*law, 2.0, points);
    for (const auto& g : got) EXPECT_EQ(g, expected);
}

TEST(SurfaceExpression, OneIsTheUnitNormalLawAndReadsZ) {
    const auto law = surface_speed_expression_law("1");
    const SurfaceNormalSpeed builtin(1.0);
    EXPECT_TRUE(law->is_normal_law());
    EXPECT_FALSE(law->needs().curvature);
    EXPECT_EQ(law->name(), "speed = 1");
    const Surface ball = sphere({0.1, 0.2, 0.3}, 0.7, 2);
    EXPECT_EQ(vertex_velocities(*law, 0.0, ball), vertex_velocities(builtin, 0.0, ball));

    const auto all = surface_speed_expression_law(
        "x + 10*y + 100*z + 1000*t + 1e4*nx + 1e5*ny "
        "+ 1e6*nz");
    const std::vector<Vec3> points = {{1, 2, 3}}, normals = {{0.6, 0.0, -0.8}};
    std::vector<double> v(1);
    all->normal_speeds(0.5, points, normals, v);
    EXPECT_NEAR(v[0], 1 + 20 + 300 + 500 + 6000 - 800000, 1e-9);
}

TEST(SurfaceExpression, WithCurvatureIsMeanCurvatureFlow) {
    const auto law = surface_speed_expression_law("C");
    EXPECT_FALSE(law->is_normal_law());
    EXPECT_TRUE(law->needs().curvature);
    const SurfaceMeanCurvatureFlow builtin;
    const Surface ball = sphere({}, 0.5, 3);
    EXPECT_EQ(vertex_velocities(*law, 0.0, ball), vertex_velocities(builtin, 0.0, ball));
    // A constant with the curvature: a + C.
    const auto shifted = surface_speed_expression_law("a + C", {{"a", 0.5}});
    const auto u = vertex_velocities(*shifted, 0.0, ball);
    const auto c = vertex_velocities(builtin, 0.0, ball);
    const SurfaceGeometry g = surface_geometry(ball, {});
    for (std::size_t i = 0; i < u.size(); ++i)
        EXPECT_NEAR(norm(u[i] - (0.5 * g.normals[i] + c[i])), 0.0, rounding_tolerance);
}

TEST(SurfaceExpression, FieldMinusYXZeroIsTheRotation) {
    const auto law = surface_field_expression_law("-y, x, 0");
    EXPECT_TRUE(law->is_field());
    EXPECT_EQ(law->name(), "field = (-y, x, 0)");
    const SurfaceRotation builtin;
    const Surface ball = sphere({0.2, -0.1, 0.3}, 0.4, 2);
    EXPECT_EQ(vertex_velocities(*law, 0.3, ball), vertex_velocities(builtin, 0.3, ball));
    const auto w = field_velocities(*surface_field_expression_law("z*k, t, x", {{"k", 2.0}}), 0.5,
                                    std::vector<Vec3>{{1, 2, 3}});
    EXPECT_EQ(w[0], (Vec3{6.0, 0.5, 1.0}));
}

TEST(SurfaceExpression, BadExpressionsThrowOneLineNamingThem) {
    struct Case {
        std::string expression;
        bool field;
        std::string expected;  // part of the message
    };
    const std::vector<Case> cases = {
        {"w + 1", false,
         "unknown name 'w' at position 0 (the variables are x, y, z, t, C, nx, ny, nz)"},
        {"", false, "speed expression is empty"},
        {"1, 2", false, "gives 2 values separated by commas; a normal speed is one"},
        {"-y, x", true, "gives 2 values; a flow field needs three, u, v and w"},
        {"C, x, y", true, "unknown name 'C' at position 0 (the variables are x, y, z, t)"},
    };
    for (const Case& c : cases) {
        const std::string m = invalid_input_message([&] {
            if (c.field)
                surface_field_expression_law(c.expression);
            else
                surface_speed_expression_law(c.expression);
        });
        EXPECT_NE(m.find(c.expected), std::string::npos) << c.expression << ": " << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
    EXPECT_NE(invalid_input_message([] {
                  surface_speed_expression_law("1", {{"z", 1.0}});
              }).find("the constant 'z' is a variable"),
              std::string::npos);
}

TEST(SurfaceExpression, NonFiniteValuesAreNumericalFailures) {
    const Surface ball = sphere({}, 1.0, 1);
    EXPECT_THROW(vertex_velocities(*surface_speed_expression_law("1 / (z - z)"), 0.0, ball),
                 NumericalFailure);
    EXPECT_THROW(field_velocities(*surface_field_expression_law("sqrt(z), 0, 0"), 0.0,
                                  std::vector<Vec3>{{0, 0, -1}}),
                 NumericalFailure);
}

}  // namespace
}  // namespace slc
