/// @file
/// OpenVDB level sets in and out (DESIGN §8, files): a surface read from the zero set of a
/// level-set grid, contoured by contour_surface (paper §2 with d = 3) from the grid's trilinear
/// interpolant; a surface written as a narrow-band level set whose values are the exact signed
/// distances of SurfaceDistanceTree (paper §1.3) at the voxel centres; and a vector grid read as
/// a steady flow field that moves surfaces. OpenVDB's own
/// headers stay in the source (src/io/vdb.cpp): this header needs none of them.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "slc/geometry/surface.hpp"
#include "slc/velocity/velocity.hpp"

namespace slc {

/// True when path names an OpenVDB file by its extension (.vdb, any case).
bool is_vdb_file(const std::filesystem::path& path);

/// What read_vdb_level_set reads, and how finely it contours.
struct VdbReadOptions {
    /// The grid to read by name; empty (the default): the file's first level-set grid.
    std::string grid;
    /// K, the depth of the contouring octree; unset (the default): the depth whose cells are
    /// nearest a voxel wide (within a factor √2), so the contour resolves what the grid does.
    std::optional<int> depth = std::nullopt;
};

/// The zero set of a level-set grid (class GRID_LEVEL_SET, float or double values) of the
/// OpenVDB file at path, as a closed surface facing outward (the grid negative inside, as slc's
/// signed distance). G is the grid's trilinear interpolant (openvdb::tools::BoxSampler) in world
/// coordinates, contoured by contour_surface in the cube around the grid's active voxels with a
/// margin of a tenth of its width and at least four voxels; its vertices lie on the zero set of G
/// to 10⁻¹⁰. NOTE: the grid's transform should be linear (uniform or affine); a frustum grid is
/// read through the same world-space sampler, which is then only as exact as its voxels.
/// Throws InvalidInput, one line naming the file: a file that is missing or cannot be read, is
/// not an OpenVDB file or is truncated; no grids; no grid of that name; a grid that is not a
/// float or double level set (a fog volume, a vector grid: named with its class and type); no
/// active voxels; no zero crossing; a zero set that reaches the edge of the active voxels or
/// values that are not finite. Cost: about (area / voxel²) evaluations of G, each O(log voxels).
Surface read_vdb_level_set(const std::filesystem::path& path, const VdbReadOptions& options = {});

/// How write_vdb_level_set writes.
struct VdbWriteOptions {
    /// h > 0: the voxel size (world units), the grid's uniform linear transform.
    double voxel = 0.0;
    /// w ≥ 1: the narrow band's half-width in voxels; OpenVDB's tools expect 3 (the default).
    /// The background value is w·h; voxels whose centre lies within w·h of the surface are active.
    double half_width = 3.0;
    /// The grid's name in the file.
    std::string name = "surface";
};

/// The largest voxel count along a side of the box write_vdb_level_set would cover: a finer
/// voxel for that surface is refused (InvalidInput naming the voxel size).
inline constexpr double max_vdb_voxels_per_side = 16384.0;

/// Writes a valid surface (prepare_surface) to path as an OpenVDB file holding one FloatGrid of
/// class GRID_LEVEL_SET: the exact signed distance (negative inside) of the surface at each voxel
/// centre within the band, computed by SurfaceDistanceTree; inactive voxels and tiles carry the
/// background value ±w·h with the sign of their side (openvdb::tools::signedFloodFill). The
/// voxels examined are those of the leaf nodes (8³ voxels) whose centre lies within w·h plus
/// their half-diagonal of the surface, so the cost is about (area / h²)·w distance queries. The
/// file is the same for any number of threads. Throws InvalidInput for an empty surface, a voxel
/// size that is not positive and finite or too fine for the surface (max_vdb_voxels_per_side), a
/// half-width below 1, or a path that cannot be written ("cannot write PATH: reason").
void write_vdb_level_set(const std::filesystem::path& path, const Surface& surface,
                         const VdbWriteOptions& options);

/// A steady flow field from the vector grid (vec3s or vec3d values) of the OpenVDB file at path:
/// the first such grid, or the one named grid. u(x) is the grid's trilinear interpolant in world
/// coordinates (OpenVDB's BoxSampler; StaggeredBoxSampler for a grid of class staggered), exact
/// for a field linear in x (a rotation) and second order in the voxel otherwise; t is ignored.
/// Its extent() is the world box of the centres of the grid's active voxels: a run refuses a
/// surface that starts outside it and ends with an error naming the time and the point where the
/// surface leaves it (sample() answers everywhere, as contouring needs). The law is named
/// "field-file PATH". NOTE: for a sparse grid the box also holds inactive voxels, whose value
/// (the background, often zero) the field then takes. Throws InvalidInput, one line naming the
/// file, as read_vdb_level_set for the file itself; for no vector grid (each grid named with its
/// class and value type), no grid of that name, or no active voxels.
std::unique_ptr<SurfaceVelocityLaw> vdb_field_law(const std::filesystem::path& path,
                                                  const std::string& grid = {});

}  // namespace slc
