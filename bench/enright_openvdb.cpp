// Enright's test in OpenVDB, the peer docs/tables/enright.md measures slc against: a sphere of
// radius 0.15 about (0.35, 0.35, 0.35) as a narrow-band level set of voxel 1/R, advected by
// OpenVDB's own EnrightField (LeVeque's field times cos(πt/3)) with HJWENO5 in space and TVD-RK3
// in time (tools::LevelSetAdvection), stretched until t = 1.5 and back at t = 3. Prints one JSON
// line: R, the volumes at t = 0, 1.5 and 3 (tools::levelSetVolume), the volume change, the
// largest distance of the returned zero set (the vertices of tools::volumeToMesh) from the
// sphere, the shape error (the volume between the returned surface and the sphere over the
// sphere's, on the lattice N LOW H that bench/enright.py samples slc's on; −1 without it), wall
// seconds and threads.
//
//   enright_openvdb R [THREADS [N LOW H]]
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

/// The lattice of the shape error, as bench/enright.py gives it: n³ cells of width h from `low`
/// in x, y and z.
struct Lattice {
    int n = 0;
    double low = 0.0, h = 0.0;
};

/// The volume between the zero set of grid and the sphere over the sphere's volume, summed over
/// the lattice, each cell's share inside clamp(1/2 − d/h, 0, 1) from the signed distance d at its
/// centre, the level set sampled trilinearly; −1 when the zero set leaves the lattice.
double shape_error(const openvdb::FloatGrid& grid, const std::vector<openvdb::Vec3s>& points,
                   openvdb::Vec3d centre, double radius, const Lattice& l) {
    auto inside = [&](double d) { return std::clamp(0.5 - d / l.h, 0.0, 1.0); };
    const double high = l.low + l.n * l.h;
    for (const openvdb::Vec3s& p : points) {
        for (int k = 0; k < 3; ++k) {
            if (p[k] < l.low + l.h || p[k] > high - l.h) return -1.0;
        }
    }
    double sum = 0.0;
    for (int i = 0; i < l.n; ++i) {
        for (int j = 0; j < l.n; ++j) {
            for (int k = 0; k < l.n; ++k) {
                const openvdb::Vec3d x(l.low + (i + 0.5) * l.h, l.low + (j + 0.5) * l.h,
                                       l.low + (k + 0.5) * l.h);
                const double d = openvdb::tools::BoxSampler::sample(
                    grid.tree(), grid.transform().worldToIndex(x));
                sum += std::abs(inside(d) - inside((x - centre).length() - radius));
            }
        }
    }
    return sum * l.h * l.h * l.h / (4.0 / 3.0 * M_PI * radius * radius * radius);
}

}  // namespace

int main(int argc, char** argv) {
    const int resolution = argc > 1 ? std::atoi(argv[1]) : 0;
    const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
    const Lattice lattice =
        argc > 5 ? Lattice{std::atoi(argv[3]), std::atof(argv[4]), std::atof(argv[5])} : Lattice{};
    if (resolution < 8 || resolution > 2048 || threads < 1) {
        std::fprintf(stderr,
                     "usage: enright_openvdb R [THREADS [N LOW H]] (8 <= R <= 2048; the shape "
                     "error's lattice, none without it)\n");
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
    const double shape = lattice.n > 0 && lattice.h > 0.0
                             ? shape_error(*grid, points, openvdb::Vec3d(centre), radius, lattice)
                             : -1.0;
    std::printf(
        "{\"R\": %d, \"volume_initial\": %.10g, \"volume_half\": %.10g, \"volume_final\": %.10g, "
        "\"volume_change\": %.6g, \"distance\": %.6g, \"shape_error\": %.6g, \"wall_s\": %.4g, "
        "\"threads\": %d}\n",
        resolution, volume0, volume_half, volume1, (volume1 - volume0) / volume0,
        points.empty() ? -1.0 : distance, shape, wall, threads);
    return 0;
}
