// Command-line plumbing shared by the subcommands: option parsing with --help generated from
// the declared options and their defaults, and the exit codes of docs/STYLE.md.
#ifndef DYNSLAM_APPS_CLI_H_
#define DYNSLAM_APPS_CLI_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace dynslam::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailed = 1;    // the solve (or other work) failed
inline constexpr int kExitBadInput = 2;  // bad usage or bad input

// Prints "error: PROBLEM" to stderr when a flag group's Finish() found one, and says whether it
// did: `if (ReportedProblem(flags.Finish())) return kExitBadInput;`.
bool ReportedProblem(const std::optional<std::string>& problem);

// Declares options and positionals, parses argv and writes --help. Every option is spelled
// out (`--linear-solver NAME`); `--name=value` is accepted too. A default is the value the
// target holds when the option is declared.
class ArgParser {
 public:
  ArgParser(std::string usage, std::string description);

  void AddFlag(const std::string& name, bool* target, const std::string& help);
  void AddString(const std::string& name, std::string* target, const std::string& help,
                 const std::string& metavar = "VALUE");
  void AddChoice(const std::string& name, std::string* target,
                 const std::vector<std::string>& choices, const std::string& help);
  void AddInt(const std::string& name, int64_t* target, const std::string& help,
              int64_t min_value, int64_t max_value);
  void AddDouble(const std::string& name, double* target, const std::string& help,
                 double min_value, double max_value);
  // Positionals in declaration order; optional ones must come last.
  void AddPositional(const std::string& name, std::string* target, const std::string& help,
                     bool required = true);

  // Parses argv[first..argc). Returns std::nullopt when the command should go on, otherwise
  // the exit code to return at once: kExitOk after --help, kExitBadInput after a usage error
  // (the message and a pointer to --help are printed to stderr).
  std::optional<int> Parse(int argc, char** argv, int first);

  // True when the option was given on the command line (not just left at its default).
  bool Given(const std::string& name) const;

  std::string Help() const;

 private:
  struct Option {
    std::string name;
    std::string metavar;  // empty for a flag
    std::string help;
    std::string default_text;
    std::function<std::optional<std::string>(const std::string&)> set;  // error or nullopt
    bool given = false;
  };
  struct Positional {
    std::string name;
    std::string* target;
    std::string help;
    bool required;
  };

  Option* FindOption(const std::string& name);

  std::string usage_;
  std::string description_;
  std::vector<Option> options_;
  std::vector<Positional> positionals_;
};

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_CLI_H_
