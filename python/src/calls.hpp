// What the long calls of the module slc._slc share: the worker threads for one call, Ctrl-C
// between steps, observers that call back into Python, JSON handed to Python, the error estimate
// of a run and what a convergence study found.
#pragma once

#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "arrays.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/evolve/overrides.hpp"
#include "slc/evolve/run.hpp"
#include "slc/evolve/self_convergence.hpp"
#include "slc/evolve/surface_run.hpp"
#include "slc/evolve/surface_study.hpp"
#include "slc/io/summary.hpp"

namespace slc::python {

/// Sets the worker threads for the life of the object (0: OMP_NUM_THREADS when set, else all
/// available cores), and restores them.
class ThreadScope {
public:
    explicit ThreadScope(int threads) : before_(thread_count()) {
        if (threads < 0)
            throw InvalidInput(fmt::format("threads must be 0 or more, got {}", threads));
        set_thread_count(threads);
    }
    ~ThreadScope() { set_thread_count(before_); }
    ThreadScope(const ThreadScope&) = delete;
    ThreadScope& operator=(const ThreadScope&) = delete;

private:
    int before_;
};

/// f() on `threads` worker threads (0: OMP_NUM_THREADS when set, else all available cores), with
/// the GIL released while it runs.
template <class F>
auto without_gil(int threads, F f) {
    const ThreadScope scope(threads);
    pybind11::gil_scoped_release release;
    return f();
}

/// Stops a long call at Ctrl-C: Python's handler has only set a flag while the GIL was released.
/// Call with the GIL held; true when an interrupt was pending (and is now taken).
inline bool interrupted() {
    if (PyErr_CheckSignals() == 0) return false;
    pybind11::error_already_set interrupt;  // KeyboardInterrupt, taken and dropped: stop here
    return true;
}

/// Whether a run goes on after its observer returned `answer`: None and True go on, False stops
/// (numpy's booleans alike); TypeError for anything else, which would otherwise fail to convert
/// with a message that names no observer. Call with the GIL held.
inline bool observer_goes_on(const pybind11::object& answer) {
    if (answer.is_none()) return true;
    pybind11::detail::make_caster<bool> caster;
    if (caster.load(answer, /*convert=*/false)) return static_cast<bool>(caster);
    std::string value = pybind11::repr(answer).cast<std::string>();
    if (value.size() > 40) value = value.substr(0, 37) + "...";
    throw pybind11::type_error(
        fmt::format("the observer must return True, False (to stop the run) or None, got {} {}",
                    Py_TYPE(answer.ptr())->tp_name, value));
}

/// An observer of a study's cells or runs: hands each to on_each (unless None) as dict_of makes
/// it, with the GIL held, and stops the study at Ctrl-C.
template <class DictOf>
auto observer_calling(const pybind11::object& on_each, DictOf dict_of) {
    return [&on_each, dict_of](const auto& each) {
        pybind11::gil_scoped_acquire hold;
        if (interrupted()) throw pybind11::error_already_set();
        if (!on_each.is_none()) on_each(dict_of(each));
    };
}

/// ValueError unless frames (the frames a run returns besides its start) is 0 or more.
inline void check_frames(int frames) {
    if (frames < 0) throw InvalidInput(fmt::format("frames must be 0 or more, got {}", frames));
}

/// q with the frames a run keeps (RunOverrides::frames: a user's run whose steps are not given
/// takes a multiple of them).
inline RunOverrides with_frames(RunOverrides q, int frames) {
    if (frames > 0) q.frames = frames;
    return q;
}

/// Whether step (1..steps) is one of the `frames` kept, evenly spread, the last among them.
inline bool is_frame(int step, int steps, int frames) {
    return frames > 0 && (std::int64_t{step} * frames) % steps < frames;
}

/// Whether a run ended with nothing left.
inline bool ended_empty(const RunResult& r) { return r.curves.empty(); }
inline bool ended_empty(const SurfaceRunResult& r) { return r.surface.empty(); }

/// summary.json's "error_estimate" of the run r (from initial under law in domain): the run
/// again at the options coarse (half resolution) on `threads` threads, stopped by Ctrl-C, and
/// the distance between the two ends; `what` names what moved ("curves", "surface").
template <class Shape, class Law, class Domain, class Options, class Result>
nlohmann::json error_estimate(const Shape& initial, const Law& law, const Domain& domain,
                              const Options& coarse, const Result& r, int threads,
                              const std::string& what) {
    return estimate_json(
        run_name(coarse), r.status,
        [&] {
            const Result c = without_gil(threads, [&] {
                return run(initial, law, domain, coarse, [](const auto&) {
                    pybind11::gil_scoped_acquire hold;
                    return !interrupted();
                });
            });
            return CoarseRun{c.status, c.t, c.cpu_s, ended_empty(c), final_distance(r, c)};
        },
        what);
}

/// Puts how the run r ended into out: "t", "status", "message", "history" and "frames".
template <class Result>
void put_end(pybind11::dict& out, const Result& r, const History& history,
             const pybind11::list& frames) {
    out["t"] = r.t;
    out["status"] = to_string(r.status);
    out["message"] = r.message;
    out["history"] = history.arrays();
    out["frames"] = frames;
}

/// A JSON value as the Python object json.loads makes of it.
inline pybind11::object python_of(const nlohmann::json& j) {
    return pybind11::module_::import("json").attr("loads")(j.dump());
}

/// A self-convergence study as a dict: "runs" (run_dict of each), "distances", "orders" (None
/// where none was observed) and "estimate" (error, order, observed; or None).
template <class Run, class RunDict>
pybind11::dict self_convergence_dict(const BasicSelfConvergenceResult<Run>& s, RunDict run_dict) {
    pybind11::list runs, orders;
    for (const Run& r : s.runs) runs.append(run_dict(r));
    for (const auto& o : s.orders)
        orders.append(o ? pybind11::cast(*o) : pybind11::object(pybind11::none()));
    pybind11::list distances;
    for (const double d : s.distances) distances.append(d);
    pybind11::dict out;
    out["runs"] = runs;
    out["distances"] = distances;
    out["orders"] = orders;
    if (s.estimate) {
        pybind11::dict e;
        e["error"] = s.estimate->error;
        e["order"] = s.estimate->order;
        e["observed"] = s.estimate->observed;
        out["estimate"] = e;
    } else {
        out["estimate"] = pybind11::none();
    }
    return out;
}

/// A convergence table as a dict: "rows", "columns", "cells" (cell_dict of each, row-major),
/// "row_orders" (rows x columns - 1) and column_orders.
template <class Study, class CellDict>
pybind11::dict study_dict(const Study& s, CellDict cell_dict, const pybind11::list& column_orders) {
    pybind11::list cells;
    for (const auto& c : s.cells) cells.append(cell_dict(c));
    pybind11::dict out;
    out["rows"] = s.rows;
    out["columns"] = s.columns;
    out["cells"] = cells;
    out["row_orders"] =
        order_table([&s](int r, int c) { return s.row_order(r, c); }, s.rows, s.columns - 1);
    out["column_orders"] = column_orders;
    return out;
}

}  // namespace slc::python
