// Moving surfaces from Python: a user's surface (the defaults of `slc run --initial S.obj`) or a
// named problem of surfaces, under a built-in law of surfaces or one written in Python, and the
// convergence studies of surfaces. Surfaces arrive as (n, 3) float64 vertices and (m, 3) int64
// triangles.
#include "surfaces.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "arrays.hpp"
#include "calls.hpp"
#include "laws.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/tolerances.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/evolve/surface_problems.hpp"
#include "slc/evolve/surface_study.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/summary.hpp"
#include "slc/io/surface_files.hpp"
#include "slc/io/surface_picture.hpp"
#include "slc/io/vdb.hpp"
#include "slc/io/vtk.hpp"
#include "slc/tree/tetrahedralization.hpp"

namespace slc::python {
namespace {

/// A problem of surfaces as Python holds it: a named one (its own settings) or a user's surface
/// (the defaults of default_surface_run_options from t_start).
struct SurfaceSubject {
    SurfaceProblem problem;
    bool named = false;
    double t_start = 0.0;
};

/// The history of a run of a surface: t, volume, area, triangles, components, cpu_s per row.
History surface_history() {
    return History(
        {{"t"}, {"volume"}, {"area"}, {"triangles", true}, {"components", true}, {"cpu_s"}});
}

/// Adds the surface at time t to h, with the CPU seconds the step took.
void add_row(History& h, double t, const Surface& s, double cpu) {
    h.add({t, volume(s), area(s), static_cast<double>(s.size()),
           s.empty() ? 0.0 : static_cast<double>(component_count(s)), cpu});
}

/// (vertices, triangles, notes) of a valid surface made of the arrays, oriented outward;
/// ValueError naming the triangle, edge or vertex at fault.
py::tuple prepare_surface_arrays(const Array& vertices, const IndexArray& triangles) {
    Surface raw = surface_of(vertices, triangles);
    std::optional<PreparedSurface> p;
    {
        py::gil_scoped_release release;
        p.emplace(prepare_surface(std::move(raw)));
    }
    const py::tuple arrays = surface_arrays(p->surface);
    return py::make_tuple(arrays[0], arrays[1], p->notes);
}

/// The surface read() gives, prepared (InvalidInput naming path when it is not valid):
/// (vertices, triangles, notes).
template <class Read>
py::tuple prepared_arrays(const std::string& path, Read read) {
    std::optional<PreparedSurface> p;
    {
        py::gil_scoped_release release;
        Surface raw = read();
        try {
            p.emplace(prepare_surface(std::move(raw)));
        } catch (const InvalidInput& e) {
            throw InvalidInput(fmt::format("{}: {}", path, e.what()));
        }
    }
    const py::tuple arrays = surface_arrays(p->surface);
    return py::make_tuple(arrays[0], arrays[1], p->notes);
}

/// A surface file (.obj, .stl, .ply, .vdb) read and prepared: (vertices, triangles, notes).
py::tuple load_surface_file(const std::string& path) {
    return prepared_arrays(path, [&] { return read_surface(path); });
}

/// The zero set of an OpenVDB file's level-set grid (the first, or the one named), contoured
/// and prepared: (vertices, triangles, notes).
py::tuple load_vdb_file(const std::string& path, const std::string& grid,
                        std::optional<int> depth) {
    return prepared_arrays(
        path, [&] { return read_vdb_level_set(path, {.grid = grid, .depth = depth}); });
}

/// Writes a valid surface as an OpenVDB narrow-band level set (write_vdb_level_set).
void save_vdb_file(const std::string& path, const Array& vertices, const IndexArray& triangles,
                   double voxel, double half_width, const std::string& name) {
    const Surface s = surface_of(vertices, triangles);
    py::gil_scoped_release release;
    write_vdb_level_set(path, s, {.voxel = voxel, .half_width = half_width, .name = name});
}

/// Writes a surface as .obj or .vtp (by the extension), atomically.
void save_surface_file(const std::string& path, const Array& vertices, const IndexArray& triangles,
                       double time) {
    if (!std::isfinite(time)) throw InvalidInput(fmt::format("time must be finite, got {}", time));
    const Surface s = surface_of(vertices, triangles);
    const std::filesystem::path file(path);
    if (file.extension() == ".obj") {
        write_file_atomic(file, obj_text(s));
    } else if (file.extension() == ".vtp") {
        write_file_atomic(file, vtp_text(s, time));
    } else {
        throw InvalidInput(fmt::format("a surface is saved as .obj or .vtp, got '{}'", path));
    }
}

/// Sets d's volume, area, components and genus to those of s (valid).
void put_measures(py::dict& d, const Surface& s) {
    d["volume"] = volume(s);
    d["area"] = area(s);
    d["components"] = component_count(s);
    d["genus"] = genus(s);
}

/// volume, area, components and genus of a valid surface.
py::dict surface_measures(const Array& vertices, const IndexArray& triangles) {
    py::dict d;
    put_measures(d, surface_of(vertices, triangles));
    return d;
}

/// (distances (m,), nearest points (m, 3)) of a valid surface at the (m, 3) points, as `slc
/// distance` with a surface file: the domain and tree depth it takes, on `threads` threads.
py::tuple surface_distance(const Array& vertices, const IndexArray& triangles,
                           const Array& xs_array, int threads) {
    const Surface surface = surface_of(vertices, triangles);
    if (surface.empty()) throw InvalidInput("the surface has no triangles");
    const std::vector<Vec3> xs = query_points3_of(xs_array);
    const std::vector<SurfacePoint> answers = without_gil(threads, [&] {
        const Box3 domain = default_domain(bounding_box(surface));
        const SurfaceDistanceTree tree(
            surface, domain, {.depth = SurfaceDistanceTree::default_depth(surface, domain)});
        return tree.closest_points(xs);
    });
    std::vector<double> d(xs.size());
    std::vector<Vec3> nearest(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) {
        d[i] = answers[i].distance;
        nearest[i] = answers[i].point;
    }
    return py::make_tuple(array_of(std::span<const double>(d)),
                          array_of(std::span<const Vec3>(nearest)));
}

std::shared_ptr<SurfaceSubject> named_surface_problem(const std::string& name,
                                                      const VelocityParams& params) {
    auto s = std::make_shared<SurfaceSubject>();
    {
        py::gil_scoped_release release;
        s->problem = make_surface_problem(name, params);
    }
    s->named = true;
    return s;
}

std::shared_ptr<SurfaceSubject> user_surface_problem(const Array& vertices,
                                                     const IndexArray& triangles, double t_start,
                                                     double t_end, const LawSpec& spec) {
    auto s = std::make_shared<SurfaceSubject>();
    Surface surface = surface_of(vertices, triangles);
    if (surface.empty()) throw InvalidInput("the surface has no triangles");
    if (!std::isfinite(t_start) || !std::isfinite(t_end) || !(t_end > t_start)) {
        throw InvalidInput(
            fmt::format("t_end ({}) must come after the surface's time ({})", t_end, t_start));
    }
    s->problem.law = make_surface_law(spec);
    s->problem.name = spec.name;
    s->problem.domain = default_domain(bounding_box(surface));
    s->problem.initial = std::move(surface);
    s->problem.t_end = t_end;
    s->t_start = t_start;
    return s;
}

py::dict run_surface_problem(const SurfaceSubject& subject, const RunOverrides& q, int frames,
                             int threads, const py::object& on_step, bool estimate) {
    check_frames(frames);
    // Held to the end: the start as the steps read it and the summary (which reports
    // thread_count()) have the run's threads.
    const ThreadScope thread_scope(threads);
    // (Not const: surface_as_read may deepen its thin cells.)
    SurfaceRunOptions options = surface_run_options(subject.problem, subject.named, subject.t_start,
                                                    with_frames(q, frames));
    if (estimate) require_half_resolution(options.steps, options.step.contour.depth, "estimate");
    const std::optional<SurfaceRunOptions> coarse =
        estimate ? std::optional(surface_resolution_options(options, -1)) : std::nullopt;
    const SurfaceProblem& p = subject.problem;
    Surface initial;  // a named problem's surface at the caller's K, P, ε, η
    if (subject.named && sets_contour(q)) {
        py::gil_scoped_release release;
        initial = initial_surface(p, options.step.contour);
    } else if (!subject.named) {  // a user's surface as the steps read it
        py::gil_scoped_release release;
        initial = surface_as_read(p.initial, p.domain, options);
    } else {
        initial = p.initial;
    }
    for (const Vec3& v : initial.vertices) {
        if (!p.domain.contains(v)) throw InvalidInput("the surface leaves the domain it runs in");
    }
    History history = surface_history();
    add_row(history, options.t_start, initial, 0.0);
    py::list frame_list;
    if (frames > 0) {
        const py::tuple a = surface_arrays(initial);
        frame_list.append(py::make_tuple(options.t_start, a[0], a[1]));
    }
    double cpu_before = 0.0;
    const SurfaceObserver observer = [&](const SurfaceStepReport& s) {
        const double cpu = s.run->cpu_s - cpu_before;
        cpu_before = s.run->cpu_s;
        add_row(history, s.t, *s.surface, cpu);
        py::gil_scoped_acquire hold;
        if (is_frame(s.step, s.steps, frames)) {
            const py::tuple a = surface_arrays(*s.surface);
            frame_list.append(py::make_tuple(s.t, a[0], a[1]));
        }
        if (interrupted()) return false;
        if (on_step.is_none()) return true;
        const py::tuple a = surface_arrays(*s.surface);
        const py::object go_on = on_step(s.step, s.steps, s.t, a[0], a[1], cpu);
        return observer_goes_on(go_on);
    };
    const SurfaceRunResult r =
        without_gil(threads, [&] { return run(initial, *p.law, p.domain, options, observer); });
    const py::tuple a = surface_arrays(r.surface);
    py::dict out;
    out["vertices"] = a[0];
    out["triangles"] = a[1];
    put_end(out, r, history, frame_list);
    nlohmann::json summary = surface_run_summary(p, initial, options, r);
    if (coarse) {
        summary["error_estimate"] =
            error_estimate(initial, *p.law, p.domain, *coarse, r, threads, "surface");
    }
    out["summary"] = python_of(summary);
    return out;
}

py::dict self_convergence_surface(const SurfaceSubject& subject, int resolutions,
                                  const RunOverrides& q, int threads, const py::object& on_run) {
    if (subject.named) {
        throw InvalidInput(
            "a self-convergence study takes a Surface under a velocity; a named problem's own "
            "study is slc.study(slc.problem(name))");
    }
    const SurfaceRunOptions base =
        surface_run_options(subject.problem, subject.named, subject.t_start, q);
    auto run_dict = [](const SurfaceResolutionRun& r) {
        const Surface& f = r.result.surface;
        py::dict d;
        d["level"] = r.level;
        d["run"] = run_name(r.options);
        d["N"] = r.options.steps;
        d["K"] = r.options.step.contour.depth;
        d["eps"] = r.options.step.contour.resolved_eps();
        d["status"] = to_string(r.result.status);
        d["message"] = r.result.message;
        d["t"] = r.result.t;
        put_measures(d, f);
        d["unconverged_steps"] = r.result.unconverged_steps;
        d["largest_residual"] = r.result.largest_residual;
        d["cpu_s"] = r.result.cpu_s;
        const py::tuple a = surface_arrays(f);
        d["vertices"] = a[0];
        d["triangles"] = a[1];
        return d;
    };
    const SurfaceSelfConvergenceObserver observer = observer_calling(on_run, run_dict);
    const SurfaceSelfConvergenceResult s = without_gil(threads, [&] {
        return surface_self_convergence(subject.problem.initial, *subject.problem.law,
                                        subject.problem.domain, base, resolutions, observer);
    });
    return self_convergence_dict(s, run_dict);
}

py::dict surface_cell_dict(const SurfaceStudyCell& c) {
    py::dict d;
    d["row"] = c.row;
    d["P"] = c.refine;
    d["N"] = c.options.steps;
    d["K"] = c.options.step.contour.depth;
    d["eps"] = c.options.step.contour.resolved_eps();
    d["status"] = to_string(c.status);
    d["e_inf"] = c.e_inf ? py::cast(*c.e_inf) : py::object(py::none());
    d["cpu_s_per_step"] = c.cpu_s_per_step;
    d["wall_s"] = c.wall_s;
    d["triangles"] = c.triangles;
    return d;
}

py::dict study_surface_problem(const SurfaceSubject& subject, int rows, int columns, int threads,
                               const py::object& on_cell) {
    const SurfaceStudyObserver observer = observer_calling(on_cell, surface_cell_dict);
    const SurfaceStudyResult s = without_gil(
        threads, [&] { return surface_study(subject.problem, rows, columns, observer); });
    return study_dict(
        s, surface_cell_dict,
        order_table([&s](int r, int c) { return s.column_order(r, c); }, s.rows - 1, s.columns));
}

}  // namespace

void add_surface_functions(py::module_& m) {
    py::class_<SurfaceSubject, std::shared_ptr<SurfaceSubject>>(m, "SurfaceProblem")
        .def_property_readonly("name", [](const SurfaceSubject& s) { return s.problem.name; })
        .def_property_readonly("description",
                               [](const SurfaceSubject& s) { return s.problem.description; })
        .def_property(
            "t_end", [](const SurfaceSubject& s) { return s.problem.t_end; },
            [](SurfaceSubject& s, double t) { s.problem.t_end = t; })
        .def_property_readonly("velocity",
                               [](const SurfaceSubject& s) { return s.problem.law->name(); })
        .def_property_readonly("settings",
                               [](const SurfaceSubject& s) {
                                   py::dict d;
                                   d["steps"] = s.problem.steps;
                                   d["depth"] = s.problem.depth;
                                   d["refine"] = "converged";
                                   d["eps"] = s.problem.eps;
                                   d["thin_depth"] = s.problem.thin_depth;
                                   return d;
                               })
        .def_property_readonly("domain",
                               [](const SurfaceSubject& s) {
                                   const Box3& b = s.problem.domain;
                                   return py::make_tuple(b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y,
                                                         b.hi.z);
                               })
        .def_property_readonly(
            "initial", [](const SurfaceSubject& s) { return surface_arrays(s.problem.initial); })
        .def_property_readonly("has_exact",
                               [](const SurfaceSubject& s) { return bool(s.problem.exact); })
        .def_property_readonly("has_study",
                               [](const SurfaceSubject& s) { return s.problem.study.has_value(); })
        .def(
            "exact",
            [](const SurfaceSubject& s, const Array& xs, double t) -> py::object {
                if (!s.problem.exact) return py::none();
                const std::vector<Vec3> points = query_points3_of(xs);
                const std::size_t n = points.size();
                std::vector<double> d(n);
                for (std::size_t i = 0; i < n; ++i) d[i] = s.problem.exact(t, points[i]);
                if (n > 0 && std::isnan(d[0])) return py::none();
                return array_of(std::span<const double>(d));
            },
            py::arg("points"), py::arg("t"))
        .def(
            "error",
            [](const SurfaceSubject& s, const Array& vertices, const IndexArray& triangles,
               double t) -> py::object {
                const auto e = surface_error(s.problem, t, surface_of(vertices, triangles));
                return e ? py::cast(*e) : py::object(py::none());
            },
            py::arg("vertices"), py::arg("triangles"), py::arg("t"));
    m.def("make_surface_problem", &named_surface_problem, py::arg("name"), py::arg("params"));
    m.def("surface_problems", [] {
        py::list out;
        for (const std::string& name : surface_problem_names())
            out.append(py::make_tuple(name, surface_problem_summary(name)));
        return out;
    });
    m.def("user_surface_problem", &user_surface_problem, py::arg("vertices"), py::arg("triangles"),
          py::arg("t_start"), py::arg("t_end"), py::arg("law"));
    m.def("run_surface", &run_surface_problem, py::arg("problem"), py::arg("options"),
          py::arg("frames"), py::arg("threads"), py::arg("on_step"), py::arg("estimate"));
    m.def("self_convergence_surface", &self_convergence_surface, py::arg("problem"),
          py::arg("rows"), py::arg("options"), py::arg("threads"), py::arg("on_run"));
    m.def("study_surface", &study_surface_problem, py::arg("problem"), py::arg("rows"),
          py::arg("columns"), py::arg("threads"), py::arg("on_cell"));
    m.def("prepare_surface", &prepare_surface_arrays, py::arg("vertices"), py::arg("triangles"));
    m.def("load_surface", &load_surface_file, py::arg("path"));
    m.def("save_surface", &save_surface_file, py::arg("path"), py::arg("vertices"),
          py::arg("triangles"), py::arg("time"));
    m.def("load_vdb", &load_vdb_file, py::arg("path"), py::arg("grid"), py::arg("depth"));
    m.def("save_vdb", &save_vdb_file, py::arg("path"), py::arg("vertices"), py::arg("triangles"),
          py::arg("voxel"), py::arg("half_width"), py::arg("name"));
    m.def("surface_distance", &surface_distance, py::arg("vertices"), py::arg("triangles"),
          py::arg("points"), py::arg("threads"));
    m.def("surface_measures", &surface_measures, py::arg("vertices"), py::arg("triangles"));
    m.def(
        "up_axis",
        [](const std::vector<double>& lo, const std::vector<double>& hi) {
            if (lo.size() != 3 || hi.size() != 3)
                throw InvalidInput("up_axis: a box's corners are 3 coordinates each");
            const UpAxis up = up_axis(Box3{{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}});
            return std::string(up == UpAxis::x ? "x" : up == UpAxis::y ? "y" : "z");
        },
        py::arg("lo"), py::arg("hi"));
}

}  // namespace slc::python
