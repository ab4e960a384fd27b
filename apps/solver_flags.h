// The solver, build, compatibility and export options as flags (their tables: solver_options.h,
// formulation.h, compat.h, trajectory_export.h).
#ifndef DYNSLAM_APPS_SOLVER_FLAGS_H_
#define DYNSLAM_APPS_SOLVER_FLAGS_H_

#include <string>
#include <vector>

#include "arg_parser.h"
#include "dynslam/compat.h"
#include "dynslam/formulation.h"
#include "dynslam/solver.h"
#include "dynslam/trajectory_export.h"

namespace dynslam::cli {

using SolverFlags = TableFlags<SolverOptions>;
using BuildFlags = TableFlags<BuildOptions>;
using CompatFlags = TableFlags<Compat>;
using ExportFlags = TableFlags<ExportOptions>;

// Every formulation's name, for AddChoice.
std::vector<std::string> FormulationChoices();

// Prints one line per linear solve to stderr once a solve has run for `after_s` seconds.
void PrintStepLines(SolverOptions* options, double after_s);

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_SOLVER_FLAGS_H_
