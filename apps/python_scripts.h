// The repository's Python scripts run by the commands (plots, HTML reports): a convenience, so a
// missing python3, script or package is a warning line, never a failure of the command.
#ifndef DYNSLAM_APPS_PYTHON_SCRIPTS_H_
#define DYNSLAM_APPS_PYTHON_SCRIPTS_H_

#include <string>
#include <vector>

namespace dynslam::cli {

// Runs /usr/bin/python3 SCRIPTS_DIR/script args… (SCRIPTS_DIR: $DYNSLAM_SCRIPTS_DIR, else the
// repository's scripts/ folder) with stdin from /dev/null and its output on stderr; `what` names
// the outputs a warning says are missing ("no plots").
void RunPythonScript(const std::string& script, const std::vector<std::string>& args,
                     const std::string& what);

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_PYTHON_SCRIPTS_H_
