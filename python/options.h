// Keyword arguments → the library's option structs, one table per struct: every field by its
// C++ name (SolverOptions::max_iterations is `max_iterations=`), enums by their command-line
// spelling (`minimizer="lm"`). An unknown name or a bad value raises TypeError or ValueError.
#ifndef DYNSLAM_PYTHON_OPTIONS_H_
#define DYNSLAM_PYTHON_OPTIONS_H_

#include <pybind11/pybind11.h>

#include "dynslam/formulation.h"
#include "dynslam/simulate.h"
#include "dynslam/solver.h"

namespace dynslam::python {

SolverOptions ToSolverOptions(const pybind11::kwargs& options);
BuildOptions ToBuildOptions(const pybind11::kwargs& options);
SimulateOptions ToSimulateOptions(const pybind11::kwargs& options);

}  // namespace dynslam::python

#endif  // DYNSLAM_PYTHON_OPTIONS_H_
