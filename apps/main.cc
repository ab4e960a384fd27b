// `dynslam <command> [options]`: dispatches to one file per subcommand.
#include <csignal>
#include <cstring>
#include <iostream>

#include "arg_parser.h"
#include "commands.h"
#include "huge_page_heap.h"
#include "inline_openmp_regions.h"
#include "version.h"

namespace {

struct Command {
  const char* name;
  const char* summary;
  int (*run)(int argc, char** argv);  // argv[0] is the program, argv[1] the command
};

constexpr Command kCommands[] = {
    {"bench", "compare solvers on identical graph files: time, memory, final cost, distance "
              "to the best answer", dynslam::cli::RunBench},
    {"build", "build one formulation (wc, oc_a, oc_b, oc_c, hy) from a front-end file",
     dynslam::cli::RunBuild},
    {"compare", "build, solve and score every formulation; print the paper's Tables I-III",
     dynslam::cli::RunCompare},
    {"metrics", "score a solved graph file against ground truth (SPEC §5)",
     dynslam::cli::RunMetrics},
    {"options", "print every solver, build, simulation, export and compatibility option (docs/OPTIONS.md)",
     dynslam::cli::RunOptions},
    {"simulate", "simulate a front end on KITTI Tracking ground truth (or a synthetic scene)",
     dynslam::cli::RunSimulate},
    {"solve", "solve a graph file and write the outputs of SPEC §4", dynslam::cli::RunSolve},
    {"verify", "compare a solve's outputs with a reference solve (GTSAM)", dynslam::cli::RunVerify},
};

void PrintUsage(std::ostream& out) {
  out << "usage: dynslam <command> [options]   (dynslam <command> --help for details)\n"
      << "       dynslam --version\n\n"
      << "Dynamic SLAM back ends on Ceres Solver.\n\ncommands:\n";
  for (const Command& command : kCommands) {
    out << "  " << command.name << "\n      " << command.summary << "\n";
  }
  out << "\nenvironment:\n"
      << "  DYNSLAM_HUGE_PAGES=0\n      keep the heap on ordinary 4 KiB pages (docs/SOLVER.md \"Page "
         "faults\")\n"
      << "  DYNSLAM_INLINE_OPENMP=0\n      run CHOLMOD's one-thread OpenMP regions through libgomp "
         "(docs/SOLVER.md\n      \"OpenMP regions of one thread\")\n"
      << "  DYNSLAM_SCRIPTS_DIR\n      where `compare` finds its plotting scripts\n";
}

}  // namespace

int main(int argc, char** argv) {
  dynslam::AdviseHugePagesForTheHeap();  // before anything large is allocated
  dynslam::InlineOneThreadOpenMpRegions();
  // Past a file-size limit (ulimit -f) a write then fails with EFBIG and the output writers
  // report the file (dynslam/file_io.h), instead of SIGXFSZ ending the process mid-write.
  std::signal(SIGXFSZ, SIG_IGN);
  // Ctrl-C in `dynslam … | tee log` ends tee too; a progress line written after that must fail
  // with EPIPE rather than kill the process before it has saved its outputs.
  std::signal(SIGPIPE, SIG_IGN);
  if (argc < 2) {
    PrintUsage(std::cerr);
    return dynslam::cli::kExitBadInput;
  }
  if (std::strcmp(argv[1], "--version") == 0) {
    std::cout << "dynslam " << DYNSLAM_VERSION << " (git " << DYNSLAM_GIT_COMMIT << ")\n";
    return dynslam::cli::kExitOk;
  }
  if (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    PrintUsage(std::cout);
    return dynslam::cli::kExitOk;
  }
  for (const Command& command : kCommands) {
    if (std::strcmp(argv[1], command.name) == 0) return command.run(argc, argv);
  }
  std::cerr << "error: unknown command '" << argv[1] << "'\n";
  PrintUsage(std::cerr);
  return dynslam::cli::kExitBadInput;
}
