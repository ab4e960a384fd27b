// SIGINT and SIGTERM during a solve: the first asks the solve to stop after its current step
// (SolverOptions::should_stop) so that its outputs are written for the last accepted state; a
// second ends the process at once, as the signal's default action would have.
#ifndef DYNSLAM_APPS_STOP_SIGNALS_H_
#define DYNSLAM_APPS_STOP_SIGNALS_H_

#include "dynslam/solver.h"

namespace dynslam::cli {

// Installs the handlers and sets options->should_stop to poll them.
void StopOnSignals(SolverOptions* options);

// The first SIGINT or SIGTERM received, or 0.
int StopSignal();

// `exit_code`, or 128 + the signal's number after a stop signal (130 SIGINT, 143 SIGTERM), as a
// shell reports a process the signal ended; the outputs are complete either way.
int ExitCodeAfterStopSignal(int exit_code);

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_STOP_SIGNALS_H_
