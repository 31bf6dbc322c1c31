// LocalMesh: building the x- and y-intervals by sorting and pruning (paper §3.2, Fig. 9), and the
// ENO differences, smoothing and interpolation along them.
#include "slc/geometry_modules/local_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry_modules/eno.hpp"

namespace slc {
namespace {

/// Lattice indices are kept within ±2^30 so that i ± a few never overflows 32 bits.
constexpr double max_lattice_index = 1073741824.0;

/// Slack, in lattice units, by which a lattice point on the boundary of a segment's band still
/// counts as inside: rounding in the band's end points must not drop a point that belongs.
constexpr double lattice_slack = 1e-9;

/// No interval yet in a row.
constexpr std::uint32_t no_interval = 0xffffffffu;

/// The x-intervals that one segment (in lattice units, a → b) contributes: for every row j
/// within range of it, the lattice points of that row within L∞ distance range of the segment.
/// An interval that overlaps or touches the last one added to its row (last[j − first_row], which
/// a curve's previous segment usually made) extends it instead: the union, all that merged()
/// keeps, is the same, and the raw intervals are far fewer where segments are short.
void add_segment_intervals(Vec2 a, Vec2 b, double range, std::int32_t first_row,
                           std::vector<std::uint32_t>& last,
                           std::vector<LocalMesh::Interval>& out) {
    const double y_lo = std::min(a.y, b.y) - range, y_hi = std::max(a.y, b.y) + range;
    const auto j_lo = static_cast<std::int32_t>(std::ceil(y_lo - lattice_slack));
    const auto j_hi = static_cast<std::int32_t>(std::floor(y_hi + lattice_slack));
    const Vec2 d = b - a;
    for (std::int32_t j = j_lo; j <= j_hi; ++j) {
        // Parameters t in [0, 1] of the segment points within vertical distance range of row j.
        double t0 = 0.0, t1 = 1.0;
        if (d.y != 0.0) {
            const double s0 = (j - range - a.y) / d.y, s1 = (j + range - a.y) / d.y;
            t0 = std::max(0.0, std::min(s0, s1));
            t1 = std::min(1.0, std::max(s0, s1));
            if (t0 > t1) {
                // Only rounding separates the row from the segment's band: use the nearer end.
                t0 = t1 = std::abs(a.y - j) < std::abs(b.y - j) ? 0.0 : 1.0;
            }
        }
        const double x0 = a.x + t0 * d.x, x1 = a.x + t1 * d.x;
        const auto i_lo =
            static_cast<std::int32_t>(std::ceil(std::min(x0, x1) - range - lattice_slack));
        const auto i_hi =
            static_cast<std::int32_t>(std::floor(std::max(x0, x1) + range + lattice_slack));
        if (i_lo > i_hi) continue;
        std::uint32_t& k = last[static_cast<std::size_t>(j - first_row)];
        if (k != no_interval && out[k].lo <= i_hi + 1 && i_lo <= out[k].hi + 1) {
            out[k].lo = std::min(out[k].lo, i_lo);
            out[k].hi = std::max(out[k].hi, i_hi);
        } else {
            k = static_cast<std::uint32_t>(out.size());
            out.push_back({j, i_lo, i_hi, 0});
        }
    }
}

/// Sorts raw x-intervals by (row, start) and merges those that overlap or touch: a counting sort
/// by row (rows span O(M) values), then a sort of each row's few intervals by start.
std::vector<LocalMesh::Interval> merged(const std::vector<LocalMesh::Interval>& raw) {
    SLC_ASSERT(!raw.empty(), "every segment reaches at least one row");
    std::int32_t j_min = raw.front().line, j_max = raw.front().line;
    for (const auto& r : raw) {
        j_min = std::min(j_min, r.line);
        j_max = std::max(j_max, r.line);
    }
    std::vector<std::uint32_t> start(static_cast<std::size_t>(j_max - j_min) + 2, 0);
    for (const auto& r : raw) ++start[static_cast<std::size_t>(r.line - j_min) + 1];
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    std::vector<LocalMesh::Interval> sorted(raw.size());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& r : raw) sorted[fill[static_cast<std::size_t>(r.line - j_min)]++] = r;
    std::vector<LocalMesh::Interval> out;
    for (std::size_t row = 0; row + 1 < start.size(); ++row) {
        const auto first = sorted.begin() + start[row], last = sorted.begin() + start[row + 1];
        std::sort(first, last, [](const auto& p, const auto& q) { return p.lo < q.lo; });
        for (auto it = first; it != last; ++it) {
            if (it != first && it->lo <= out.back().hi + 1) {
                out.back().hi = std::max(out.back().hi, it->hi);
            } else {
                out.push_back(*it);
            }
        }
    }
    return out;
}

}  // namespace

LocalMesh::LocalMesh(const Interface& curves, Vec2 origin, double h, int range)
    : origin_(origin), h_(h), range_(range) {
    if (curves.empty()) throw InvalidInput("local mesh: the interface is empty");
    if (!(h > 0.0) || !std::isfinite(h))
        throw InvalidInput(
            fmt::format("local mesh: spacing must be positive and finite, got {}", h));
    if (range < 1)
        throw InvalidInput(fmt::format("local mesh: range must be at least 1, got {}", range));
    // Segments in lattice units, checked against the index limit, and the rows they can reach.
    std::vector<Segment> lattice(curves.size());
    double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
    for (std::size_t s = 0; s < curves.size(); ++s) {
        const Segment seg = curves.segment(s);
        const Vec2 a = (seg.a - origin) / h, b = (seg.b - origin) / h;
        const double reach = std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y)});
        if (!(reach + range < max_lattice_index)) {
            throw InvalidInput(fmt::format(
                "local mesh: segment {} lies {} lattice steps from the origin (at most 2^30)", s,
                reach));
        }
        lattice[s] = {a, b};
        y_min = std::min({y_min, a.y, b.y});
        y_max = std::max({y_max, a.y, b.y});
    }
    const auto first_row = static_cast<std::int32_t>(std::floor(y_min)) - range - 1;
    const auto last_row = static_cast<std::int32_t>(std::ceil(y_max)) + range + 1;
    std::vector<std::uint32_t> last(static_cast<std::size_t>(last_row - first_row) + 1,
                                    no_interval);
    std::vector<Interval> raw;
    for (const Segment& seg : lattice)
        add_segment_intervals(seg.a, seg.b, static_cast<double>(range), first_row, last, raw);
    rows_ = merged(raw);
    for (Interval& r : rows_) {
        r.first = static_cast<std::uint32_t>(size_);
        size_ += r.size();
    }
    SLC_ASSERT(size_ < 0xffffffffu, "point numbers fit 32 bits");
    first_row_ = rows_.front().line;
    const auto row_count = static_cast<std::size_t>(rows_.back().line - first_row_) + 1;
    row_offsets_.assign(row_count + 1, 0);
    for (const Interval& r : rows_)
        ++row_offsets_[static_cast<std::size_t>(r.line - first_row_) + 1];
    for (std::size_t k = 0; k < row_count; ++k) row_offsets_[k + 1] += row_offsets_[k];
    build_columns();
}

void LocalMesh::build_columns() {
    // Counting sort of the points by column; rows are visited in increasing j, so each column's
    // points come out in increasing j and split into y-intervals where j jumps.
    std::int32_t i_min = rows_.front().lo, i_max = rows_.front().hi;
    for (const Interval& r : rows_) {
        i_min = std::min(i_min, r.lo);
        i_max = std::max(i_max, r.hi);
    }
    const auto width = static_cast<std::size_t>(i_max - i_min) + 1;
    std::vector<std::uint32_t> start(width + 1, 0);  // difference array, then column starts
    for (const Interval& r : rows_) {
        ++start[static_cast<std::size_t>(r.lo - i_min) + 1];
        if (r.hi < i_max) --start[static_cast<std::size_t>(r.hi - i_min) + 2];
    }
    for (std::size_t c = 1; c <= width; ++c) start[c] += start[c - 1];  // points per column
    for (std::size_t c = 1; c <= width; ++c) start[c] += start[c - 1];  // column starts
    column_order_.assign(size_, 0);
    std::vector<std::int32_t> row_of(size_);
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const Interval& r : rows_) {
        for (std::int32_t i = r.lo; i <= r.hi; ++i) {
            const std::uint32_t pos = fill[static_cast<std::size_t>(i - i_min)]++;
            column_order_[pos] = r.first + static_cast<std::uint32_t>(i - r.lo);
            row_of[pos] = r.line;
        }
    }
    for (std::size_t c = 0; c < width; ++c) {
        for (std::uint32_t p = start[c]; p < start[c + 1]; ++p) {
            const auto i = static_cast<std::int32_t>(c) + i_min;
            if (p > start[c] && row_of[p] == columns_.back().hi + 1) {
                ++columns_.back().hi;
            } else {
                columns_.push_back({i, row_of[p], row_of[p], p});
            }
        }
    }
}

std::vector<Vec2> LocalMesh::points() const {
    std::vector<Vec2> out(size_);
    for (const Interval& r : rows_)
        for (std::int32_t i = r.lo; i <= r.hi; ++i)
            out[r.first + static_cast<std::uint32_t>(i - r.lo)] = position(i, r.line);
    return out;
}

const LocalMesh::Interval* LocalMesh::row_interval(std::int32_t i, std::int32_t j) const {
    if (rows_.empty() || j < first_row_ ||
        j >= first_row_ + static_cast<std::int32_t>(row_offsets_.size()) - 1)
        return nullptr;
    const auto k = static_cast<std::size_t>(j - first_row_);
    const auto begin = rows_.begin() + row_offsets_[k], end = rows_.begin() + row_offsets_[k + 1];
    auto it =
        std::upper_bound(begin, end, i, [](std::int32_t v, const Interval& r) { return v < r.lo; });
    if (it == begin) return nullptr;
    --it;
    return i <= it->hi ? &*it : nullptr;
}

std::optional<std::size_t> LocalMesh::find(std::int32_t i, std::int32_t j) const {
    const Interval* r = row_interval(i, j);
    if (r == nullptr) return std::nullopt;
    return r->first + static_cast<std::size_t>(i - r->lo);
}

std::vector<double> derivative(const LocalMesh& mesh, std::span<const double> values, Axis axis,
                               int order, double bias) {
    SLC_ASSERT(values.size() == mesh.size(), "one value per mesh point");
    std::vector<double> out(mesh.size());
    const double h = mesh.spacing();
    if (axis == Axis::x) {
        const auto rows = mesh.rows();
        parallel_for(rows.size(), [&](std::size_t k) {
            const auto& r = rows[k];
            eno::derivative(values.subspan(r.first, r.size()), h, order,
                            std::span<double>(out).subspan(r.first, r.size()), bias);
        });
        return out;
    }
    const auto columns = mesh.columns();
    const auto order_of = mesh.column_order();
    parallel_for(columns.size(), [&](std::size_t k) {
        const auto& c = columns[k];
        std::vector<double> line(c.size()), result(c.size());
        for (std::size_t m = 0; m < c.size(); ++m) line[m] = values[order_of[c.first + m]];
        eno::derivative(line, h, order, result, bias);
        for (std::size_t m = 0; m < c.size(); ++m) out[order_of[c.first + m]] = result[m];
    });
    return out;
}

std::vector<double> smoothed(const LocalMesh& mesh, std::span<const double> values, int passes) {
    SLC_ASSERT(values.size() == mesh.size(), "one value per mesh point");
    std::vector<double> f(values.begin(), values.end()), g(mesh.size());
    const auto rows = mesh.rows();
    const auto columns = mesh.columns();
    const auto order_of = mesh.column_order();
    for (int pass = 0; pass < passes; ++pass) {
        parallel_for(rows.size(), [&](std::size_t k) {
            const auto& r = rows[k];
            eno::smooth(std::span<const double>(f).subspan(r.first, r.size()),
                        std::span<double>(g).subspan(r.first, r.size()));
        });
        parallel_for(columns.size(), [&](std::size_t k) {
            const auto& c = columns[k];
            std::vector<double> line(c.size()), result(c.size());
            for (std::size_t m = 0; m < c.size(); ++m) line[m] = g[order_of[c.first + m]];
            eno::smooth(line, result);
            for (std::size_t m = 0; m < c.size(); ++m) f[order_of[c.first + m]] = result[m];
        });
    }
    return f;
}

std::optional<double> interpolate(const LocalMesh& mesh, std::span<const double> values, Vec2 x,
                                  int order) {
    double out;
    if (!interpolate(mesh, std::span(&values, 1), x, order, std::span(&out, 1)))
        return std::nullopt;
    return out;
}

bool interpolate(const LocalMesh& mesh, std::span<const std::span<const double>> fields, Vec2 x,
                 int order, std::span<double> out, CellStencils* cache) {
    SLC_ASSERT(out.size() == fields.size(), "one output per field");
    const Vec2 u = (x - mesh.origin()) / mesh.spacing();
    const double fi = std::floor(u.x), fj = std::floor(u.y);
    if (!(std::abs(fi) < max_lattice_index && std::abs(fj) < max_lattice_index)) return false;
    const auto i = static_cast<std::int32_t>(fi), j = static_cast<std::int32_t>(fj);
    CellStencils local;
    CellStencils& cell =
        cache != nullptr && fields.size() <= CellStencils::max_fields ? *cache : local;
    const bool known = cell.valid && cell.i == i && cell.j == j;
    if (!known) {
        // Row jj's interval, if it holds both corners i and i + 1.
        auto row_at = [&](std::int32_t jj) -> const LocalMesh::Interval* {
            const LocalMesh::Interval* r = mesh.row_interval(i, jj);
            return r != nullptr && i + 1 <= r->hi ? r : nullptr;
        };
        // Rows j − order + 1 .. j + order, stopping at the first row without the cell's
        // corners: rows[lo..hi], row j at position order − 1.
        cell.valid = false;
        cell.lo = order - 1;
        cell.hi = order;
        cell.rows[static_cast<std::size_t>(cell.lo)] = row_at(j);
        cell.rows[static_cast<std::size_t>(cell.hi)] = row_at(j + 1);
        if (cell.rows[static_cast<std::size_t>(cell.lo)] == nullptr ||
            cell.rows[static_cast<std::size_t>(cell.hi)] == nullptr)
            return false;
        for (int k = 1; k < order; ++k) {
            const LocalMesh::Interval* r = row_at(j - k);
            if (r == nullptr) break;
            cell.rows[static_cast<std::size_t>(--cell.lo)] = r;
        }
        for (int k = 2; k <= order; ++k) {
            const LocalMesh::Interval* r = row_at(j + k);
            if (r == nullptr) break;
            cell.rows[static_cast<std::size_t>(++cell.hi)] = r;
        }
        cell.i = i;
        cell.j = j;
        cell.valid = true;
    }
    std::array<double, 2 * eno::max_order> column{};
    for (std::size_t f = 0; f < fields.size(); ++f) {
        SLC_ASSERT(fields[f].size() == mesh.size(), "one value per mesh point");
        for (int k = cell.lo; k <= cell.hi; ++k) {
            const LocalMesh::Interval& r = *cell.rows[static_cast<std::size_t>(k)];
            const auto line = fields[f].subspan(r.first, r.size());
            const auto at = static_cast<std::size_t>(i - r.lo);
            eno::Stencil s;
            if (known) {
                s = cell.stencils[f][static_cast<std::size_t>(k)];
            } else {
                s = eno::stencil(line, at, at + 1, order);
                if (f < CellStencils::max_fields) cell.stencils[f][static_cast<std::size_t>(k)] = s;
            }
            column[static_cast<std::size_t>(k)] = eno::interpolate(line, s, at, u.x - fi);
        }
        const auto line = std::span<const double>(column).subspan(
            static_cast<std::size_t>(cell.lo), static_cast<std::size_t>(cell.hi - cell.lo + 1));
        out[f] =
            eno::interpolate(line, static_cast<std::size_t>(order - 1 - cell.lo), u.y - fj, order);
    }
    return true;
}

}  // namespace slc
