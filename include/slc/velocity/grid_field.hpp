/// @file
/// A steady velocity given at the points of a uniform lattice (`slc run --field-file PATH`),
/// bilinearly interpolated: the law, and the readers of its two file formats, CSV lines
/// `x,y,u,v` and legacy VTK STRUCTURED_POINTS (ASCII).
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "slc/velocity/velocity.hpp"

namespace slc {

/// Velocities at the points (x0 + i hx, y0 + j hy), 0 ≤ i < nx, 0 ≤ j < ny.
struct GridVelocity {
    Vec2 origin;               ///< (x0, y0), the point i = j = 0
    Vec2 spacing;              ///< (hx, hy), both positive
    std::size_t nx = 0;        ///< points along x, at least 2
    std::size_t ny = 0;        ///< points along y, at least 2
    std::vector<Vec2> values;  ///< the velocity at point (i, j) in values[i + nx·j]

    /// The lattice's box [x0, x0 + (nx − 1) hx] × [y0, y0 + (ny − 1) hy].
    Box box() const {
        return {origin,
                {origin.x + static_cast<double>(nx - 1) * spacing.x,
                 origin.y + static_cast<double>(ny - 1) * spacing.y}};
    }
};

/// The flow field u(x) bilinearly interpolated in the lattice cell holding x: exact for fields
/// linear in x and y (a rigid rotation), error at most h²/8 · max|∂²u| along each axis otherwise
/// (second order in the spacing h). Steady: t is ignored. Its extent() is the lattice's box,
/// outside which run() refuses the curves; sample() answers outside it too, with the velocity at
/// the nearest point of the box, since contouring samples the whole domain and characteristics
/// of points near the curve may leave the box for part of a step.
class GridField final : public FlowFieldLaw {
public:
    /// name: the law's name in messages. Throws InvalidInput naming `name` unless nx, ny ≥ 2,
    /// values.size() == nx·ny, the spacing is positive and everything is finite.
    GridField(GridVelocity grid, std::string name);
    std::string name() const override { return name_; }
    /// The field at each point, as the base's sample().
    void sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const override;
    std::optional<Box> extent() const override { return grid_.box(); }

    /// The interpolated velocity at x (clamped to the box).
    Vec2 operator()(Vec2 x) const;

private:
    GridVelocity grid_;
    std::string name_;
};

/// Parses CSV text: one line `x,y,u,v` per lattice point, in any order; blank lines and lines
/// starting with '#' are skipped, and a first line that is not four numbers is a header. The
/// distinct x (and y) must be evenly spaced, to a relative 1e−6 of the spacing, and every
/// lattice point must appear exactly once. source names the text in messages. Throws
/// InvalidInput naming source (and the line) for anything else.
GridVelocity parse_grid_csv(std::string_view text, const std::string& source);

/// Parses a legacy VTK file (ASCII, DATASET STRUCTURED_POINTS: DIMENSIONS nx ny 1, ORIGIN,
/// SPACING or ASPECT_RATIO) and takes the velocity from its first point-data array with 2 or 3
/// components (VECTORS, or a SCALARS or FIELD array with 2 or 3 components; a third component is
/// ignored). Throws InvalidInput naming source for binary files, other datasets, nz ≠ 1, no such
/// array, or malformed text.
GridVelocity parse_grid_vtk(std::string_view text, const std::string& source);

/// Reads a lattice velocity file: legacy VTK when its name ends in .vtk, CSV otherwise. Throws
/// InvalidInput naming the file when it cannot be read or parsed.
GridVelocity read_grid_velocity(const std::filesystem::path& path);

/// The GridField of the file at path, named "field-file <path>". Throws as read_grid_velocity.
std::unique_ptr<VelocityLaw> grid_field_law(const std::filesystem::path& path);

}  // namespace slc
