// Moving surfaces, their named problems and studies for the module slc._slc.
#pragma once

#include <pybind11/pybind11.h>

namespace slc::python {

/// Adds SurfaceProblem, make_surface_problem, surface_problems, user_surface_problem,
/// run_surface, study_surface, prepare_surface, load_surface, save_surface and
/// surface_measures to m.
void add_surface_functions(pybind11::module_& m);

}  // namespace slc::python
