// Tests of the lattice velocity: exact interpolation of linear fields, second-order error on a
// smooth one, the extent and clamping outside it, and the CSV and legacy VTK readers with their
// errors.
#include "slc/velocity/grid_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "slc/core/error.hpp"
#include "slc/velocity/laws.hpp"
#include "temp_dir.hpp"

namespace slc {
namespace {

using std::numbers::pi;

/// Rounding in a few operations on values of size ~1.
constexpr double rounding_tolerance = 1e-12;

/// The field f on the lattice of n × n points over [lo, hi]².
template <class F>
GridVelocity lattice(double lo, double hi, std::size_t n, F f) {
    const double h = (hi - lo) / static_cast<double>(n - 1);
    GridVelocity g{{lo, lo}, {h, h}, n, n, {}};
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i)
            g.values.push_back(
                f(Vec2{lo + static_cast<double>(i) * h, lo + static_cast<double>(j) * h}));
    return g;
}

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

TEST(GridField, InterpolatesALinearFieldExactly) {
    const GridField field(lattice(-2, 2, 41, [](Vec2 x) { return perp(x); }), "rotation grid");
    const Rotation rotation;
    std::vector<Vec2> points;
    for (int k = 0; k < 500; ++k)
        points.push_back({std::cos(0.37 * k) * 1.9, std::sin(0.91 * k) * 1.7});
    const auto a = field_velocities(field, 0.0, points),
               b = field_velocities(rotation, 0.0, points);
    for (std::size_t i = 0; i < a.size(); ++i)
        EXPECT_NEAR(norm(a[i] - b[i]), 0.0, rounding_tolerance);
    EXPECT_TRUE(field.is_field());
    EXPECT_EQ(field.extent(), (Box{{-2, -2}, {2, 2}}));
}

TEST(GridField, ErrorOnASmoothFieldIsSecondOrder) {
    // The single vortex on [0, 1]²: bilinear error ≤ h²/8 (max|u_xx| + max|u_yy|) = h²/8 · 6π²
    // for each component (|u_xx| ≤ 2π², |u_yy| ≤ 4π²), so halving h divides it by about 4; the
    // observed ratio must exceed 3.5.
    const SingleVortex vortex;
    auto f = [&](Vec2 x) {
        Vec2 u;
        vortex.sample(0.0, std::span<const Vec2>(&x, 1), std::span<Vec2>(&u, 1));
        return u;
    };
    std::vector<Vec2> points;
    for (int k = 0; k < 400; ++k)
        points.push_back({0.5 + 0.45 * std::cos(0.7 * k), 0.5 + 0.45 * std::sin(1.3 * k)});
    const auto exact = field_velocities(vortex, 0.0, points);
    auto error = [&](std::size_t n) {
        const GridField field(lattice(0, 1, n, f), "vortex grid");
        const auto u = field_velocities(field, 0.0, points);
        double e = 0;
        for (std::size_t i = 0; i < u.size(); ++i) e = std::max(e, norm(u[i] - exact[i]));
        return e;
    };
    const double coarse = error(33), fine = error(65);
    EXPECT_LT(fine, std::sqrt(2.0) * 6 * pi * pi / (8.0 * 64 * 64));  // both components
    EXPECT_GT(coarse / fine, 3.5);
}

TEST(GridField, OutsideItsBoxTakesTheNearestPointAndRunsRefuseCurvesThere) {
    const GridField field(lattice(0, 1, 3, [](Vec2 x) { return Vec2{x.x, 2 * x.y}; }), "grid");
    EXPECT_EQ(field(Vec2{3.0, 0.5}), (Vec2{1.0, 1.0}));
    EXPECT_EQ(field(Vec2{-1.0, -1.0}), (Vec2{0.0, 0.0}));
    const Interface inside({{{0.2, 0.2}, {0.8, 0.2}, {0.5, 0.8}}});
    const Interface outside({{{0.2, 0.2}, {1.8, 0.2}, {0.5, 0.8}}});
    EXPECT_FALSE(vertex_outside_extent(field, inside));
    EXPECT_EQ(vertex_outside_extent(field, outside), std::optional<std::size_t>(1));
    const std::string m = invalid_input_message([&] { require_inside_extent(field, outside); });
    EXPECT_NE(m.find("the initial curves leave the region where velocity 'grid' is known, [0, 1] "
                     "x [0, 1]: vertex 1 at (1.8, 0.2)"),
              std::string::npos)
        << m;
}

TEST(GridField, RejectsBadLattices) {
    GridVelocity g = lattice(0, 1, 3, [](Vec2) { return Vec2{}; });
    g.values.pop_back();
    EXPECT_THROW(GridField(g, "g"), InvalidInput);
    g = lattice(0, 1, 3, [](Vec2) { return Vec2{}; });
    g.values[4].x = NAN;
    EXPECT_NE(invalid_input_message([&] { GridField(g, "g"); }).find("lattice point (1, 1)"),
              std::string::npos);
    g = lattice(0, 1, 3, [](Vec2) { return Vec2{}; });
    g.spacing.y = 0;
    EXPECT_THROW(GridField(g, "g"), InvalidInput);
}

TEST(GridCsv, ReadsLinesInAnyOrderWithAHeader) {
    const GridVelocity g = parse_grid_csv(
        "x,y,u,v\n1,1,4,5\n0,0,0,1\n\n# a comment\n1,0,2,3\r\n0,1,6,7\n2,0,8,9\n2,1,10,11\n",
        "test.csv");
    EXPECT_EQ(g.nx, 3u);
    EXPECT_EQ(g.ny, 2u);
    EXPECT_EQ(g.origin, (Vec2{0, 0}));
    EXPECT_EQ(g.spacing, (Vec2{1, 1}));
    const std::vector<Vec2> expected = {{0, 1}, {2, 3}, {8, 9}, {6, 7}, {4, 5}, {10, 11}};
    EXPECT_EQ(g.values, expected);
}

TEST(GridCsv, RejectsWhatIsNotALattice) {
    auto message = [](const std::string& text) {
        return invalid_input_message([&] { parse_grid_csv(text, "f.csv"); });
    };
    EXPECT_NE(message("0,0,1,1\n1,0,1\n").find("f.csv, line 2: expected 4 numbers x,y,u,v"),
              std::string::npos);
    EXPECT_NE(message("0,0,1,1\n1,0,1,1\n0,1,1,1\n").find("3 lines for a lattice of 2 x 2"),
              std::string::npos);
    EXPECT_NE(message("0,0,1,1\n1,0,1,1\n3,0,1,1\n0,1,1,1\n1,1,1,1\n3,1,1,1\n")
                  .find("the x values are not evenly spaced"),
              std::string::npos);
    EXPECT_NE(message("0,0,1,1\n1,0,1,1\n0,1,1,1\n0,1,1,1\n")
                  .find("line 4: the point (0, 1) appears twice"),
              std::string::npos);
    EXPECT_NE(message("0,0,1,1\n0,1,1,1\n").find("at least 2 distinct x"), std::string::npos);
    EXPECT_NE(message("x,y,u,v\n").find("no lines"), std::string::npos);
    EXPECT_NE(message("0,0,nan,1\n").find("not finite"), std::string::npos);
}

/// A 3 × 2 lattice with origin (1, 2), spacing (0.5, 0.25) and velocity (i, 10 j) at point (i, j).
const std::string vtk_header =
    "# vtk DataFile Version 3.0\nvelocity\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 3 2 1\n"
    "ORIGIN 1 2 0\nSPACING 0.5 0.25 1\nPOINT_DATA 6\n";

TEST(GridVtk, ReadsVectorsScalarsAndFieldArrays) {
    const std::vector<Vec2> expected = {{0, 0}, {1, 0}, {2, 0}, {0, 10}, {1, 10}, {2, 10}};
    for (const std::string data :
         {"SCALARS p float\nLOOKUP_TABLE default\n1 2 3 4 5 6\n"
          "VECTORS u double\n0 0 0 1 0 0 2 0 0\n0 10 0 1 10 0 2 10 0\n",
          "SCALARS u float 2\nLOOKUP_TABLE default\n0 0 1 0 2 0 0 10 1 10 2 10\n",
          "FIELD data 2\np 1 6 float\n1 2 3 4 5 6\nu 2 6 double\n0 0 1 0 2 0 0 10 1 10 2 10\n"}) {
        const GridVelocity g = parse_grid_vtk(vtk_header + data, "v.vtk");
        EXPECT_EQ(g.nx, 3u);
        EXPECT_EQ(g.ny, 2u);
        EXPECT_EQ(g.origin, (Vec2{1, 2}));
        EXPECT_EQ(g.spacing, (Vec2{0.5, 0.25}));
        EXPECT_EQ(g.values, expected) << data;
    }
}

TEST(GridVtk, RejectsWhatItCannotRead) {
    auto message = [](const std::string& text) {
        return invalid_input_message([&] { parse_grid_vtk(text, "v.vtk"); });
    };
    EXPECT_NE(message("hello\n").find("v.vtk: not a legacy VTK file"), std::string::npos);
    EXPECT_NE(message("# vtk DataFile Version 3.0\nt\nBINARY\n").find("only ASCII"),
              std::string::npos);
    EXPECT_NE(message("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\n")
                  .find("DATASET STRUCTURED_POINTS"),
              std::string::npos);
    EXPECT_NE(message(vtk_header + "SCALARS p float\nLOOKUP_TABLE default\n1 2 3 4 5 6\n")
                  .find("no point-data array with 2 or 3 components"),
              std::string::npos);
    EXPECT_NE(message(vtk_header + "VECTORS u float\n1 2 3\n").find("the file ends"),
              std::string::npos);
    std::string three_d = vtk_header;
    three_d.replace(three_d.find("3 2 1"), 5, "3 2 2");
    EXPECT_NE(message(three_d).find("must be 2D"), std::string::npos);
}

TEST(GridFile, ReadsByExtensionAndNamesMissingFiles) {
    test_support::TempDir dir("slc_grid");
    const auto csv = dir.path() / "f.csv", vtk = dir.path() / "f.VTK";
    std::ofstream(csv) << "0,0,1,2\n1,0,1,2\n0,1,1,2\n1,1,1,2\n";
    std::ofstream(vtk) << vtk_header << "VECTORS u float\n0 0 0 1 0 0 2 0 0 0 10 0 1 10 0 2 10 0\n";
    EXPECT_EQ(read_grid_velocity(csv).nx, 2u);
    EXPECT_EQ(read_grid_velocity(vtk).nx, 3u);
    const auto law = grid_field_law(csv);
    EXPECT_EQ(law->name(), "field-file " + csv.string());
    EXPECT_NE(invalid_input_message([&] {
                  read_grid_velocity(dir.path() / "none.csv");
              }).find("cannot read"),
              std::string::npos);
}

}  // namespace
}  // namespace slc
