// Enright's test in OpenVDB, the peer docs/tables/enright.md measures slc against: a sphere of
// radius 0.15 about (0.35, 0.35, 0.35) as a narrow-band level set of voxel 1/R, advected by
// OpenVDB's own EnrightField (LeVeque's field times cos(πt/3)) with HJWENO5 in space and TVD-RK3
// in time (tools::LevelSetAdvection), stretched until t = 1.5 and back at t = 3. Prints one JSON
// line: R, the volumes at t = 0, 1.5 and 3 (tools::levelSetVolume), the volume change, the
// largest distance of the returned zero set (the vertices of tools::volumeToMesh) from the
// sphere, the shape error (the volume between the returned surface and the sphere over the
// sphere's, on the lattice bench/enright.py samples slc's on), wall seconds and threads.
//
//   enright_openvdb R [THREADS]
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetAdvect.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/VelocityFields.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

namespace {

/// The enclosed volume, 0 for a level set that has vanished (which LevelSetMeasure refuses).
double volume_of(const openvdb::FloatGrid& grid) {
    try {
        return openvdb::tools::levelSetVolume(grid);
    } catch (const openvdb::RuntimeError&) {
        return 0.0;
    }
}

/// The lattice of the shape error: n³ points at the centres of cells of width h from `low` in
/// x, y and z (bench/enright.py's).
constexpr int lattice_n = 100;
constexpr double lattice_low = 0.05, lattice_h = 0.006;

/// The share of a lattice cell inside, from the signed distance d at its centre.
double inside(double d) { return std::clamp(0.5 - d / lattice_h, 0.0, 1.0); }

/// The volume between the zero set of grid and the sphere over the sphere's volume, summed over
/// the lattice, the level set sampled trilinearly; -1 when the zero set leaves the lattice.
double shape_error(const openvdb::FloatGrid& grid, const std::vector<openvdb::Vec3s>& points,
                   openvdb::Vec3d centre, double radius) {
    const double high = lattice_low + lattice_n * lattice_h;
    for (const openvdb::Vec3s& p : points) {
        for (int k = 0; k < 3; ++k) {
            if (p[k] < lattice_low + lattice_h || p[k] > high - lattice_h) return -1.0;
        }
    }
    double sum = 0.0;
    for (int i = 0; i < lattice_n; ++i) {
        for (int j = 0; j < lattice_n; ++j) {
            for (int k = 0; k < lattice_n; ++k) {
                const openvdb::Vec3d x(lattice_low + (i + 0.5) * lattice_h,
                                       lattice_low + (j + 0.5) * lattice_h,
                                       lattice_low + (k + 0.5) * lattice_h);
                const double d = openvdb::tools::BoxSampler::sample(
                    grid.tree(), grid.transform().worldToIndex(x));
                sum += std::abs(inside(d) - inside((x - centre).length() - radius));
            }
        }
    }
    return sum * lattice_h * lattice_h * lattice_h / (4.0 / 3.0 * M_PI * radius * radius * radius);
}

}  // namespace

int main(int argc, char** argv) {
    const int resolution = argc > 1 ? std::atoi(argv[1]) : 0;
    const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
    if (resolution < 8 || resolution > 2048 || threads < 1) {
        std::fprintf(stderr, "usage: enright_openvdb R [THREADS] (8 <= R <= 2048)\n");
        return 2;
    }
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    openvdb::initialize();
    const openvdb::Vec3f centre(0.35f);
    const float radius = 0.15f;
    const auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
        radius, centre, 1.0f / static_cast<float>(resolution), 3.0f);
    using Field = openvdb::tools::EnrightField<float>;
    openvdb::tools::LevelSetAdvection<openvdb::FloatGrid, Field> advection(*grid, Field());
    advection.setSpatialScheme(openvdb::math::HJWENO5_BIAS);
    advection.setTemporalScheme(openvdb::math::TVD_RK3);
    advection.setTrackerSpatialScheme(openvdb::math::HJWENO5_BIAS);
    advection.setTrackerTemporalScheme(openvdb::math::TVD_RK1);

    const double volume0 = volume_of(*grid);
    double volume_half = 0.0;
    const auto start = std::chrono::steady_clock::now();
    // In chunks of 0.05 (the advection takes its own CFL steps within each).
    for (int i = 0; i < 60; ++i) {
        advection.advect(0.05f * static_cast<float>(i), 0.05f * static_cast<float>(i + 1));
        if (i == 29) volume_half = volume_of(*grid);
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double volume1 = volume_of(*grid);

    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*grid, points, triangles, quads, 0.0);
    double distance = 0.0;
    for (const openvdb::Vec3s& p : points) {
        const openvdb::Vec3d d = openvdb::Vec3d(p) - openvdb::Vec3d(centre);
        distance = std::max(distance, std::abs(d.length() - radius));
    }
    const double shape = shape_error(*grid, points, openvdb::Vec3d(centre), radius);
    std::printf(
        "{\"R\": %d, \"volume_initial\": %.10g, \"volume_half\": %.10g, \"volume_final\": %.10g, "
        "\"volume_change\": %.6g, \"distance\": %.6g, \"shape_error\": %.6g, \"wall_s\": %.4g, "
        "\"threads\": %d}\n",
        resolution, volume0, volume_half, volume1, (volume1 - volume0) / volume0,
        points.empty() ? -1.0 : distance, shape, wall, threads);
    return 0;
}
