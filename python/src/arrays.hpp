// Conversions between numpy arrays and the library's points, shared by the files of the module
// slc._slc. Every array arriving here is C-contiguous float64: the package has checked its shape.
#pragma once

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/point_text.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/surface.hpp"

namespace slc::python {

namespace py = pybind11;

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Curves = std::vector<std::vector<Vec2>>;

static_assert(sizeof(Vec2) == 2 * sizeof(double), "Vec2 must be two packed doubles");

/// n points from 2n doubles x0, y0, x1, y1, ...
inline std::vector<Vec2> vectors_of(const double* xy, std::size_t n) {
    std::vector<Vec2> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = {xy[2 * i], xy[2 * i + 1]};
    return out;
}

/// n points from 3n doubles x0, y0, z0, x1, ...
inline std::vector<Vec3> vectors3_of(const double* xyz, std::size_t n) {
    std::vector<Vec3> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    return out;
}

/// The n points of 2n (Vec2) or 3n (Vec3) doubles.
template <class Point>
std::vector<Point> points_from(const double* data, std::size_t n) {
    if constexpr (std::is_same_v<Point, Vec2>) {
        return vectors_of(data, n);
    } else {
        return vectors3_of(data, n);
    }
}

/// The points of an (n, 2) array.
inline std::vector<Vec2> points_of(const Array& a) {
    if (a.ndim() != 2 || a.shape(1) != 2)
        throw InvalidInput("points must be an (n, 2) array of numbers");
    return vectors_of(a.data(), static_cast<std::size_t>(a.shape(0)));
}

/// The largest magnitude of the point's coordinates.
inline double largest_magnitude(Vec2 p) { return std::max(std::abs(p.x), std::abs(p.y)); }
inline double largest_magnitude(Vec3 p) {
    return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

/// Query points (of a distance, an exact solution) as the tool reads them from a file
/// (read_points_csv): InvalidInput naming the first point that is not finite or lies beyond the
/// coordinate limit, where the library's kernels would fail (a NaN point climbs out of the tree).
template <class Point>
void check_query_points(std::span<const Point> points) {
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point p = points[i];
        if (!is_finite(p))
            throw InvalidInput(fmt::format("point {}: {} is not finite", i, point_text(p)));
        if (largest_magnitude(p) > tolerance::max_coordinate) {
            throw InvalidInput(fmt::format("point {}: {} is beyond the coordinate limit ±{:g}", i,
                                           point_text(p), tolerance::max_coordinate));
        }
    }
}

/// The query points of an (n, 2) array, checked by check_query_points.
inline std::vector<Vec2> query_points_of(const Array& a) {
    std::vector<Vec2> points = points_of(a);
    check_query_points(std::span<const Vec2>(points));
    return points;
}

/// The query points of an (n, 3) array, checked by check_query_points.
inline std::vector<Vec3> query_points3_of(const Array& a) {
    if (a.ndim() != 2 || a.shape(1) != 3)
        throw InvalidInput("points must be an (n, 3) array of numbers");
    std::vector<Vec3> points = vectors3_of(a.data(), static_cast<std::size_t>(a.shape(0)));
    check_query_points(std::span<const Vec3>(points));
    return points;
}

inline Curves curves_of(const std::vector<Array>& arrays) {
    Curves out;
    out.reserve(arrays.size());
    for (const Array& a : arrays) out.push_back(points_of(a));
    return out;
}

/// An (n, 2) array holding points.
inline Array array_of(std::span<const Vec2> points) {
    Array a({static_cast<py::ssize_t>(points.size()), py::ssize_t{2}});
    if (!points.empty()) std::memcpy(a.mutable_data(), points.data(), points.size() * sizeof(Vec2));
    return a;
}

/// An (n, 3) array holding points.
inline Array array_of(std::span<const Vec3> points) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
    Array a({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
    if (!points.empty()) std::memcpy(a.mutable_data(), points.data(), points.size() * sizeof(Vec3));
    return a;
}

/// An (n,) array holding values.
inline Array array_of(std::span<const double> values) {
    Array a(static_cast<py::ssize_t>(values.size()));
    if (!values.empty())
        std::memcpy(a.mutable_data(), values.data(), values.size() * sizeof(double));
    return a;
}

/// The curves as a list of (n, 2) arrays.
inline py::list arrays_of(const Interface& curves) {
    py::list out;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) out.append(array_of(curves.curve(c)));
    return out;
}

/// Triangle indices as numpy gives them.
using IndexArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

/// A surface as (vertices (n, 3) float64, triangles (m, 3) int64).
inline py::tuple surface_arrays(const Surface& surface) {
    const Array vertices = array_of(std::span<const Vec3>(surface.vertices));
    IndexArray triangles({static_cast<py::ssize_t>(surface.size()), py::ssize_t{3}});
    auto t = triangles.mutable_unchecked<2>();
    for (std::size_t i = 0; i < surface.size(); ++i)
        for (int k = 0; k < 3; ++k)
            t(static_cast<py::ssize_t>(i), k) = static_cast<std::int64_t>(surface.triangles[i][k]);
    return py::make_tuple(vertices, triangles);
}

/// The surface of (n, 3) vertices and (m, 3) triangle indices, unchecked but for the shapes and
/// the indices' range: InvalidInput otherwise.
inline Surface surface_of(const Array& vertices, const IndexArray& triangles) {
    if (vertices.ndim() != 2 || vertices.shape(1) != 3)
        throw InvalidInput("vertices must be an (n, 3) array of numbers");
    if (triangles.ndim() != 2 || triangles.shape(1) != 3)
        throw InvalidInput("triangles must be an (m, 3) array of vertex indices");
    Surface s;
    const auto n = static_cast<std::size_t>(vertices.shape(0));
    s.vertices = vectors3_of(vertices.data(), n);
    const auto t = triangles.unchecked<2>();
    s.triangles.resize(static_cast<std::size_t>(triangles.shape(0)));
    for (py::ssize_t i = 0; i < triangles.shape(0); ++i) {
        for (int k = 0; k < 3; ++k) {
            const std::int64_t v = t(i, k);
            if (v < 0 || static_cast<std::size_t>(v) >= n) {
                throw InvalidInput(fmt::format(
                    "triangle {} names vertex {}, but there are {} vertices (numbered from 0)", i,
                    v, n));
            }
            s.triangles[static_cast<std::size_t>(i)][k] = static_cast<std::uint32_t>(v);
        }
    }
    return s;
}

/// The shape of an array as Python prints it: "(3,)", "(4, 3)".
inline std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

/// What a callback returned, as an array of numbers: InvalidInput naming `what` otherwise.
inline Array numbers_of(const py::object& result, const std::string& what) {
    const auto a = py::array::ensure(result);
    if (!a || a.dtype().kind() == 'O' || a.dtype().kind() == 'U' || a.dtype().kind() == 'S')
        throw InvalidInput(what + " must return an array of numbers");
    return a.cast<Array>();
}

/// A run's history, curves' or a surface's: one row a step, columns by name, each an array in the
/// end (int64 for the counting columns).
class History {
public:
    /// A column's name and whether it counts (components, segments, triangles).
    struct Column {
        const char* name;
        bool counts = false;
    };
    explicit History(std::vector<Column> columns)
        : columns_(std::move(columns)), values_(columns_.size()) {}
    /// One row, a value a column in their order.
    void add(std::initializer_list<double> row) {
        std::size_t i = 0;
        for (const double v : row) values_[i++].push_back(v);
    }
    /// The columns as a dict of arrays.
    py::dict arrays() const {
        py::dict h;
        for (std::size_t i = 0; i < columns_.size(); ++i) {
            py::object a = array_of(std::span<const double>(values_[i]));
            h[columns_[i].name] = columns_[i].counts ? a.attr("astype")("int64") : a;
        }
        return h;
    }

private:
    std::vector<Column> columns_;
    std::vector<std::vector<double>> values_;
};

/// A study's observed orders as a list of rows, each of floats or None: order(r, c) for r below
/// rows and c below columns (order an optional<double> of them).
template <class Order>
py::list order_table(Order order, int rows, int columns) {
    py::list table;
    for (int r = 0; r < rows; ++r) {
        py::list row;
        for (int c = 0; c < columns; ++c) {
            const std::optional<double> o = order(r, c);
            row.append(o ? py::cast(*o) : py::object(py::none()));
        }
        table.append(row);
    }
    return table;
}

}  // namespace slc::python
