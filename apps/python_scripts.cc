// RunPythonScript (python_scripts.h).
#include "python_scripts.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
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
int RunWithOutputOnStderr(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
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


}  // namespace

void RunPythonScript(const std::string& script, const std::vector<std::string>& args,
                     const std::string& what) {
  namespace fs = std::filesystem;
  const char* from_environment = std::getenv("DYNSLAM_SCRIPTS_DIR");
  const fs::path path = fs::path(from_environment && *from_environment ? from_environment
                                                                       : DYNSLAM_SCRIPTS_DIR) /
                        script;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    std::cerr << "warning: no " << path.string() << " (DYNSLAM_SCRIPTS_DIR), so no " << what
              << "\n";
    return;
  }
  std::vector<std::string> command = {"/usr/bin/python3", path.string()};
  command.insert(command.end(), args.begin(), args.end());
  if (RunWithOutputOnStderr(command) == -1) {
    std::cerr << "warning: could not run /usr/bin/python3 " << path.string() << ", so no "
              << what << "\n";
  }
}

}  // namespace dynslam::cli
