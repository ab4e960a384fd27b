// The repository's Python scripts run by the commands (plots, HTML reports): a convenience, so a
// missing python3, script or package is a warning line, never a failure of the command.
#ifndef DYNSLAM_APPS_PYTHON_SCRIPTS_H_
#define DYNSLAM_APPS_PYTHON_SCRIPTS_H_

#include <string>
#include <vector>

namespace dynslam::cli {

// The arguments plot_compare.py and html_report.py share: OUT_DIR --title=TITLE [--gt=GT].
std::vector<std::string> ReportArguments(const std::string& out_dir, const std::string& title,
                                         const std::string& gt_path);

// Runs /usr/bin/python3 SCRIPTS_DIR/script args… (SCRIPTS_DIR: $DYNSLAM_SCRIPTS_DIR, else the
// repository's scripts/ folder) with stdin from /dev/null and its output on stderr; `what` names
// the outputs a warning says are missing ("no plots"). Returns the script's exit code, or -1
// when it could not be run (after the warning).
int RunPythonScript(const std::string& script, const std::vector<std::string>& args,
                    const std::string& what);

// Runs python3 SCRIPTS_DIR/script args… as a command of its own: stdin, stdout and stderr are
// this process's, and $DYNSLAM_CLI names this dynslam. Returns its exit code, or 1 after an error
// line when it could not be run.
int RunPythonCommand(const std::string& script, const std::vector<std::string>& args);

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_PYTHON_SCRIPTS_H_
