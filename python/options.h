// Keyword arguments → the library's option structs, from their option tables (options.h): the
// keyword is the option's name, its value the Python type of the option (bool for a switch, str
// for a choice).
// An unknown name or a value of the wrong type raises TypeError, a bad value ValueError naming
// the option.
#ifndef DYNSLAM_PYTHON_OPTIONS_H_
#define DYNSLAM_PYTHON_OPTIONS_H_

#include <string>

#include <pybind11/pybind11.h>

#include "dynslam/formulation.h"
#include "dynslam/simulate.h"
#include "dynslam/solver.h"

namespace dynslam::python {

SolverOptions ToSolverOptions(const pybind11::kwargs& options);
BuildOptions ToBuildOptions(const pybind11::kwargs& options);
SimulateOptions ToSimulateOptions(const pybind11::kwargs& options);

// "    name (type, default value): help" per option, for docstrings.
std::string SolverOptionsDoc();
std::string BuildOptionsDoc();
std::string SimulateOptionsDoc();

}  // namespace dynslam::python

#endif  // DYNSLAM_PYTHON_OPTIONS_H_
