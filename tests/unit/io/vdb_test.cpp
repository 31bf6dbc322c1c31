// Tests of OpenVDB level sets in and out (vdb.hpp), against OpenVDB's own tools: a sphere made by
// openvdb::tools::createLevelSetSphere is read within a voxel of the sphere; slc's level set of a
// surface measured by openvdb::tools::levelSetVolume and levelSetArea gives the surface's volume
// and area; its values are the exact signed distances; a vector grid is a flow field, exact for a
// rotation; bad files are one-line InvalidInput.
#include "slc/io/vdb.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include "slc/core/error.hpp"
#include "slc/evolve/surface_run.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/io/surface_files.hpp"
#include "slc/velocity/surface_laws.hpp"
#include "temp_dir.hpp"

namespace slc {
namespace {

namespace fs = std::filesystem;
using test_support::slurp;
using test_support::TempDir;

/// Writes grids to path with OpenVDB's own writer.
void write_with_openvdb(const fs::path& path, const openvdb::GridPtrVec& grids) {
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.write(grids);
    file.close();
}

/// The one grid of the OpenVDB file at path, read by OpenVDB.
openvdb::FloatGrid::Ptr read_with_openvdb(const fs::path& path) {
    openvdb::initialize();
    openvdb::io::File file(path.string());
    file.open(false);
    const openvdb::GridPtrVecPtr grids = file.getGrids();
    file.close();
    EXPECT_EQ(grids->size(), 1u);
    return openvdb::gridPtrCast<openvdb::FloatGrid>(grids->front());
}

/// The largest |‖x − c‖ − R| over the vertices: their distance from the sphere.
double sphere_error(const Surface& s, Vec3 c, double r) {
    double worst = 0.0;
    for (const Vec3 x : s.vertices) worst = std::max(worst, std::abs(norm(x - c) - r));
    return worst;
}

/// The message of the InvalidInput that f throws; fails the test when it throws none.
template <class F>
std::string invalid_input_message(F f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InvalidInput";
    return {};
}

template <class GridT>
void expect_sphere_within_a_voxel() {
    const TempDir dir("slc_vdb");
    const fs::path path = dir.path() / "sphere.vdb";
    const Vec3 c{0.1, -0.2, 0.3};
    const double r = 1.0;
    const double voxel = 0.05;
    const auto grid = openvdb::tools::createLevelSetSphere<GridT>(
        static_cast<float>(r), openvdb::Vec3f(0.1f, -0.2f, 0.3f), static_cast<float>(voxel));
    grid->setName("ball");
    write_with_openvdb(path, {grid});

    const Surface s = read_vdb_level_set(path);
    ASSERT_FALSE(s.empty());
    // The grid holds the exact distance to the sphere at voxel centres; its trilinear
    // interpolant is within h²/(8R) of it, so vertices on its zero set are well within a voxel.
    const double error = sphere_error(s, c, r);
    EXPECT_LE(error, voxel);
    EXPECT_EQ(genus(s), 0);
    EXPECT_EQ(component_count(s), 1u);
    EXPECT_NEAR(volume(s), 4.0 / 3.0 * M_PI * r * r * r, 0.01);
    ::testing::Test::RecordProperty("max_vertex_error_over_voxel",
                                    fmt::format("{:.3g}", error / voxel));
    fmt::print("{} sphere: {} triangles, max |‖x−c‖−R| = {:.3g} = {:.3g} voxel\n",
               openvdb::typeNameAsString<typename GridT::ValueType>(), s.size(), error,
               error / voxel);
}

TEST(VdbLevelSet, ReadsOpenVdbFloatSphereWithinAVoxel) {
    expect_sphere_within_a_voxel<openvdb::FloatGrid>();
}

TEST(VdbLevelSet, ReadsOpenVdbDoubleSphereWithinAVoxel) {
    expect_sphere_within_a_voxel<openvdb::DoubleGrid>();
}

TEST(VdbLevelSet, ReadSurfaceTakesVdbFiles) {
    EXPECT_TRUE(is_surface_file("a/model.vdb"));
    EXPECT_TRUE(is_surface_file("MODEL.VDB"));
    const TempDir dir("slc_vdb");
    const fs::path path = dir.path() / "ball.VDB";
    write_with_openvdb(path, {openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
                                 0.5f, openvdb::Vec3f(0.0f), 0.05f)});
    const Surface s = read_surface(path);
    EXPECT_LE(sphere_error(s, {0, 0, 0}, 0.5), 0.05);
}

TEST(VdbLevelSet, WrittenSphereHasOpenVdbsVolumeAndArea) {
    const TempDir dir("slc_vdb");
    const fs::path path = dir.path() / "out" / "sphere.vdb";
    const Surface s = sphere({0.05, -0.1, 0.2}, 1.0, 4);
    const double voxel = 0.01;
    write_vdb_level_set(path, s, {.voxel = voxel, .half_width = 3.0, .name = "sphere"});

    const openvdb::FloatGrid::Ptr grid = read_with_openvdb(path);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_EQ(grid->getName(), "sphere");
    EXPECT_FLOAT_EQ(grid->background(), static_cast<float>(3.0 * voxel));
    EXPECT_DOUBLE_EQ(grid->voxelSize().x(), voxel);
    // OpenVDB's measures of a level set: a smeared Dirac delta over the band, second order in the
    // voxel; at 100 voxels a radius they agree with the polyhedron's exact measures to 1e−3.
    constexpr double measure_tolerance = 1e-3;
    const double vdb_volume = openvdb::tools::levelSetVolume(*grid);
    const double vdb_area = openvdb::tools::levelSetArea(*grid);
    const double volume_error = std::abs(vdb_volume - volume(s)) / volume(s);
    const double area_error = std::abs(vdb_area - area(s)) / area(s);
    EXPECT_LE(volume_error, measure_tolerance);
    EXPECT_LE(area_error, measure_tolerance);
    RecordProperty("volume_relative_difference", fmt::format("{:.3g}", volume_error));
    RecordProperty("area_relative_difference", fmt::format("{:.3g}", area_error));
    fmt::print("{} active voxels: volume {} (slc {}), area {} (slc {}): relative {:.3g}, {:.3g}\n",
               grid->activeVoxelCount(), vdb_volume, volume(s), vdb_area, area(s), volume_error,
               area_error);
}

TEST(VdbLevelSet, WrittenValuesAreExactDistancesInTheBand) {
    const TempDir dir("slc_vdb");
    const fs::path path = dir.path() / "box.vdb";
    // A cube [−1, 1]³: its exact signed distance is known everywhere, edges and corners included.
    const Surface s = box_surface({-1, -1, -1}, {1, 1, 1}, 4);
    const double voxel = 0.1;
    // A band of 2.5 voxels: no voxel centre lies at exactly that distance, on either side.
    write_vdb_level_set(path, s, {.voxel = voxel, .half_width = 2.5});
    const openvdb::FloatGrid::Ptr grid = read_with_openvdb(path);
    ASSERT_TRUE(grid);
    const double band = 2.5 * voxel;
    auto exact = [](Vec3 x) {
        const Vec3 q{std::abs(x.x) - 1, std::abs(x.y) - 1, std::abs(x.z) - 1};
        const Vec3 out{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
        return norm(out) + std::min(std::max({q.x, q.y, q.z}), 0.0);
    };
    std::size_t active = 0;
    for (int i = -14; i <= 14; ++i)
        for (int j = -14; j <= 14; ++j)
            for (int k = -14; k <= 14; ++k) {
                const openvdb::Coord ijk(i, j, k);
                const double f = exact({i * voxel, j * voxel, k * voxel});
                const float value = grid->tree().getValue(ijk);
                if (std::abs(f) < band) {
                    ASSERT_TRUE(grid->tree().isValueOn(ijk)) << i << "," << j << "," << k;
                    // Stored as float: exact to its rounding.
                    EXPECT_NEAR(value, f, 1e-6) << i << "," << j << "," << k;
                    ++active;
                } else {
                    EXPECT_FALSE(grid->tree().isValueOn(ijk)) << i << "," << j << "," << k;
                    EXPECT_FLOAT_EQ(value, static_cast<float>(f > 0 ? band : -band))
                        << i << "," << j << "," << k;
                }
            }
    EXPECT_EQ(static_cast<std::size_t>(grid->activeVoxelCount()), active);
}

TEST(VdbLevelSet, WriteThenReadGivesTheSurfaceBack) {
    const TempDir dir("slc_vdb");
    const fs::path path = dir.path() / "torus.vdb";
    const Surface s = torus({0, 0, 0}, 1.0, 0.4, 64, 32);
    write_vdb_level_set(path, s, {.voxel = 0.04});
    const Surface back = read_vdb_level_set(path);
    EXPECT_EQ(genus(back), 1);
    EXPECT_EQ(component_count(back), 1u);
    EXPECT_NEAR(volume(back), volume(s), 0.01 * volume(s));
}

TEST(VdbLevelSet, WriteRefusesBadOptions) {
    const TempDir dir("slc_vdb");
    const Surface s = sphere({0, 0, 0}, 1.0, 1);
    EXPECT_EQ(invalid_input_message([&] { write_vdb_level_set(dir.path() / "a.vdb", s, {}); }),
              "voxel size must be positive and finite, got 0");
    EXPECT_EQ(invalid_input_message([&] {
                  write_vdb_level_set(dir.path() / "a.vdb", s, {.voxel = 0.1, .half_width = 0.5});
              }),
              "narrow-band half-width must be at least 1 voxel, got 0.5");
    EXPECT_EQ(invalid_input_message(
                  [&] { write_vdb_level_set(dir.path() / "a.vdb", Surface{}, {.voxel = 0.1}); }),
              "cannot write an empty surface as a level set");
    EXPECT_NE(invalid_input_message([&] {
                  write_vdb_level_set(dir.path() / "a.vdb", s, {.voxel = 1e-5});
              }).find("too fine"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(dir.path() / "a.vdb"));
}

/// A file's errors: InvalidInput, one line, beginning with the file's name.
void expect_refused(const fs::path& path, const std::string& says) {
    const std::string message = invalid_input_message([&] { read_vdb_level_set(path); });
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(says), std::string::npos) << message;
}

TEST(VdbLevelSet, RefusesMissingTruncatedAndForeignFiles) {
    const TempDir dir("slc_vdb");
    expect_refused(dir.path() / "missing.vdb", "cannot read");
    expect_refused(dir.path(), "not a regular file");
    const fs::path text = dir.path() / "text.vdb";
    std::ofstream(text) << "v 0 0 0\n";
    expect_refused(text, "not a readable OpenVDB file");
    const fs::path empty = dir.path() / "empty.vdb";
    std::ofstream{empty};
    expect_refused(empty, "not a readable OpenVDB file");

    const fs::path whole = dir.path() / "whole.vdb";
    write_with_openvdb(whole, {openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
                                  1.0f, openvdb::Vec3f(0.0f), 0.1f)});
    const std::string bytes = slurp(whole);
    for (const std::size_t kept : {std::size_t{4}, std::size_t{100}, bytes.size() / 2,
                                   bytes.size() - 16, bytes.size() - 1}) {
        SCOPED_TRACE(kept);
        const fs::path cut = dir.path() / fmt::format("cut{}.vdb", kept);
        std::ofstream(cut, std::ios::binary) << bytes.substr(0, kept);
        expect_refused(cut, "not a readable OpenVDB file");
    }
}

TEST(VdbLevelSet, RefusesGridsThatAreNotLevelSets) {
    const TempDir dir("slc_vdb");
    const fs::path none = dir.path() / "none.vdb";
    write_with_openvdb(none, {});
    expect_refused(none, "no grids");

    const auto fog =
        openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0.0f), 0.1f);
    openvdb::tools::sdfToFogVolume(*fog);
    fog->setName("density");
    const fs::path fog_file = dir.path() / "fog.vdb";
    write_with_openvdb(fog_file, {fog});
    expect_refused(
        fog_file,
        "no level-set grid of float or double values (grids: 'density' (class fog volume, "
        "float values))");

    const auto velocity = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    velocity->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1.0f, 0.0f, 0.0f));
    velocity->setName("v");
    const fs::path vector_file = dir.path() / "vector.vdb";
    write_with_openvdb(vector_file, {velocity});
    expect_refused(vector_file, "(grids: 'v' (class unknown, vec3s values))");

    // A level set beside them is read; a grid asked for by name must be one.
    const auto ball =
        openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0.0f), 0.1f);
    ball->setName("ball");
    const fs::path mixed = dir.path() / "mixed.vdb";
    write_with_openvdb(mixed, {fog, velocity, ball});
    EXPECT_LE(sphere_error(read_vdb_level_set(mixed), {0, 0, 0}, 1.0), 0.1);
    EXPECT_LE(sphere_error(read_vdb_level_set(mixed, {.grid = "ball"}), {0, 0, 0}, 1.0), 0.1);
    EXPECT_EQ(invalid_input_message([&] { read_vdb_level_set(mixed, {.grid = "density"}); }),
              mixed.string() +
                  ": grid 'density' (class fog volume, float values) is not a level set of float "
                  "or double values");
    EXPECT_NE(invalid_input_message([&] {
                  read_vdb_level_set(mixed, {.grid = "nothing"});
              }).find("no grid named 'nothing'"),
              std::string::npos);
}

TEST(VdbLevelSet, RefusesLevelSetsWithoutZeroCrossing) {
    const TempDir dir("slc_vdb");
    const auto outside = openvdb::FloatGrid::create(0.3f);
    outside->setGridClass(openvdb::GRID_LEVEL_SET);
    outside->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    outside->setName("outside");
    for (int i = 0; i < 4; ++i) outside->tree().setValue(openvdb::Coord(i, 0, 0), 0.2f);
    const fs::path path = dir.path() / "outside.vdb";
    write_with_openvdb(path, {outside});
    expect_refused(path, "level set 'outside' has no zero crossing");

    const auto blank = openvdb::FloatGrid::create(0.3f);
    blank->setGridClass(openvdb::GRID_LEVEL_SET);
    const fs::path blank_file = dir.path() / "blank.vdb";
    write_with_openvdb(blank_file, {blank});
    expect_refused(blank_file, "has no active voxels");
}

/// A vec3s grid of the field (−y, x, 0.5) at the voxels [−20, 20]³ of size 0.1.
openvdb::Vec3SGrid::Ptr rotation_grid() {
    const auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    grid->setName("velocity");
    auto accessor = grid->getAccessor();
    for (int i = -20; i <= 20; ++i)
        for (int j = -20; j <= 20; ++j)
            for (int k = -20; k <= 20; ++k)
                accessor.setValue(openvdb::Coord(i, j, k),
                                  openvdb::Vec3s(static_cast<float>(-0.1 * j),
                                                 static_cast<float>(0.1 * i), 0.5f));
    return grid;
}

TEST(VdbField, SamplesARotationWithinItsActiveVoxels) {
    const TempDir dir("slc_vdb");
    const fs::path path = dir.path() / "field.vdb";
    write_with_openvdb(path, {rotation_grid()});
    const auto law = vdb_field_law(path);
    EXPECT_TRUE(law->is_field());
    EXPECT_EQ(law->name(), "field-file " + path.string());
    const std::optional<Box3> extent = law->extent();
    ASSERT_TRUE(extent);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(extent->lo[a], -2.0, 1e-12);
        EXPECT_NEAR(extent->hi[a], 2.0, 1e-12);
    }
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> in(-1.95, 1.95);
    std::vector<Vec3> x(1000);
    for (Vec3& p : x) p = {in(rng), in(rng), in(rng)};
    std::vector<Vec3> u(x.size());
    law->sample(0.0, x, u);
    // Trilinear interpolation is exact for a linear field; the values are floats (6e−8
    // relative, at most 2 here).
    constexpr double float_rounding = 1e-6;
    for (std::size_t i = 0; i < x.size(); ++i) {
        EXPECT_NEAR(u[i].x, -x[i].y, float_rounding) << "seed 7, point " << i;
        EXPECT_NEAR(u[i].y, x[i].x, float_rounding) << "seed 7, point " << i;
        EXPECT_NEAR(u[i].z, 0.5, float_rounding) << "seed 7, point " << i;
    }
}

TEST(VdbField, TurnsASurfaceAFullTurnAsTheBuiltInRotationDoes) {
    // u = (−y, x, 0) on voxels 0.1 apart over [−2, 2]³ as a vec3s grid: trilinear interpolation
    // of a linear field is the field to float rounding, so a sphere off the axis turned once ends
    // as near where it started as under the built-in rotation at the same settings, to the
    // tolerance its steps trace their feet to (a tenth of ε: each run counts its own substeps).
    const TempDir dir("slc_vdb");
    const fs::path path = dir.path() / "turn.vdb";
    const auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    auto accessor = grid->getAccessor();
    for (int i = -20; i <= 20; ++i)
        for (int j = -20; j <= 20; ++j)
            for (int k = -20; k <= 20; ++k)
                accessor.setValue(openvdb::Coord(i, j, k),
                                  openvdb::Vec3s(static_cast<float>(-0.1 * j),
                                                 static_cast<float>(0.1 * i), 0.0f));
    write_with_openvdb(path, {grid});
    const Vec3 centre{0.8, 0.05, 0.1};
    constexpr double radius = 0.4;
    const Surface start = sphere(centre, radius, 3);
    SurfaceRunOptions o;
    o.t_end = 2.0 * std::numbers::pi;
    o.steps = 32;
    o.step.contour = {
        .depth = 5, .refine_passes = SurfaceContourOptions::until_converged, .eps = 1e-3};
    const auto off_the_start = [&](const SurfaceVelocityLaw& law) {
        const SurfaceRunResult r = run(start, law, Box3::centered_cube(1.5), o);
        EXPECT_EQ(r.status, RunStatus::ok) << r.message;
        double worst = 0.0;
        for (const Vec3& x : r.surface.vertices)
            worst = std::max(worst, std::abs(distance(x, centre) - radius));
        return worst;
    };
    const double builtin = off_the_start(SurfaceRotation());
    const double from_file = off_the_start(*vdb_field_law(path));
    RecordProperty("builtin_error", std::to_string(builtin));
    RecordProperty("vdb_field_error", std::to_string(from_file));
    EXPECT_LT(builtin, 0.01);
    EXPECT_NEAR(from_file, builtin, 0.1 * *o.step.contour.eps);
}

TEST(VdbField, RefusesFilesWithoutAVectorGrid) {
    const TempDir dir("slc_vdb");
    const auto ball =
        openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0.0f), 0.1f);
    ball->setName("ball");
    const fs::path level_set = dir.path() / "ball.vdb";
    write_with_openvdb(level_set, {ball});
    EXPECT_EQ(invalid_input_message([&] { vdb_field_law(level_set); }),
              level_set.string() +
                  ": no vector grid of vec3s or vec3d values (grids: 'ball' (class level set, "
                  "float values))");
    const fs::path both = dir.path() / "both.vdb";
    write_with_openvdb(both, {ball, rotation_grid()});
    EXPECT_EQ(vdb_field_law(both)->extent()->hi.x, vdb_field_law(both, "velocity")->extent()->hi.x);
    EXPECT_NE(invalid_input_message([&] {
                  vdb_field_law(both, "ball");
              }).find("grid 'ball' (class level set, float values) is not a vector grid"),
              std::string::npos);
    const fs::path blank = dir.path() / "blank.vdb";
    write_with_openvdb(blank, {openvdb::Vec3DGrid::create()});
    EXPECT_NE(invalid_input_message([&] { vdb_field_law(blank); }).find("has no active voxels"),
              std::string::npos);
    EXPECT_NE(invalid_input_message([&] {
                  vdb_field_law(dir.path() / "missing.vdb");
              }).find("cannot read"),
              std::string::npos);
}

}  // namespace
}  // namespace slc
