// One entry point per subcommand; each lives in <name>_command.cc.
#ifndef DYNSLAM_APPS_COMMANDS_H_
#define DYNSLAM_APPS_COMMANDS_H_

namespace dynslam::cli {

int RunBench(int argc, char** argv);
int RunBuild(int argc, char** argv);
int RunCompare(int argc, char** argv);
int RunMetrics(int argc, char** argv);
int RunOptions(int argc, char** argv);
int RunSimulate(int argc, char** argv);
int RunSolve(int argc, char** argv);
int RunVerify(int argc, char** argv);

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_COMMANDS_H_
