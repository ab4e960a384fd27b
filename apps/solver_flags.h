// The solver and build options as flags (their tables: solver_options.h, formulation.h).
#ifndef DYNSLAM_APPS_SOLVER_FLAGS_H_
#define DYNSLAM_APPS_SOLVER_FLAGS_H_

#include <string>
#include <vector>

#include "cli.h"
#include "dynslam/formulation.h"
#include "dynslam/solver.h"

namespace dynslam::cli {

using SolverFlags = TableFlags<SolverOptions>;
using BuildFlags = TableFlags<BuildOptions>;

// Every formulation's name, for AddChoice.
std::vector<std::string> FormulationChoices();

// Prints one line per linear solve to stderr once a solve has run for more than a second.
void PrintProgressAfterOneSecond(SolverOptions* options);

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_SOLVER_FLAGS_H_
