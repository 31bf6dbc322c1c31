// Runs, named problems and convergence studies for the module slc._slc.
#pragma once

#include <pybind11/pybind11.h>

namespace slc::python {

/// Adds Problem, make_problem, problems, curve_problem, run, study and self_convergence to m.
void add_run_functions(pybind11::module_& m);

}  // namespace slc::python
