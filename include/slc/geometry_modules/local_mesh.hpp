/// @file
/// LocalMesh: the local uniform mesh of the embedded geometry module (paper §3.2, Figure 9), the
/// points of a uniform lattice of spacing h that lie within R lattice steps of Γ, stored as sorted,
/// pruned x-intervals (runs of a row) and the y-intervals (runs of a column) of the same points.
/// Memory and cost grow with (length of Γ)/h · R, never with the number of lattice points of the
/// domain. Also the operations the embedded module applies on it: ENO differences along rows or
/// columns, cosine smoothing, and ENO interpolation at any point near Γ.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry_modules/eno.hpp"

namespace slc {

/// The lattice points origin + (i, j)·h, i and j integers, whose L∞ distance to Γ is at most
/// range·h: the union over the segments of Γ of the segment grown by a square of half-width
/// range·h (the sets the paper's two passes, horizontal then vertical, produce).
///
/// Points are numbered row by row (increasing j, then increasing i), so the points of an
/// x-interval are consecutive. The y-intervals list the same points column by column; position p
/// of the column order holds point column_order()[p].
class LocalMesh {
public:
    /// A run of consecutive lattice points: x-interval (lo..hi, line) = points (i, line) for
    /// i = lo..hi, or y-interval = points (line, j) for j = lo..hi. `first` is the number of its
    /// first point (x-intervals) or its first position in the column order (y-intervals).
    struct Interval {
        std::int32_t line = 0;    ///< the row j (x-interval) or the column i (y-interval)
        std::int32_t lo = 0;      ///< first lattice index along the line
        std::int32_t hi = 0;      ///< last lattice index along the line, hi >= lo
        std::uint32_t first = 0;  ///< first point number, or first position in the column order

        /// Number of points, hi − lo + 1.
        std::size_t size() const { return static_cast<std::size_t>(hi - lo) + 1; }
    };

    /// No points.
    LocalMesh() = default;

    /// Builds the mesh around curves with lattice origin and spacing h > 0, range >= 1 steps:
    /// one x-interval per segment and row it reaches (extending the row's last one where they
    /// overlap or touch, as consecutive segments' do), sorted by (row, start) and merged where
    /// they overlap or touch; the y-intervals by a counting sort of the points by column.
    /// Throws InvalidInput for an empty interface, h <= 0 or non-finite, range < 1, or a lattice
    /// index beyond ±2^30. Cost O(I log I + P + W) for I raw intervals, P points, W columns.
    LocalMesh(const Interface& curves, Vec2 origin, double h, int range);

    /// Number of mesh points.
    std::size_t size() const { return size_; }
    /// h, the lattice spacing.
    double spacing() const { return h_; }
    /// The lattice point (0, 0).
    Vec2 origin() const { return origin_; }
    /// R: points lie within R lattice steps of Γ (L∞ distance).
    int range() const { return range_; }

    /// The x-intervals, sorted by row and then by start; disjoint and not adjacent.
    std::span<const Interval> rows() const { return rows_; }
    /// The y-intervals, sorted by column and then by start; disjoint and not adjacent.
    std::span<const Interval> columns() const { return columns_; }
    /// Point number at each position of the column order.
    std::span<const std::uint32_t> column_order() const { return column_order_; }

    /// The lattice position origin + (i, j)·h.
    Vec2 position(std::int32_t i, std::int32_t j) const {
        return {origin_.x + i * h_, origin_.y + j * h_};
    }
    /// Positions of all points, in point order.
    std::vector<Vec2> points() const;
    /// The x-interval holding lattice point (i, j), if it is a mesh point. O(log of the number of
    /// intervals in row j).
    const Interval* row_interval(std::int32_t i, std::int32_t j) const;
    /// The number of lattice point (i, j), if it is a mesh point.
    std::optional<std::size_t> find(std::int32_t i, std::int32_t j) const;

private:
    void build_columns();

    Vec2 origin_;
    double h_ = 1.0;
    int range_ = 1;
    std::size_t size_ = 0;
    std::vector<Interval> rows_;
    std::int32_t first_row_ = 0;
    std::vector<std::uint32_t>
        row_offsets_;  ///< x-intervals of row j: [row_offsets_[j − first_row_], +1)
    std::vector<Interval> columns_;
    std::vector<std::uint32_t> column_order_;
};

/// The direction of a difference on the mesh.
enum class Axis { x, y };

/// ∂f/∂x or ∂f/∂y at every mesh point, by ENO differences of order `order` (1..eno::max_order)
/// along its x- or y-interval (one-sided near the interval's ends). values.size() == mesh.size().
/// Error O(h^order) where f is smooth over the stencil. `bias` as for eno::derivative (1: the
/// plain ENO rule). Parallel; independent of thread count.
std::vector<double> derivative(const LocalMesh& mesh, std::span<const double> values, Axis axis,
                               int order, double bias = 1.0);

/// `passes` passes of cosine smoothing, each one 1-2-1 pass along the x-intervals followed by one
/// along the y-intervals (the tensor filter (1 2 1)⊗(1 2 1)/16 inside). Interval ends are left
/// unchanged by their pass. Smooth data moves by O(passes·h²).
std::vector<double> smoothed(const LocalMesh& mesh, std::span<const double> values, int passes);

/// ENO interpolation of order `order` of the mesh values at x: one-dimensional ENO interpolation
/// along each of the rows j − order + 1 .. j + order around x's lattice cell (i, j) that holds
/// the cell's corners, then along the column of those row values. Points of a row or column
/// missing from the mesh shorten the stencils there. Error O(h^(order+1)) for smooth data.
/// Returns nothing when a corner of x's lattice cell is not a mesh point.
std::optional<double> interpolate(const LocalMesh& mesh, std::span<const double> values, Vec2 x,
                                  int order);

/// The rows around one lattice cell and each field's ENO stencils along them: they depend on the
/// cell and the values, not on where in the cell a point lies, so interpolate() keeps them here
/// and reuses them for the next point in the same cell (consecutive vertices of a curve often
/// share one). Use one per thread, and only with the same mesh, fields and order.
struct CellStencils {
    static constexpr std::size_t max_fields = 4;  ///< fields interpolated at once, at most
    bool valid = false;                           ///< whether the rest holds a cell
    std::int32_t i = 0;                           ///< the lattice cell: its column
    std::int32_t j = 0;                           ///< and its row
    int lo = 0;                                   ///< rows[lo..hi] hold the cell's corners
    int hi = 0;                                   ///< (see lo)
    std::array<const LocalMesh::Interval*, 2 * eno::max_order> rows{};  ///< the rows around it
    /// Each field's ENO stencil along each row.
    std::array<std::array<eno::Stencil, 2 * eno::max_order>, max_fields> stencils{};
};

/// interpolate() of several fields at the same x, each with its own stencils: out[f] for
/// fields[f] (out.size() == fields.size()). The rows are looked up once for all fields; with a
/// cache (at most CellStencils::max_fields fields), once per lattice cell, and so are the
/// stencils. The results are the same with or without it. Returns false, leaving out
/// unspecified, when a corner of x's lattice cell is not a mesh point.
bool interpolate(const LocalMesh& mesh, std::span<const std::span<const double>> fields, Vec2 x,
                 int order, std::span<double> out, CellStencils* cache = nullptr);

}  // namespace slc
