// What the long calls of the module slc._slc share: the worker threads for one call, Ctrl-C
// between steps, JSON handed to Python, and what a self-convergence study found.
#pragma once

#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/evolve/self_convergence.hpp"

namespace slc::python {

/// Sets the worker threads for the life of the object (0: all cores), and restores them.
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

/// Stops a long call at Ctrl-C: Python's handler has only set a flag while the GIL was released.
/// Call with the GIL held; true when an interrupt was pending (and is now taken).
inline bool interrupted() {
    if (PyErr_CheckSignals() == 0) return false;
    pybind11::error_already_set interrupt;  // KeyboardInterrupt, taken and dropped: stop here
    return true;
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

}  // namespace slc::python
