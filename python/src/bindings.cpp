// The Python module slc._slc (DESIGN §9): the library's entry points on numpy arrays, with the
// defaults of `slc run --initial`. The package python/slc/ checks shapes and types and builds the
// user-facing classes on top; here every curve arrives as a C-contiguous float64 (n, 2) array.
//
// Python is called only from the thread that called into the module, with the GIL held for that
// call alone: the contour's G and a velocity law are handed whole batches (all vertices of a stage)
// on the calling thread, while the library's own loops run with the GIL released on all cores.
// Errors: slc::InvalidInput becomes ValueError and slc::NumericalFailure RuntimeError, the same
// one-line message; an exception raised in a callback reaches the caller unchanged.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "arrays.hpp"
#include "calls.hpp"
#include "run.hpp"
#include "slc/contour/contour.hpp"
#include "slc/contour/implicit_function.hpp"
#include "slc/contour/surface_contour.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/guards.hpp"
#include "slc/evolve/keeping_topology.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/summary.hpp"
#include "slc/tree/orthtree.hpp"
#include "slc/velocity/factory.hpp"
#include "surfaces.hpp"

namespace slc::python {
namespace {

// ---- interfaces --------------------------------------------------------------------------------

/// The domain the tool gives a file's curves when none is given: default_domain.
PreparedInterface prepare(const Curves& raw) { return prepare_interface(raw, default_domain(raw)); }

py::tuple prepare_arrays(const std::vector<Array>& arrays) {
    const Curves raw = curves_of(arrays);
    std::optional<PreparedInterface> p;
    {
        py::gil_scoped_release release;
        p.emplace(prepare(raw));
    }
    return py::make_tuple(arrays_of(p->curves), p->notes);
}

py::tuple load(const std::string& path) {
    std::optional<InterfaceFile> file;
    std::optional<PreparedInterface> p;
    {
        py::gil_scoped_release release;
        file.emplace(read_interface_json(path));
        try {
            p.emplace(prepare(file->curves));
        } catch (const InvalidInput& e) {
            throw InvalidInput(path + ": " + e.what());
        }
    }
    return py::make_tuple(arrays_of(p->curves), file->time, p->notes);
}

void save(const std::string& path, const std::vector<Array>& arrays, double time) {
    if (!std::isfinite(time)) throw InvalidInput(fmt::format("time must be finite, got {}", time));
    write_file_atomic(path, interface_json(Interface(curves_of(arrays)), time));
}

/// (distances (m,), nearest points (m, 2)) of the curves at the (m, 2) points, as `slc distance`,
/// on `threads` threads (0: as --threads 0).
py::tuple distance(const std::vector<Array>& arrays, const Array& xs_array, int threads) {
    const Curves raw = curves_of(arrays);
    const std::vector<Vec2> xs = query_points_of(xs_array);
    const std::vector<ClosestPoint> answers = without_gil(threads, [&] {
        const Interface curves(raw);
        const Box domain = default_domain(raw);
        const DistanceTree tree(
            curves, domain,
            {.depth = DistanceTree::default_depth(curves, domain), .triangulate = false});
        return tree.closest_points(xs);
    });
    std::vector<double> d(xs.size());
    std::vector<Vec2> nearest(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) {
        d[i] = answers[i].distance;
        nearest[i] = answers[i].point;
    }
    return py::make_tuple(array_of(std::span<const double>(d)),
                          array_of(std::span<const Vec2>(nearest)));
}

// ---- contour -----------------------------------------------------------------------------------

/// A square domain from (x0, y0, x1, y1), a rectangle taken as the square around it, as --box.
Box square_box(const std::vector<double>& v) {
    if (v.size() != 4) throw InvalidInput("box must be four numbers (x0, y0, x1, y1)");
    const Box b{{v[0], v[1]}, {v[2], v[3]}};
    if (!is_finite(b.lo) || !is_finite(b.hi) || !(b.width() > 0) || !(b.height() > 0)) {
        throw InvalidInput(
            fmt::format("box must have x0 < x1 and y0 < y1, all finite, got ({}, {}, {}, {})", v[0],
                        v[1], v[2], v[3]));
    }
    if (b.largest_magnitude() > tolerance::max_coordinate)
        throw InvalidInput("box corners must lie within the largest coordinate slc accepts");
    return Box::square(b.center(), 0.5 * std::max(b.width(), b.height()));
}

/// Calls a Python f((m, 2) or (m, 3) array) -> (m,) array for a batch of points (Vec2 or Vec3),
/// with the GIL held for the call.
template <class Point>
void call_batch(const py::object& f, std::span<const Point> points, std::span<double> values) {
    constexpr int columns = std::is_same_v<Point, Vec2> ? 2 : 3;
    py::gil_scoped_acquire hold;
    const Array v = numbers_of(f(array_of(points)), "f");
    if (v.ndim() != 1 || static_cast<std::size_t>(v.shape(0)) != points.size()) {
        throw InvalidInput(fmt::format(
            "f must return an (m,) array for an (m, {}) array of points, got shape {} for m = {}",
            columns, shape_text(v), points.size()));
    }
    std::memcpy(values.data(), v.data(), values.size() * sizeof(double));
}

/// thin_depth within setting_range::thin_depth, as the tool's --thin-depth; InvalidInput else.
int checked_thin_depth(int thin_depth) {
    const IntRange r = setting_range::thin_depth;
    if (thin_depth < r.lo || thin_depth > r.hi) {
        throw InvalidInput(fmt::format("thin_depth: must be an integer from {} to {}, got {}", r.lo,
                                       r.hi, thin_depth));
    }
    return thin_depth;
}

py::tuple contour_function(const py::object& f, const std::vector<double>& box, int depth,
                           std::optional<double> eps, int refine, int thin_depth) {
    const Box domain = square_box(box);
    ContourOptions options;
    options.depth = depth;
    options.eps = eps;
    options.refine_passes = refine;
    options.thin_depth = checked_thin_depth(thin_depth);
    auto g = [&f](std::span<const Vec2> points, std::span<double> values) {
        call_batch(f, points, values);
    };
    std::optional<ContourResult> result;
    {
        py::gil_scoped_release release;
        result.emplace(contour(g, domain, options));
    }
    const ContourResult& r = *result;
    nlohmann::json stats = contour_stats_json(r.stats);
    stats["eps"] = options.resolved_eps();
    stats["domain"] = {domain.lo.x, domain.lo.y, domain.hi.x, domain.hi.y};
    return py::make_tuple(arrays_of(r.curves), python_of(stats));
}

/// contour_surface's options as Python gives them.
SurfaceContourOptions surface_contour_options(int depth, int refine, std::optional<double> eps,
                                              std::optional<double> eta, int thin_depth,
                                              bool creases, std::optional<double> slack) {
    return {.depth = depth,
            .refine_passes = refine,
            .eps = eps,
            .eta = eta,
            .thin_depth = checked_thin_depth(thin_depth),
            .creases = creases,
            .distance_slack = slack};
}

/// contour_surface's answer: the surface's arrays and its statistics.
py::tuple surface_contour_answer(const SurfaceContour& result, const SurfaceContourOptions& options,
                                 const Box3& domain) {
    const py::tuple arrays = surface_arrays(result.surface);
    nlohmann::json stats = contour_stats_json(result.stats);
    stats["converged"] = result.stats.converged;
    stats["eps"] = options.resolved_eps();
    stats["eta"] = options.resolved_eta();
    stats["creases"] = options.creases;
    stats["domain"] = {domain.lo.x, domain.lo.y, domain.lo.z,
                       domain.hi.x, domain.hi.y, domain.hi.z};
    return py::make_tuple(arrays[0], arrays[1], python_of(stats));
}

py::tuple contour_surface_function(const py::object& f, const std::vector<double>& box, int depth,
                                   std::optional<double> eps, int refine,
                                   std::optional<double> slack, std::optional<double> eta,
                                   int thin_depth, bool creases) {
    const Box3 domain = cube_around_corners(box, "box");
    const SurfaceContourOptions options =
        surface_contour_options(depth, refine, eps, eta, thin_depth, creases, slack);
    auto g = [&f](std::span<const Vec3> points, std::span<double> values) {
        call_batch(f, points, values);
    };
    std::optional<SurfaceContour> result;
    {
        py::gil_scoped_release release;
        result.emplace(contour_surface(g, domain, options));
    }
    return surface_contour_answer(*result, options, domain);
}

/// contour_surface of a Surface: its exact signed distance (the distance tree's, as `slc
/// contour` of a mesh file), on all threads, without calls into Python.
py::tuple contour_surface_mesh(const Array& vertices, const IndexArray& triangles,
                               const std::vector<double>& box, int depth, std::optional<double> eps,
                               int refine, std::optional<double> eta, std::optional<int> thin_depth,
                               bool creases, int threads) {
    const Surface surface = surface_of(vertices, triangles);
    if (surface.empty()) throw InvalidInput("the surface has no triangles");
    const Box3 domain = cube_around_corners(box, "box");
    // A signed distance is 1-Lipschitz: points far from its surface need no value.
    const int asked = thin_depth.value_or(default_thin_depth(3));
    SurfaceContourOptions options =
        surface_contour_options(depth, refine, eps, eta, asked, creases, 0.0);
    // The surface's topology is known: the contour keeps it beside its sharp edges and points.
    options.keep_topology = shape_topology(surface);
    // As slc contour: the thin depth left unset, the one that keeps the surface's components and
    // handles where the default does not (the linear contours decide, the one kept is refined).
    const SurfaceContour result = without_gil(threads, [&] {
        const SurfaceDistanceTree tree(
            surface, domain, {.depth = SurfaceDistanceTree::default_depth(surface, domain)});
        const auto g = pointwise<Vec3>([&](Vec3 x) { return tree.closest_point(x).distance; },
                                       expensive_grain);
        if (!thin_depth) {
            SurfaceContourOptions linear = options;
            linear.refine_passes = 0;
            auto [kept, c] = keeping_topology(
                shape_topology(surface), asked,
                [&](int levels) {
                    linear.thin_depth = levels;
                    return contour_surface(g, domain, linear);
                },
                [](const SurfaceContour& l) { return shape_topology(l.surface); });
            options.thin_depth = kept;
            if (options.refine_passes == 0) return std::move(c);
        }
        return contour_surface(g, domain, options);
    });
    py::tuple answer = surface_contour_answer(result, options, domain);
    // Whether the contour kept the surface's components and handles, as slc contour says.
    const std::optional<std::string> lost =
        lost_topology_note(shape_topology(surface), shape_topology(result.surface), 3,
                           fmt::format("raise thin_depth (now {}) or depth", options.thin_depth));
    const std::optional<std::string> kept_note =
        thin_depth_note("surface", asked, options.thin_depth, "thin_depth");
    py::dict stats = answer[2];
    stats["kept_topology"] = !lost;
    stats["thin_depth"] = options.thin_depth;
    if (lost) stats["note"] = *lost;
    if (kept_note) stats["note"] = lost ? *lost + "; " + *kept_note : *kept_note;
    return answer;
}

py::list velocity_names() {
    py::list out;
    for (const VelocityInfo& v : velocity_catalog()) out.append(v.name);
    return out;
}

py::list surface_velocity_names() {
    py::list out;
    for (const VelocityInfo& v : surface_velocity_catalog()) out.append(v.name);
    return out;
}

}  // namespace
}  // namespace slc::python

PYBIND11_MODULE(_slc, m) {
    using namespace slc::python;
    m.doc() = "slc's C++ library on numpy arrays; use the package slc, not this module";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const slc::InvalidInput& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const slc::NumericalFailure& e) {
            PyErr_SetString(PyExc_RuntimeError, e.what());
        }
    });
    m.def("prepare", &prepare_arrays, py::arg("curves"));
    m.def("load", &load, py::arg("path"));
    m.def("save", &save, py::arg("path"), py::arg("curves"), py::arg("time"));
    m.def("area",
          [](const std::vector<Array>& c) { return slc::area(slc::Interface(curves_of(c))); });
    m.def("length",
          [](const std::vector<Array>& c) { return slc::length(slc::Interface(curves_of(c))); });
    m.def("distance", &distance, py::arg("curves"), py::arg("points"), py::arg("threads"));
    m.def("contour", &contour_function, py::arg("f"), py::arg("box"), py::arg("depth"),
          py::arg("eps"), py::arg("refine"), py::arg("thin_depth"));
    m.def("contour_surface", &contour_surface_function, py::arg("f"), py::arg("box"),
          py::arg("depth"), py::arg("eps"), py::arg("refine"), py::arg("slack"), py::arg("eta"),
          py::arg("thin_depth"), py::arg("creases"));
    m.def("contour_surface_mesh", &contour_surface_mesh, py::arg("vertices"), py::arg("triangles"),
          py::arg("box"), py::arg("depth"), py::arg("eps"), py::arg("refine"), py::arg("eta"),
          py::arg("thin_depth"), py::arg("creases"), py::arg("threads"));
    add_run_functions(m);
    add_surface_functions(m);
    m.def("velocity_names", &velocity_names);
    m.def("surface_velocity_names", &surface_velocity_names);
    m.attr("until_converged") = slc::ContourOptions::until_converged;
}
