// A steady velocity on a uniform lattice, bilinearly interpolated (slc run --field-file).
#include "slc/velocity/grid_field.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

/// The cell index and the fraction along it of coordinate s in lattice units, clamped to the
/// lattice [0, n − 1]: cell i in [0, n − 2], fraction in [0, 1].
std::pair<std::size_t, double> locate(double s, std::size_t n) {
    const double last = static_cast<double>(n - 1);
    s = std::clamp(s, 0.0, last);
    const std::size_t i = std::min(static_cast<std::size_t>(s), n - 2);
    return {i, s - static_cast<double>(i)};
}

}  // namespace

GridField::GridField(GridVelocity grid, std::string name)
    : grid_(std::move(grid)), name_(std::move(name)) {
    const GridVelocity& g = grid_;
    if (g.nx < 2 || g.ny < 2) {
        throw InvalidInput(fmt::format(
            "velocity '{}': the lattice needs at least 2 points along x and along y, got {} x {}",
            name_, g.nx, g.ny));
    }
    if (g.values.size() != g.nx * g.ny) {
        throw InvalidInput(fmt::format("velocity '{}': {} velocities for a {} x {} lattice", name_,
                                       g.values.size(), g.nx, g.ny));
    }
    if (!is_finite(g.origin) || !(g.spacing.x > 0.0) || !(g.spacing.y > 0.0) ||
        !is_finite(g.spacing) || !is_finite(g.box().hi)) {
        throw InvalidInput(fmt::format(
            "velocity '{}': the lattice needs a finite origin and positive spacing, got origin "
            "({}, {}) and spacing ({}, {})",
            name_, g.origin.x, g.origin.y, g.spacing.x, g.spacing.y));
    }
    for (std::size_t k = 0; k < g.values.size(); ++k) {
        if (!is_finite(g.values[k])) {
            throw InvalidInput(
                fmt::format("velocity '{}': the velocity at lattice point ({}, {}) "
                            "is not finite",
                            name_, k % g.nx, k / g.nx));
        }
    }
}

Vec2 GridField::operator()(Vec2 x) const {
    const GridVelocity& g = grid_;
    const auto [i, a] = locate((x.x - g.origin.x) / g.spacing.x, g.nx);
    const auto [j, b] = locate((x.y - g.origin.y) / g.spacing.y, g.ny);
    const Vec2* row = g.values.data() + j * g.nx + i;
    const Vec2 below = (1.0 - a) * row[0] + a * row[1];
    const Vec2 above = (1.0 - a) * row[g.nx] + a * row[g.nx + 1];
    return (1.0 - b) * below + b * above;
}

void GridField::sample(double, std::span<const Vec2> points, std::span<Vec2> out) const {
    parallel_for(points.size(), [&](std::size_t i) { out[i] = (*this)(points[i]); });
}

std::unique_ptr<VelocityLaw> grid_field_law(const std::filesystem::path& path) {
    return std::make_unique<GridField>(read_grid_velocity(path), "field-file " + path.string());
}

}  // namespace slc
