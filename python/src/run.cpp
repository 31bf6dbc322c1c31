// Runs, named problems and convergence studies on numpy arrays. A run is always a Problem: a
// named one (its paper settings) or a user's curves with the defaults of `slc run --initial`
// (curve_problem); options the caller sets override either, as the tool's flags do.
#include "run.hpp"

#include <pybind11/stl.h>

#include <cmath>

#include "arrays.hpp"
#include "calls.hpp"
#include "laws.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/evolve/problems.hpp"
#include "slc/evolve/run.hpp"
#include "slc/evolve/self_convergence.hpp"
#include "slc/evolve/study.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/summary.hpp"

namespace slc::python {
namespace {

/// The history of a run of curves: t, area, length, components, segments, cpu_s per row.
History curve_history() {
    return History(
        {{"t"}, {"area"}, {"length"}, {"components", true}, {"segments", true}, {"cpu_s"}});
}

/// Adds the curves at time t to h, with the CPU seconds the step took.
void add_row(History& h, double t, const Interface& curves, double cpu) {
    h.add({t, area(curves), length(curves), static_cast<double>(curves.curve_count()),
           static_cast<double>(curves.size()), cpu});
}

/// The problem's law: spec when given (a user's curves), else the problem's built-in one.
std::unique_ptr<VelocityLaw> law_of(const Problem& p, const std::optional<LawSpec>& spec) {
    if (spec) return make_law(*spec);
    return make_velocity(p.velocity, p.velocity_params, p.module);
}

/// The problem's initial curves, validated in its domain.
Interface initial_of(const Problem& p) { return prepare_interface(p.initial, p.domain).curves; }

py::dict run_problem(const Problem& p, const std::optional<LawSpec>& spec, const RunOverrides& q,
                     int frames, int threads, const py::object& on_step, bool estimate) {
    check_frames(frames);
    // Held to the end: the summary reports the threads the run had (thread_count()).
    const ThreadScope thread_scope(threads);
    const std::unique_ptr<VelocityLaw> law = law_of(p, spec);
    const Interface initial = initial_of(p);
    const RunOptions options = run_options(p, with_frames(q, frames));
    // The run at half resolution, resolved first: one it cannot have is bad input before
    // anything runs.
    if (estimate) require_half_resolution(options.steps, options.step.contour.depth, "estimate");
    const std::optional<RunOptions> coarse =
        estimate ? std::optional(resolution_options(options, -1)) : std::nullopt;

    History history = curve_history();
    add_row(history, options.t_start, initial, 0.0);
    py::list frame_list;
    if (frames > 0) frame_list.append(py::make_tuple(options.t_start, arrays_of(initial)));
    const Observer observer = [&](const StepReport& s) {
        add_row(history, s.t, *s.curves, s.step_cpu_s);
        py::gil_scoped_acquire hold;
        if (is_frame(s.step, s.steps, frames))
            frame_list.append(py::make_tuple(s.t, arrays_of(*s.curves)));
        if (interrupted()) return false;
        if (on_step.is_none()) return true;
        const py::object go_on = on_step(s.step, s.steps, s.t, arrays_of(*s.curves), s.step_cpu_s);
        return observer_goes_on(go_on);
    };

    const RunResult r =
        without_gil(threads, [&] { return run(initial, *law, p.domain, options, observer); });
    py::dict out;
    out["curves"] = arrays_of(r.curves);
    put_end(out, r, history, frame_list);
    nlohmann::json summary = run_summary(p, options, r, *law);
    if (coarse) {
        summary["error_estimate"] =
            error_estimate(initial, *law, p.domain, *coarse, r, threads, "curves");
    }
    out["summary"] = python_of(summary);
    return out;
}

/// One cell of a study as a dict: row, P, run, N, K, eps, S, status, e_inf, cpu_s_per_step,
/// g_evals_per_vertex, segments, stopped_by_guards (the guards' message where they stopped the
/// run and the cell was run again without them, else None).
py::dict cell_dict(const StudyCell& c) {
    py::dict d;
    d["row"] = c.row;
    d["P"] = c.refine;
    d["run"] = run_name(c.options);
    d["N"] = c.options.steps;
    d["K"] = c.options.step.contour.depth;
    d["eps"] = c.options.step.contour.resolved_eps();
    d["S"] = c.options.step.embedded.smoothing;
    d["status"] = to_string(c.status);
    d["e_inf"] = c.e_inf ? py::cast(*c.e_inf) : py::object(py::none());
    d["cpu_s_per_step"] = c.cpu_s_per_step;
    d["g_evals_per_vertex"] = c.g_evals_per_vertex;
    d["segments"] = c.segments;
    d["stopped_by_guards"] = c.stopped.empty() ? py::object(py::none()) : py::cast(c.stopped);
    return d;
}

py::dict study_problem(const Problem& p, int rows, const RunOverrides& q, int threads,
                       const py::object& on_cell) {
    if (!p.exact)
        throw InvalidInput("problem '" + p.name +
                           "' has no exact solution; study a user's curves (self-convergence)");
    const RunOptions base = run_options(p, q);
    const StudyObserver observer = observer_calling(on_cell, cell_dict);
    const StudyResult s = without_gil(threads, [&] { return study(p, rows, base, observer); });
    return study_dict(
        s, cell_dict,
        order_table(
            [&s](int r, int c) { return r + 1 < s.rows ? s.column_order(r, c) : std::nullopt; },
            s.rows, s.columns));
}

py::dict self_convergence_problem(const Problem& p, const std::optional<LawSpec>& spec,
                                  int resolutions, const RunOverrides& q, int threads,
                                  const py::object& on_run) {
    const std::unique_ptr<VelocityLaw> law = law_of(p, spec);
    const Interface initial = initial_of(p);
    const RunOptions base = run_options(p, q);
    auto run_dict = [](const ResolutionRun& r) {
        py::dict d;
        d["level"] = r.level;
        d["run"] = run_name(r.options);
        d["status"] = to_string(r.result.status);
        d["t"] = r.result.t;
        d["area"] = area(r.result.curves);
        d["components"] = r.result.curves.curve_count();
        d["segments"] = r.result.curves.size();
        d["cpu_s"] = r.result.cpu_s;
        d["curves"] = arrays_of(r.result.curves);
        return d;
    };
    const SelfConvergenceObserver observer = observer_calling(on_run, run_dict);
    const SelfConvergenceResult s = without_gil(threads, [&] {
        return self_convergence(initial, *law, p.domain, base, resolutions, observer);
    });
    return self_convergence_dict(s, run_dict);
}

Problem curve_problem_of(const std::vector<Array>& arrays, double t_start, double t_end,
                         const LawSpec& spec) {
    const Curves raw = curves_of(arrays);
    const Interface curves(raw);
    const std::unique_ptr<VelocityLaw> law = make_law(spec);
    Problem p = curve_problem(spec.name, curves, default_domain(raw), t_start, t_end, *law,
                              spec.name, spec.params);
    if (spec.kind == "speed" || spec.kind == "field") {
        p.velocity = spec.kind;
        p.velocity_expression = spec.velocity.cast<std::string>();
    } else if (spec.kind == "field-file") {
        p.velocity = spec.kind;
        p.velocity_file = spec.velocity.cast<std::string>();
        p.velocity_zero_outside = spec.zero_outside;
    }
    return p;
}

py::dict problem_parameters(const Problem& p) {
    py::dict d;
    for (const ProblemParameter& q : p.parameters) d[py::str(q.name)] = q.value;
    return d;
}

}  // namespace

void add_run_functions(py::module_& m) {
    py::class_<LawSpec>(m, "LawSpec")
        .def(py::init([](py::object velocity, std::string kind, std::string name,
                         VelocityParams params, std::optional<std::string> geometry,
                         bool zero_outside) {
                 return LawSpec{std::move(velocity), std::move(kind),     std::move(name),
                                std::move(params),   std::move(geometry), zero_outside};
             }),
             py::arg("velocity"), py::arg("kind"), py::arg("name"), py::arg("params"),
             py::arg("geometry"), py::arg("zero_outside") = false);
    py::class_<RunOverrides>(m, "RunOverrides")
        .def(py::init<>())
        .def_readwrite("steps", &RunOverrides::steps)
        .def_readwrite("depth", &RunOverrides::depth)
        .def_readwrite("refine", &RunOverrides::refine)
        .def_readwrite("eps", &RunOverrides::eps)
        .def_readwrite("eta", &RunOverrides::eta)
        .def_readwrite("smoothing", &RunOverrides::smoothing)
        .def_property(
            "extension",
            [](const RunOverrides& q) {
                return q.extension ? std::optional(to_string(*q.extension)) : std::nullopt;
            },
            [](RunOverrides& q, const std::optional<std::string>& name) {
                q.extension =
                    name
                        ? std::optional(value_named<Extension>(extension_names, *name, "extension"))
                        : std::nullopt;
            })
        .def_readwrite("arcs", &RunOverrides::arcs)
        .def_readwrite("area_correction", &RunOverrides::area_correction)
        .def_readwrite("thin_depth", &RunOverrides::thin_depth)
        .def_readwrite("volume_drift", &RunOverrides::volume_drift)
        .def_readwrite("guards", &RunOverrides::guards)
        .def_readwrite("until_components", &RunOverrides::until_components);
    py::class_<Problem>(m, "Problem")
        .def_readonly("name", &Problem::name)
        .def_readonly("description", &Problem::description)
        .def_readonly("t_start", &Problem::t_start)
        .def_readwrite("t_end", &Problem::t_end)
        .def_property_readonly("steps", [](const Problem& p) { return p.run.steps; })
        .def_property_readonly("depth", [](const Problem& p) { return p.run.step.contour.depth; })
        .def_property_readonly(
            "refine",
            [](const Problem& p) { return refine_name(p.run.step.contour.refine_passes); })
        .def_property_readonly("eps",
                               [](const Problem& p) { return p.run.step.contour.resolved_eps(); })
        .def_property_readonly("eta",
                               [](const Problem& p) { return p.run.step.contour.resolved_eta(); })
        .def_property_readonly("smoothing",
                               [](const Problem& p) { return p.run.step.embedded.smoothing; })
        .def_readonly("length_scale", &Problem::length_scale)
        .def_readonly("velocity", &Problem::velocity)
        .def_readonly("velocity_params", &Problem::velocity_params)
        .def_property_readonly("parameters", &problem_parameters)
        .def_property_readonly("domain",
                               [](const Problem& p) {
                                   return py::make_tuple(p.domain.lo.x, p.domain.lo.y,
                                                         p.domain.hi.x, p.domain.hi.y);
                               })
        .def_property_readonly("initial",
                               [](const Problem& p) {
                                   std::optional<Interface> curves;
                                   {
                                       py::gil_scoped_release release;
                                       curves.emplace(initial_of(p));
                                   }
                                   return arrays_of(*curves);
                               })
        .def_property_readonly("has_exact", [](const Problem& p) { return bool(p.exact); })
        .def(
            "exact",
            [](const Problem& p, const Array& xs, double t) -> py::object {
                if (!p.exact) return py::none();
                const std::vector<Vec2> points = query_points_of(xs);
                const auto d = p.exact(points, t);
                if (!d) return py::none();
                return array_of(std::span<const double>(*d));
            },
            py::arg("points"), py::arg("t"))
        .def(
            "error",
            [](const Problem& p, const std::vector<Array>& curves, double t) -> py::object {
                const auto e = max_error(p, Interface(curves_of(curves)), t);
                return e ? py::cast(*e) : py::object(py::none());
            },
            py::arg("curves"), py::arg("t"));
    m.def(
        "make_problem",
        [](const std::string& name, const VelocityParams& params) {
            Problem p = make_problem(name, params);
            law_of(p, std::nullopt);  // a parameter neither the problem's nor its law's: refused
            return p;
        },
        py::arg("name"), py::arg("params"));
    m.def("problems", [] {
        py::list out;
        for (const ProblemInfo& p : problem_catalog())
            out.append(py::make_tuple(p.name, p.summary));
        return out;
    });
    m.def("curve_problem", &curve_problem_of, py::arg("curves"), py::arg("t_start"),
          py::arg("t_end"), py::arg("law"));
    m.def("run", &run_problem, py::arg("problem"), py::arg("law"), py::arg("options"),
          py::arg("frames"), py::arg("threads"), py::arg("on_step"), py::arg("estimate"));
    m.def("study", &study_problem, py::arg("problem"), py::arg("rows"), py::arg("options"),
          py::arg("threads"), py::arg("on_cell"));
    m.def("self_convergence", &self_convergence_problem, py::arg("problem"), py::arg("law"),
          py::arg("resolutions"), py::arg("options"), py::arg("threads"), py::arg("on_run"));
}

}  // namespace slc::python
