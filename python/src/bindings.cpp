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
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "slc/contour/contour.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/run.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/tree/quadtree.hpp"
#include "slc/velocity/factory.hpp"

namespace py = pybind11;

namespace slc::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Curves = std::vector<std::vector<Vec2>>;

static_assert(sizeof(Vec2) == 2 * sizeof(double), "Vec2 must be two packed doubles");

// ---- arrays ------------------------------------------------------------------------------------

/// n points from 2n doubles x0, y0, x1, y1, ...
std::vector<Vec2> vectors_of(const double* xy, std::size_t n) {
    std::vector<Vec2> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = {xy[2 * i], xy[2 * i + 1]};
    return out;
}

/// The points of an (n, 2) array; the package has checked the shape.
std::vector<Vec2> points_of(const Array& a) {
    if (a.ndim() != 2 || a.shape(1) != 2)
        throw InvalidInput("points must be an (n, 2) array of numbers");
    return vectors_of(a.data(), static_cast<std::size_t>(a.shape(0)));
}

Curves curves_of(const std::vector<Array>& arrays) {
    Curves out;
    out.reserve(arrays.size());
    for (const Array& a : arrays) out.push_back(points_of(a));
    return out;
}

/// An (n, 2) array holding points.
Array array_of(std::span<const Vec2> points) {
    Array a({static_cast<py::ssize_t>(points.size()), py::ssize_t{2}});
    if (!points.empty()) std::memcpy(a.mutable_data(), points.data(), points.size() * sizeof(Vec2));
    return a;
}

/// An (n,) array holding values.
Array array_of(std::span<const double> values) {
    Array a(static_cast<py::ssize_t>(values.size()));
    if (!values.empty())
        std::memcpy(a.mutable_data(), values.data(), values.size() * sizeof(double));
    return a;
}

py::list arrays_of(const Interface& curves) {
    py::list out;
    for (std::size_t c = 0; c < curves.curve_count(); ++c) out.append(array_of(curves.curve(c)));
    return out;
}

/// The shape of an array as Python prints it: "(3,)", "(4, 3)".
std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

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
    write_file_atomic(path, interface_json(Interface(curves_of(arrays)), time));
}

py::tuple distance(const std::vector<Array>& arrays, const Array& xs_array) {
    const Curves raw = curves_of(arrays);
    const std::vector<Vec2> xs = points_of(xs_array);
    std::vector<double> d(xs.size());
    std::vector<Vec2> nearest(xs.size());
    {
        py::gil_scoped_release release;
        const Interface curves(raw);
        const Box domain = default_domain(raw);
        const DistanceTree tree(
            curves, domain,
            {.depth = DistanceTree::default_depth(curves, domain), .triangulate = false});
        const std::vector<ClosestPoint> answers = tree.closest_points(xs);
        for (std::size_t i = 0; i < xs.size(); ++i) {
            d[i] = answers[i].distance;
            nearest[i] = answers[i].point;
        }
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

/// Calls a Python f((m, 2) array) -> (m,) array for a batch, with the GIL held for the call.
void call_batch(const py::object& f, std::span<const Vec2> points, std::span<double> values) {
    py::gil_scoped_acquire hold;
    const py::object result = f(array_of(points));
    const auto a = py::array::ensure(result);
    if (!a) throw InvalidInput("f must return an array of numbers");
    const Array v = a.cast<Array>();
    if (v.ndim() != 1 || static_cast<std::size_t>(v.shape(0)) != points.size()) {
        throw InvalidInput(fmt::format(
            "f must return an (m,) array for an (m, 2) array of points, got shape {} for m = {}",
            shape_text(v), points.size()));
    }
    std::memcpy(values.data(), v.data(), values.size() * sizeof(double));
}

py::tuple contour_function(const py::object& f, const std::vector<double>& box, int depth,
                           std::optional<double> eps, int refine) {
    const Box domain = square_box(box);
    ContourOptions options;
    options.depth = depth;
    options.eps = eps;
    options.refine_passes = refine;
    auto g = [&f](std::span<const Vec2> points, std::span<double> values) {
        call_batch(f, points, values);
    };
    std::optional<ContourResult> result;
    {
        py::gil_scoped_release release;
        result.emplace(contour(g, domain, options));
    }
    const ContourResult& r = *result;
    py::dict stats;
    stats["cells"] = r.stats.cells;
    stats["segments"] = r.stats.segments;
    stats["g_evals"] = r.stats.g_evals;
    stats["passes"] = r.stats.passes;
    stats["eps"] = options.resolved_eps();
    stats["domain"] = py::make_tuple(domain.lo.x, domain.lo.y, domain.hi.x, domain.hi.y);
    stats["max_midpoint_value"] =
        r.stats.max_midpoint_value ? py::cast(*r.stats.max_midpoint_value) : py::object(py::none());
    return py::make_tuple(arrays_of(r.curves), stats);
}

// ---- velocity laws written in Python -----------------------------------------------------------

/// f(t, points, normals, curvature) -> (m, 2) vertex velocities or (m,) normal speeds v (u = v·N),
/// called once per stage with all vertices, on the thread that runs the step.
class PythonCurveLaw final : public VelocityLaw {
public:
    PythonCurveLaw(py::object f, std::string name, std::optional<GeometryModule> module)
        : f_(std::move(f)), name_(std::move(name)), module_(module) {}
    std::string name() const override { return name_; }
    GeometryNeeds needs() const override {
        return {.normals = true, .curvature = true, .module = module_};
    }
    std::vector<Vec2> velocities(double t, const Interface& curves,
                                 const VertexGeometry& geometry) const override {
        py::gil_scoped_acquire hold;
        const std::size_t m = curves.size();
        const py::object result =
            f_(t, array_of(curves.points()), array_of(std::span<const Vec2>(geometry.normals)),
               array_of(std::span<const double>(geometry.curvature)));
        const auto a = py::array::ensure(result);
        if (!a) throw InvalidInput("velocity '" + name_ + "' must return an array of numbers");
        const Array v = a.cast<Array>();
        std::vector<Vec2> u(m);
        const auto n = static_cast<py::ssize_t>(m);
        if (v.ndim() == 1 && v.shape(0) == n) {
            for (std::size_t i = 0; i < m; ++i) u[i] = v.data()[i] * geometry.normals[i];
        } else if (v.ndim() == 2 && v.shape(0) == n && v.shape(1) == 2) {
            u = vectors_of(v.data(), m);
        } else {
            throw InvalidInput(fmt::format(
                "velocity '{}' must return (m,) normal speeds or (m, 2) velocities for m = {} "
                "vertices, got shape {}",
                name_, m, shape_text(v)));
        }
        return u;
    }

private:
    py::object f_;
    std::string name_;
    std::optional<GeometryModule> module_;
};

/// A flow field f(t, points) -> (m, 2) known everywhere: sampled off the curve along the
/// characteristics, one call per batch and Runge–Kutta stage.
class PythonFieldLaw final : public VelocityLaw {
public:
    PythonFieldLaw(py::object f, std::string name) : f_(std::move(f)), name_(std::move(name)) {}
    std::string name() const override { return name_; }
    std::vector<Vec2> velocities(double t, const Interface& curves,
                                 const VertexGeometry&) const override {
        std::vector<Vec2> u(curves.size());
        sample(t, curves.points(), u);
        return u;
    }
    bool is_field() const override { return true; }
    void sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const override {
        py::gil_scoped_acquire hold;
        const py::object result = f_(t, array_of(points));
        const auto a = py::array::ensure(result);
        if (!a) throw InvalidInput("flow field '" + name_ + "' must return an array of numbers");
        const Array v = a.cast<Array>();
        if (v.ndim() != 2 || v.shape(0) != static_cast<py::ssize_t>(points.size()) ||
            v.shape(1) != 2) {
            throw InvalidInput("flow field '" + name_ + "' must return (m, 2) velocities for m = " +
                               std::to_string(points.size()) + " points, got shape " +
                               shape_text(v));
        }
        const std::vector<Vec2> u = vectors_of(v.data(), out.size());
        std::copy(u.begin(), u.end(), out.begin());
    }

private:
    py::object f_;
    std::string name_;
};

// ---- run ---------------------------------------------------------------------------------------

const std::map<std::string, Extension> extension_names = {{"nearest", Extension::nearest_point},
                                                          {"whitney", Extension::whitney},
                                                          {"direct", Extension::direct}};
const std::map<std::string, GeometryModule> geometry_names = {
    {"intrinsic", GeometryModule::intrinsic},
    {"embedded", GeometryModule::embedded},
    {"arclength", GeometryModule::arclength}};

template <class T>
T named(const std::map<std::string, T>& names, const std::string& what, const std::string& name) {
    const auto it = names.find(name);
    if (it != names.end()) return it->second;
    std::string known;
    for (const auto& [n, v] : names) known += (known.empty() ? "" : ", ") + n;
    throw InvalidInput(what + " must be one of " + known + ", got '" + name + "'");
}

std::string extension_name(Extension e) {
    for (const auto& [name, value] : extension_names)
        if (value == e) return name;
    return "nearest";
}

/// What `run` was asked for, beside the curves and the law.
struct RunRequest {
    double t_start = 0.0;
    double t_end = 1.0;
    std::optional<int> steps;
    std::optional<int> depth;
    std::optional<int> refine;
    std::optional<double> eps;
    std::optional<std::string> extension;
    int frames = 0;
    int threads = 0;
};

/// The run's options as `slc run --initial` resolves them: default_run_options, then N, K, P, ε
/// given (ε 10^−K ℓ when K is given without it), as resolve_run_options does.
RunOptions resolve(const Interface& curves, const VelocityLaw& law, const RunRequest& q) {
    RunOptions r = default_run_options(curves, law, q.t_start, q.t_end);
    ContourOptions& c = r.step.contour;
    if (q.steps) {
        if (*q.steps < 1)
            throw InvalidInput(fmt::format("steps must be at least 1, got {}", *q.steps));
        r.steps = *q.steps;
    }
    if (q.depth) {
        if (*q.depth < 1 || *q.depth > 24)
            throw InvalidInput(fmt::format("depth must be from 1 to 24, got {}", *q.depth));
        c.depth = *q.depth;
        c.eps = std::pow(10.0, -c.depth) * length_scale(curves);
        r.step.embedded.mesh = default_mesh_size(c.depth);
    }
    if (q.refine) {
        if (*q.refine != ContourOptions::until_converged && (*q.refine < 0 || *q.refine > 64))
            throw InvalidInput(
                fmt::format("refine must be from 0 to 64 or 'converged', got {}", *q.refine));
        c.refine_passes = *q.refine;
    }
    if (q.eps) {
        if (!(*q.eps > 0.0) || !std::isfinite(*q.eps))
            throw InvalidInput(fmt::format("eps must be positive and finite, got {}", *q.eps));
        c.eps = *q.eps;
    }
    if (*c.eps < c.eta) {
        throw InvalidInput(fmt::format("eps ({}) must not be below eta ({})", *c.eps, c.eta));
    }
    if (q.extension) r.step.extension = named(extension_names, "extension", *q.extension);
    return r;
}

double peak_rss_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
}

py::dict summary(const RunOptions& o, const RunResult& r, const VelocityLaw& law, const Box& domain,
                 const VelocityParams& params) {
    const ContourOptions& c = o.step.contour;
    const py::object passes = c.refine_passes == ContourOptions::until_converged
                                  ? py::object(py::str("converged"))
                                  : py::object(py::int_(c.refine_passes));
    py::dict p;
    p["N"] = o.steps;
    p["K"] = c.depth;
    p["P"] = passes;
    p["eps"] = c.resolved_eps();
    p["eta"] = c.eta;
    p["rho"] = c.rho;
    p["M"] = o.step.embedded.mesh;
    p["E"] = o.step.embedded.eno_order;
    p["S"] = o.step.embedded.smoothing;
    p["L"] = o.step.resolved_tree_depth();
    p["domain"] = py::make_tuple(domain.lo.x, domain.lo.y, domain.hi.x, domain.hi.y);
    p["t_end"] = o.t_end;
    p["velocity"] = law.name();
    p["velocity_params"] = params;
    p["extension"] = extension_name(o.step.resolved_extension(law));
    p["arcs"] = o.step.resolved_arcs(law);
    p["area_correction"] = o.step.area_correction.value_or(law.preserves_area());
    p["arc_width"] = o.step.resolved_arc_width((o.t_end - o.t_start) / o.steps);
    py::dict s;
    // The run's name N/S/K/P/ε as the paper writes it (summary.json "run").
    s["run"] = fmt::format("{}/{}/{}/{}/{:.0e}", o.steps, o.step.embedded.smoothing, c.depth,
                           py::str(passes).cast<std::string>(), c.resolved_eps());
    s["params"] = p;
    s["t_end"] = o.t_end;
    s["t"] = r.t;
    s["steps"] = o.steps;
    s["steps_done"] = r.steps_done;
    s["status"] = to_string(r.status);
    s["e_inf"] = py::none();
    s["area"] = area(r.curves);
    s["length"] = length(r.curves);
    s["components"] = r.curves.curve_count();
    s["segments"] = r.curves.size();
    s["wall_s"] = r.wall_s;
    s["cpu_s"] = r.cpu_s;
    s["cpu_s_per_step"] = r.steps_done > 0 ? r.cpu_s / r.steps_done : 0.0;
    s["threads"] = thread_count();
    s["g_evals"] = r.g_evals;
    s["peak_rss_mib"] = peak_rss_mib();
    s["g_evals_per_vertex"] =
        r.vertices_produced > 0 ? static_cast<double>(r.g_evals) / r.vertices_produced : 0.0;
    if (r.status == RunStatus::error) s["message"] = r.message;
    if (o.step.area_correction.value_or(law.preserves_area()))
        s["area_corrected"] = r.area_corrected;
    if (r.domain_doublings > 0) {
        const Box d = doubled_domain(domain, r.domain_doublings);
        py::dict grown;
        grown["at_t"] = r.domain_grown_at;
        grown["doublings"] = r.domain_doublings;
        grown["domain"] = py::make_tuple(d.lo.x, d.lo.y, d.hi.x, d.hi.y);
        grown["K"] = c.depth + r.domain_doublings;
        s["domain_grown"] = grown;
    }
    return s;
}

/// The history of a run: t, area, length, components, segments, cpu_s per row.
struct History {
    std::vector<double> t, area, length, cpu_s;
    std::vector<double> components, segments;
    void add(double time, const Interface& curves, double cpu) {
        t.push_back(time);
        area.push_back(slc::area(curves));
        length.push_back(slc::length(curves));
        components.push_back(static_cast<double>(curves.curve_count()));
        segments.push_back(static_cast<double>(curves.size()));
        cpu_s.push_back(cpu);
    }
};

/// velocity: a built-in law's name, a callable (PythonCurveLaw) or, with field = true, a flow
/// field. on_step(step, steps, t, curves, cpu_s), when given, is called after every step; it
/// returns False to stop.
py::dict run_curves(const std::vector<Array>& arrays, const py::object& velocity, bool field,
                    const std::string& name, const VelocityParams& params,
                    std::optional<std::string> geometry, const RunRequest& q,
                    const py::object& on_step) {
    const std::optional<GeometryModule> module =
        geometry ? std::optional(named(geometry_names, "geometry", *geometry)) : std::nullopt;
    std::unique_ptr<VelocityLaw> law;
    if (py::isinstance<py::str>(velocity)) {
        law = make_velocity(velocity.cast<std::string>(), params, module);
    } else {
        if (!params.empty())
            throw InvalidInput("params are for the built-in laws, not for a Python velocity");
        if (field)
            law = std::make_unique<PythonFieldLaw>(velocity, name);
        else
            law = std::make_unique<PythonCurveLaw>(velocity, name, module);
    }
    const Curves raw = curves_of(arrays);
    const Interface initial(raw);
    const Box domain = default_domain(raw);
    const RunOptions options = resolve(initial, *law, q);
    if (q.frames < 0) throw InvalidInput(fmt::format("frames must be 0 or more, got {}", q.frames));
    if (q.threads < 0)
        throw InvalidInput(fmt::format("threads must be 0 or more, got {}", q.threads));

    History history;
    history.add(options.t_start, initial, 0.0);
    py::list frames;
    if (q.frames > 0) frames.append(py::make_tuple(options.t_start, arrays_of(initial)));
    const bool call_back = !on_step.is_none();
    const Observer observer = [&](const StepReport& s) {
        history.add(s.t, *s.curves, s.step_cpu_s);
        py::gil_scoped_acquire hold;
        if (q.frames > 0 && (std::int64_t{s.step} * q.frames) % s.steps < q.frames)
            frames.append(py::make_tuple(s.t, arrays_of(*s.curves)));
        // Ctrl-C: Python's handler has only set a flag while the GIL was released.
        if (PyErr_CheckSignals() != 0) {
            py::error_already_set interrupt;  // KeyboardInterrupt, taken and dropped: stop here
            return false;
        }
        if (!call_back) return true;
        const py::object go_on = on_step(s.step, s.steps, s.t, arrays_of(*s.curves), s.step_cpu_s);
        return go_on.is_none() || go_on.cast<bool>();
    };

    const int threads_before = thread_count();
    set_thread_count(q.threads);
    RunResult r;
    try {
        py::gil_scoped_release release;
        r = run(initial, *law, domain, options, observer);
    } catch (...) {
        set_thread_count(threads_before);
        throw;
    }
    set_thread_count(threads_before);

    py::dict h;
    h["t"] = array_of(std::span<const double>(history.t));
    h["area"] = array_of(std::span<const double>(history.area));
    h["length"] = array_of(std::span<const double>(history.length));
    h["components"] = array_of(std::span<const double>(history.components)).attr("astype")("int64");
    h["segments"] = array_of(std::span<const double>(history.segments)).attr("astype")("int64");
    h["cpu_s"] = array_of(std::span<const double>(history.cpu_s));
    py::dict out;
    out["curves"] = arrays_of(r.curves);
    out["t"] = r.t;
    out["status"] = to_string(r.status);
    out["message"] = r.message;
    out["history"] = h;
    out["frames"] = frames;
    out["summary"] = summary(options, r, *law, domain, params);
    return out;
}

py::list velocity_names() {
    py::list out;
    for (const VelocityInfo& v : velocity_catalog()) out.append(v.name);
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
    m.def("distance", &distance, py::arg("curves"), py::arg("points"));
    m.def("contour", &contour_function, py::arg("f"), py::arg("box"), py::arg("depth"),
          py::arg("eps"), py::arg("refine"));
    m.def("run", [](const std::vector<Array>& curves, const py::object& velocity, bool field,
                    const std::string& name, const slc::VelocityParams& params,
                    std::optional<std::string> geometry, double t_start, double t_end,
                    std::optional<int> steps, std::optional<int> depth, std::optional<int> refine,
                    std::optional<double> eps, std::optional<std::string> extension, int frames,
                    int threads, const py::object& on_step) {
        RunRequest q{t_start, t_end, steps, depth, refine, eps, extension, frames, threads};
        return run_curves(curves, velocity, field, name, params, geometry, q, on_step);
    });
    m.def("velocity_names", &velocity_names);
    m.attr("until_converged") = slc::ContourOptions::until_converged;
}
