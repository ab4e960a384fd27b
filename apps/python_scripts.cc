// Running the repository's Python scripts (python_scripts.h).
#include "python_scripts.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>

// The repository's scripts/ folder, set by apps/CMakeLists.txt; the environment variable of the
// same name overrides it at run time (a moved or installed tree).
#ifndef DYNSLAM_SCRIPTS_DIR
#define DYNSLAM_SCRIPTS_DIR ""
#endif

namespace dynslam::cli {
namespace {

// Runs args[0] (an absolute path, no shell: paths may hold spaces or quotes) with stdin from
// /dev/null and its output on stderr (stdout holds the tables). Returns its exit code, or -1
// when it could not be started (glibc reports a failed exec here) or did not exit normally.
// posix_spawn, not fork: the child does not copy the page tables of a process that may hold a
// whole sequence's solve.
// args as exec's null-terminated argv (pointing into args).
std::vector<char*> Argv(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  return argv;
}

// /usr/bin/python3 SCRIPT args…
std::vector<std::string> PythonCommand(const std::string& script,
                                       const std::vector<std::string>& args) {
  std::vector<std::string> command = {"/usr/bin/python3", script};
  command.insert(command.end(), args.begin(), args.end());
  return command;
}

int RunWithOutputOnStderr(const std::vector<std::string>& args) {
  std::vector<char*> argv = Argv(args);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// $DYNSLAM_SCRIPTS_DIR/script, else the repository's; "" (after `missing`'s line) when absent.
std::string ScriptPath(const std::string& script, const std::string& missing) {
  namespace fs = std::filesystem;
  const char* from_environment = std::getenv("DYNSLAM_SCRIPTS_DIR");
  const fs::path path = fs::path(from_environment && *from_environment ? from_environment
                                                                       : DYNSLAM_SCRIPTS_DIR) /
                        script;
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return path.string();
  std::cerr << missing << "no " << path.string() << " (DYNSLAM_SCRIPTS_DIR)\n";
  return "";
}

}  // namespace

std::vector<std::string> ReportArguments(const std::string& out_dir, const std::string& title,
                                         const std::string& gt_path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // Absolute paths and --title=: no argument can look like an option.
  std::vector<std::string> args = {fs::absolute(out_dir, ec).string(), "--title=" + title};
  if (!gt_path.empty()) args.push_back("--gt=" + fs::absolute(gt_path, ec).string());
  return args;
}

int RunPythonScript(const std::string& script, const std::vector<std::string>& args,
                    const std::string& what) {
  const std::string path = ScriptPath(script, "warning: no " + what + ": ");
  if (path.empty()) return -1;
  const int code = RunWithOutputOnStderr(PythonCommand(path, args));
  if (code == -1) {
    std::cerr << "warning: could not run /usr/bin/python3 " << path << ", so no " << what << "\n";
  }
  return code;
}

int RunPythonCommand(const std::string& script, const std::vector<std::string>& args) {
  const std::string path = ScriptPath(script, "error: ");
  if (path.empty()) return 1;
  std::error_code ec;
  const std::string self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  if (!ec) setenv("DYNSLAM_CLI", self.c_str(), 1);
  const std::vector<std::string> command = PythonCommand(path, args);
  std::vector<char*> argv = Argv(command);
  std::fflush(stdout);
  std::fflush(stderr);
  execv(argv[0], argv.data());
  std::cerr << "error: could not run /usr/bin/python3 " << path << ": " << std::strerror(errno)
            << "\n";
  return 1;
}

}  // namespace dynslam::cli
