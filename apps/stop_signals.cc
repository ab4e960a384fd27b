#include "stop_signals.h"

#include <unistd.h>

#include <cerrno>
#include <csignal>

namespace dynslam::cli {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;

// Async-signal-safe calls only.
extern "C" void OnStopSignal(int signal_number) {
  const int saved_errno = errno;  // the interrupted code may be about to read it
  if (g_stop_signal != 0) {
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
    errno = saved_errno;
    return;
  }
  g_stop_signal = signal_number;
  static const char kMessage[] =
      "\ndynslam: stopping after the current step and writing the outputs (signal again to quit "
      "at once, losing them)\n";
  [[maybe_unused]] const ssize_t ignored = write(STDERR_FILENO, kMessage, sizeof(kMessage) - 1);
  errno = saved_errno;
}

}  // namespace

void StopOnSignals(SolverOptions* options) {
  struct sigaction action = {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // reads and writes in progress go on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  options->should_stop = [] { return g_stop_signal != 0; };
}

int StopSignal() { return g_stop_signal; }

int ExitCodeAfterStopSignal(int exit_code) {
  return g_stop_signal != 0 ? 128 + g_stop_signal : exit_code;
}

}  // namespace dynslam::cli
