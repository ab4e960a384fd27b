#include "solver_flags.h"

#include <cstdio>

namespace dynslam::cli {

std::vector<std::string> FormulationChoices() {
  std::vector<std::string> names;
  for (const FormulationInfo& info : Formulations()) names.push_back(info.name);
  return names;
}

void PrintStepLines(SolverOptions* options, double after_s) {
  options->on_step = [after_s](const StepRecord& row) {
    if (row.time_s < after_s) return;
    std::fprintf(stderr, "step %4d  iteration %4d  cost %.10e  trial %.10e  lambda %.1e  %s  %.2f s\n",
                 row.step, row.iteration, row.cost, row.trial_cost, row.lambda,
                 row.accepted ? "accepted" : "rejected", row.time_s);
  };
}

}  // namespace dynslam::cli
