/// @file
/// OpenVDB level sets in and out, and vector grids as flow fields (vdb.hpp): the only file that
/// includes OpenVDB's headers. A level set is read by contouring its trilinear interpolant (paper
/// §2, d = 3) and written as the exact signed distance of the surface (paper §1.3) in a narrow
/// band of voxels.
#include "slc/io/vdb.hpp"

#include <fmt/format.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/SignedFloodFill.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <ios>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "slc/contour/surface_contour.hpp"
#include "slc/core/error.hpp"
#include "slc/core/input_text.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/tree/tetrahedralization.hpp"

namespace slc {

namespace {

/// An exception's message on one line, as the tool prints it.
std::string one_line(const char* what) {
    std::string s = what;
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

/// A grid as a message names it: 'name' (class, values).
std::string described(const openvdb::GridBase& grid) {
    return fmt::format("'{}' (class {}, {} values)", one_line(grid.getName().c_str()),
                       openvdb::GridBase::gridClassToString(grid.getGridClass()), grid.valueType());
}

bool is_level_set(const openvdb::GridBase& grid) {
    return grid.getGridClass() == openvdb::GRID_LEVEL_SET &&
           (grid.isType<openvdb::FloatGrid>() || grid.isType<openvdb::DoubleGrid>());
}

bool is_vector_grid(const openvdb::GridBase& grid) {
    return grid.isType<openvdb::Vec3SGrid>() || grid.isType<openvdb::Vec3DGrid>();
}

/// The world box of the centres of voxels [lo, hi] (an index box) under a linear transform.
Box3 world_box(const openvdb::math::Transform& transform, const openvdb::Vec3d& lo,
               const openvdb::Vec3d& hi) {
    Box3 world = Box3::empty();
    for (int corner = 0; corner < 8; ++corner) {
        const openvdb::Vec3d index(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y(),
                                   corner & 4 ? hi.z() : lo.z());
        const openvdb::Vec3d p = transform.indexToWorld(index);
        const Vec3 q{p.x(), p.y(), p.z()};
        world = unite(world, Box3{q, q});
    }
    return world;
}

/// All the grids of the file at path, read whole. Any failure of OpenVDB's reader (not an
/// OpenVDB file, a truncated one, an unknown grid type) is InvalidInput naming the file.
openvdb::GridPtrVecPtr file_grids(const std::filesystem::path& path) {
    const std::uintmax_t size = regular_file_size(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw cannot_read(path, errno);
    // OpenVDB's reader does not check every read: a stream that throws at the first short read
    // turns a truncated file into an error instead of grids made of whatever followed.
    in.exceptions(std::ios::failbit | std::ios::badbit);
    openvdb::initialize();
    try {
        openvdb::io::Stream stream(in, /*delayLoad=*/false);
        return stream.getGrids();
    } catch (const std::ios_base::failure&) {
        throw InvalidInput(fmt::format(
            "{}: not a readable OpenVDB file: its {} bytes end before its grids do (truncated?)",
            path.string(), size));
    } catch (const std::exception& e) {
        throw InvalidInput(fmt::format("{}: not a readable OpenVDB file of {} bytes ({})",
                                       path.string(), size, one_line(e.what())));
    }
}

/// What read_vdb_level_set and vdb_field_law read: a test of a grid, and how messages say it
/// ("level-set grid of ...", "level set of ...").
struct GridKind {
    bool (*fits)(const openvdb::GridBase&);
    const char* grid;  ///< "no {grid}"
    const char* one;   ///< "grid 'x' is not a {one}"
};

/// The grid `name` names, or the first grid of its kind; a clear error when there is none.
openvdb::GridBase::Ptr chosen_grid(const openvdb::GridPtrVec& grids, const std::string& source,
                                   const std::string& name, const GridKind& kind) {
    if (grids.empty()) throw InvalidInput(fmt::format("{}: no grids", source));
    std::string all;
    for (const auto& g : grids) all += (all.empty() ? "" : ", ") + described(*g);
    if (!name.empty()) {
        for (const auto& g : grids) {
            if (g->getName() != name) continue;
            if (!kind.fits(*g)) {
                throw InvalidInput(
                    fmt::format("{}: grid {} is not a {}", source, described(*g), kind.one));
            }
            return g;
        }
        throw InvalidInput(
            fmt::format("{}: no grid named '{}' (grids: {})", source, one_line(name.c_str()), all));
    }
    for (const auto& g : grids)
        if (kind.fits(*g)) return g;
    throw InvalidInput(fmt::format("{}: no {} (grids: {})", source, kind.grid, all));
}

/// The contour of a level set's trilinear interpolant (read_vdb_level_set).
template <class GridT>
Surface contoured(const GridT& grid, const std::string& source, const VdbReadOptions& options) {
    const std::string what =
        fmt::format("{}: level set '{}'", source, one_line(grid.getName().c_str()));
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    if (active.empty()) throw InvalidInput(fmt::format("{} has no active voxels", what));

    // The world box of the active voxels: their index box grown by half a voxel (voxel
    // centres sit at integer index coordinates), its eight corners mapped to world space.
    const openvdb::math::Transform& transform = grid.transform();
    const Box3 world = world_box(transform, active.min().asVec3d() - openvdb::Vec3d(0.5),
                                 active.max().asVec3d() + openvdb::Vec3d(0.5));
    const openvdb::Vec3d sizes = transform.voxelSize();
    const double voxel = std::min({sizes.x(), sizes.y(), sizes.z()});
    const double width = std::max({world.extent(0), world.extent(1), world.extent(2)});
    // Room around the band for the contour tree, which must not meet the zero set at its edge.
    const double margin = std::max(0.1 * width, 4.0 * voxel);
    const Box3 domain = Box3::cube(world.center(), 0.5 * width + margin);

    SurfaceContourOptions contour;
    if (options.depth) {
        contour.depth = *options.depth;
    } else {
        // The depth whose cells are nearest a voxel wide (within a factor √2): finer cells
        // would only sample the same trilinear pieces again, coarser ones miss what they hold.
        const double cells = std::round(std::log2(domain.width() / voxel));
        contour.depth = static_cast<int>(std::clamp(cells, 1.0, double{max_tetrahedralized_depth}));
    }
    const openvdb::tools::GridSampler<GridT, openvdb::tools::BoxSampler> sampler(grid);
    // The sampler reads the tree without a cache: safe on all threads at once.
    const auto g = pointwise<Vec3>([&sampler](Vec3 x) {
        return static_cast<double>(sampler.wsSample(openvdb::Vec3d(x.x, x.y, x.z)));
    });
    SurfaceContour result;
    try {
        result = contour_surface(g, domain, contour);
    } catch (const NumericalFailure& e) {
        throw InvalidInput(fmt::format("{}: {}", what, one_line(e.what())));
    }
    if (result.surface.empty()) {
        const bool inside = grid.background() < 0;
        throw InvalidInput(fmt::format("{} has no zero crossing (its values are {} than 0)", what,
                                       inside ? "less" : "greater"));
    }
    return std::move(result.surface);
}

/// Checks write_vdb_level_set's input; returns the index box of the voxels to examine.
openvdb::CoordBBox voxel_box(const Surface& surface, const VdbWriteOptions& options) {
    if (surface.empty()) throw InvalidInput("cannot write an empty surface as a level set");
    const double h = options.voxel;
    if (!(h > 0.0) || !std::isfinite(h)) {
        throw InvalidInput(fmt::format("voxel size must be positive and finite, got {}", h));
    }
    if (!(options.half_width >= 1.0) || !std::isfinite(options.half_width)) {
        throw InvalidInput(fmt::format("narrow-band half-width must be at least 1 voxel, got {}",
                                       options.half_width));
    }
    const double band = options.half_width * h;
    const Box3 bounds = bounding_box(surface);
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
        const double first = std::floor((bounds.lo[a] - band) / h);
        const double last = std::ceil((bounds.hi[a] + band) / h);
        if (!(last - first <= max_vdb_voxels_per_side) || !(std::abs(first) < 1e9) ||
            !(std::abs(last) < 1e9)) {
            throw InvalidInput(fmt::format(
                "voxel size {} is too fine for a surface {} wide: more than {} voxels a side", h,
                bounds.extent(a), max_vdb_voxels_per_side));
        }
        lo[static_cast<std::size_t>(a)] = static_cast<int>(first);
        hi[static_cast<std::size_t>(a)] = static_cast<int>(last);
    }
    return {openvdb::Coord(lo[0], lo[1], lo[2]), openvdb::Coord(hi[0], hi[1], hi[2])};
}

/// The centre of voxel ijk in world space (the transform is i·h).
Vec3 voxel_centre(const openvdb::Coord& ijk, double h) {
    return {ijk.x() * h, ijk.y() * h, ijk.z() * h};
}

/// Writes grids to path through a temporary file beside it, renamed when complete, so that a
/// failure leaves any earlier file whole.
void write_grids(const std::filesystem::path& path, const openvdb::GridPtrVec& grids) {
    write_file_atomic(path, [&grids](const std::filesystem::path& temp) {
        try {
            openvdb::io::File file(temp.string());
            file.write(grids);
            file.close();
        } catch (const std::exception& e) {
            throw std::runtime_error(one_line(e.what()));
        }
    });
}

/// A vector grid as a steady flow field (vdb_field_law).
template <class GridT, class Sampler>
class VdbField final : public SurfaceFlowFieldLaw {
public:
    VdbField(typename GridT::ConstPtr grid, Box3 extent, std::string name)
        : grid_(std::move(grid)), sampler_(*grid_), extent_(extent), name_(std::move(name)) {}
    std::string name() const override { return name_; }
    void sample(double, std::span<const Vec3> points, std::span<Vec3> out) const override {
        // The sampler reads the tree without a cache: safe on all threads at once.
        parallel_for(points.size(), [&](std::size_t i) {
            const Vec3 x = points[i];
            const auto u = sampler_.wsSample(openvdb::Vec3d(x.x, x.y, x.z));
            out[i] = {static_cast<double>(u.x()), static_cast<double>(u.y()),
                      static_cast<double>(u.z())};
        });
    }
    std::optional<Box3> extent() const override { return extent_; }

private:
    typename GridT::ConstPtr grid_;  ///< owned here; the sampler refers to it
    openvdb::tools::GridSampler<GridT, Sampler> sampler_;
    Box3 extent_;
    std::string name_;
};

template <class GridT>
std::unique_ptr<SurfaceVelocityLaw> field_of(typename GridT::ConstPtr grid,
                                             const std::string& source) {
    const openvdb::CoordBBox active = grid->evalActiveVoxelBoundingBox();
    if (active.empty()) {
        throw InvalidInput(fmt::format("{}: vector grid '{}' has no active voxels", source,
                                       one_line(grid->getName().c_str())));
    }
    const Box3 extent =
        world_box(grid->transform(), active.min().asVec3d(), active.max().asVec3d());
    std::string name = "field-file " + source;
    if (grid->getGridClass() == openvdb::GRID_STAGGERED) {
        return std::make_unique<VdbField<GridT, openvdb::tools::StaggeredBoxSampler>>(
            std::move(grid), extent, std::move(name));
    }
    return std::make_unique<VdbField<GridT, openvdb::tools::BoxSampler>>(std::move(grid), extent,
                                                                         std::move(name));
}

}  // namespace

bool is_vdb_file(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".vdb";
}

std::unique_ptr<SurfaceVelocityLaw> vdb_field_law(const std::filesystem::path& path,
                                                  const std::string& grid) {
    const openvdb::GridPtrVecPtr grids = file_grids(path);
    const std::string source = path.string();
    const openvdb::GridBase::Ptr chosen =
        chosen_grid(*grids, source, grid,
                    {is_vector_grid, "vector grid of vec3s or vec3d values",
                     "vector grid of vec3s or vec3d values"});
    if (const auto f = openvdb::gridConstPtrCast<openvdb::Vec3SGrid>(chosen))
        return field_of<openvdb::Vec3SGrid>(f, source);
    return field_of<openvdb::Vec3DGrid>(openvdb::gridConstPtrCast<openvdb::Vec3DGrid>(chosen),
                                        source);
}

Surface read_vdb_level_set(const std::filesystem::path& path, const VdbReadOptions& options) {
    const openvdb::GridPtrVecPtr grids = file_grids(path);
    const std::string source = path.string();
    const openvdb::GridBase::Ptr grid =
        chosen_grid(*grids, source, options.grid,
                    {is_level_set, "level-set grid of float or double values",
                     "level set of float or double values"});
    if (const auto f = openvdb::gridConstPtrCast<openvdb::FloatGrid>(grid))
        return contoured(*f, source, options);
    return contoured(*openvdb::gridConstPtrCast<openvdb::DoubleGrid>(grid), source, options);
}

void write_vdb_level_set(const std::filesystem::path& path, const Surface& surface,
                         const VdbWriteOptions& options) {
    const openvdb::CoordBBox box = voxel_box(surface, options);
    const double h = options.voxel;
    const double band = options.half_width * h;
    openvdb::initialize();

    // The distance tree's cube holds every voxel examined, so that each query starts in a leaf.
    const Box3 bounds = bounding_box(surface);
    const double reach = band + 16.0 * h;
    const Box3 domain =
        Box3::cube(bounds.center(),
                   0.5 * std::max({bounds.extent(0), bounds.extent(1), bounds.extent(2)}) + reach);
    const SurfaceDistanceTree tree(surface, domain,
                                   {SurfaceDistanceTree::default_depth(surface, domain), false});

    // Leaf-node blocks of 8³ voxels (origins multiples of 8) covering the box; a block is
    // examined voxel by voxel only when its centre lies within the band plus the distance from
    // its centre to its farthest voxel centre, since |F| changes no faster than distance.
    constexpr int leaf = 8;
    const openvdb::Coord first(box.min().x() & ~(leaf - 1), box.min().y() & ~(leaf - 1),
                               box.min().z() & ~(leaf - 1));
    std::vector<openvdb::Coord> origins;
    std::vector<Vec3> centres;
    for (int i = first.x(); i <= box.max().x(); i += leaf)
        for (int j = first.y(); j <= box.max().y(); j += leaf)
            for (int k = first.z(); k <= box.max().z(); k += leaf) {
                origins.emplace_back(i, j, k);
                const double c = 0.5 * (leaf - 1);
                centres.push_back({(i + c) * h, (j + c) * h, (k + c) * h});
            }
    const std::vector<double> at_centres = tree.signed_distances(centres);
    const double half_diagonal = std::sqrt(3.0) * 0.5 * (leaf - 1) * h;

    const auto grid = openvdb::FloatGrid::create(static_cast<float>(band));
    grid->setTransform(openvdb::math::Transform::createLinearTransform(h));
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setName(options.name);
    auto accessor = grid->getAccessor();

    // Near blocks a few thousand at a time, their voxels' distances in one batch each.
    constexpr std::size_t blocks_per_batch = 2048;
    std::vector<openvdb::Coord> voxels;
    std::vector<Vec3> points;
    auto flush = [&] {
        const std::vector<double> d = tree.signed_distances(points);
        for (std::size_t v = 0; v < voxels.size(); ++v)
            if (std::abs(d[v]) < band) accessor.setValue(voxels[v], static_cast<float>(d[v]));
        voxels.clear();
        points.clear();
    };
    for (std::size_t b = 0; b < origins.size(); ++b) {
        if (!(std::abs(at_centres[b]) < band + half_diagonal)) continue;
        const openvdb::Coord& o = origins[b];
        for (int i = o.x(); i < o.x() + leaf; ++i)
            for (int j = o.y(); j < o.y() + leaf; ++j)
                for (int k = o.z(); k < o.z() + leaf; ++k) {
                    voxels.emplace_back(i, j, k);
                    points.push_back(voxel_centre(voxels.back(), h));
                }
        if (voxels.size() >= blocks_per_batch * leaf * leaf * leaf) flush();
    }
    flush();
    // Inactive voxels and tiles take ±background by the side they lie on.
    openvdb::tools::signedFloodFill(grid->tree());
    write_grids(path, {grid});
}

}  // namespace slc
