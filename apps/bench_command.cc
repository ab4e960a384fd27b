// dynslam bench GRAPH... --solvers LIST --out DIR [--gt GT] [--repeat N]: solvers compared on
// identical graph files, each solve its own `dynslam solve` process. The command is
// scripts/bench.py (its --help is this command's), run with this dynslam as $DYNSLAM_CLI.
#include <string>
#include <vector>

#include "commands.h"
#include "python_scripts.h"

namespace dynslam::cli {

int RunBench(int argc, char** argv) {
  return RunPythonCommand("bench.py", std::vector<std::string>(argv + 2, argv + argc));
}

}  // namespace dynslam::cli
