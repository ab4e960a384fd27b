// Command-line plumbing of dynslam's executables (the `dynslam` command's subcommands, the
// benchmark tools): option parsing with --help generated from the declared options and their
// defaults, an option table's options as flags, and the exit codes of docs/STYLE.md.
#ifndef DYNSLAM_CLI_ARG_PARSER_H_
#define DYNSLAM_CLI_ARG_PARSER_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dynslam/options.h"
#include "dynslam/status.h"

namespace dynslam::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailed = 1;    // the solve (or other work) failed
inline constexpr int kExitBadInput = 2;  // bad usage or bad input

// Prints "error: PROBLEM" to stderr when a flag group's Finish() found one, and says whether it
// did: `if (ReportedProblem(flags.Finish())) return kExitBadInput;`.
bool ReportedProblem(const std::optional<std::string>& problem);

// Prints "error: " and the error to stderr and returns `exit_code`:
// `if (!graph.ok()) return ErrorExit(graph.error(), kExitBadInput);`.
int ErrorExit(const Error& error, int exit_code);
int ErrorExit(const std::string& message, int exit_code);

// Declares options and positionals, parses argv and writes --help. Every option is spelled
// out (`--linear-solver NAME`); `--name=value` is accepted too. A default is the value the
// target holds when the option is declared.
class ArgParser {
 public:
  // Takes an option's text: nullopt, or what is wrong with it.
  using Setter = std::function<std::optional<std::string>(const std::string&)>;

  ArgParser(std::string usage, std::string description);

  void AddFlag(const std::string& name, bool* target, const std::string& help);
  // An option with a value shown as `metavar`; `set` checks and takes it (error or nullopt).
  void AddValue(const std::string& name, const std::string& metavar, const std::string& help,
                const std::string& default_text, Setter set);
  void AddString(const std::string& name, std::string* target, const std::string& help,
                 const std::string& metavar = "VALUE");
  void AddChoice(const std::string& name, std::string* target,
                 const std::vector<std::string>& choices, const std::string& help);
  void AddDouble(const std::string& name, double* target, const std::string& help,
                 double min_value, double max_value);
  // An option whose value is optional (a switch: --name alone means on; --name on|off too).
  void AddSwitch(const std::string& name, const std::string& help, const std::string& default_text,
                 Setter set);
  // The --help section of the options declared after this call (until the next).
  void Group(std::string name) { group_ = std::move(name); }
  // A command line shown under "examples:" at the end of --help.
  void AddExample(std::string example) { examples_.push_back(std::move(example)); }
  // Another spelling of the option `name` (declared before).
  void AddAlias(const std::string& name, const std::string& alias);
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
    Setter set;
    std::string group;
    bool value_optional = false;  // a switch
    std::vector<std::string> aliases;
    bool given = false;
  };
  struct Positional {
    std::string name;
    std::string* target;
    std::string help;
    bool required;
  };

  Option* FindOption(const std::string& name);

  Option& Add(const std::string& name, const std::string& metavar, const std::string& help,
              const std::string& default_text, Setter set);

  std::string usage_;
  std::string description_;
  std::string group_ = "options";
  std::vector<std::string> examples_;
  std::vector<Option> options_;
  std::vector<Positional> positionals_;
};

// The options of an option table (options.h) as flags: --name with '-' for '_', its aliases
// too, under its group in --help, each value checked as it is parsed. Finish applies them.
template <typename Options>
class TableFlags {
 public:
  // `defaults` are the values the flags start from and --help shows.
  TableFlags(ArgParser* parser, const OptionTable<Options>& table, Options defaults = {})
      : table_(table), defaults_(std::move(defaults)) {
    for (const Option<Options>& option : table_) {
      parser->Group(option.group);
      auto set = [this, &option](const std::string& text) {
        Options scratch = defaults_;
        std::optional<std::string> problem = option.set(text, &scratch);
        if (!problem) given_.emplace_back(option.name, text);
        return problem;
      };
      const std::string flag = FlagName(option.name);
      if (option.type == OptionType::kSwitch) {
        parser->AddSwitch(flag, option.help, option.get(defaults_), set);
      } else {
        parser->AddValue(flag, option.metavar, option.help, option.get(defaults_), set);
      }
      for (const std::string& alias : option.aliases) parser->AddAlias(flag, FlagName(alias));
    }
  }

  // After a successful Parse: the defaults with the flags given applied, or a usage problem.
  std::optional<std::string> Finish(Options* options) const {
    *options = defaults_;
    return ApplyOptions(table_, given_, [](const std::string& name) { return "--" + FlagName(name); },
                        options);
  }

 private:
  const OptionTable<Options>& table_;
  Options defaults_;
  std::vector<std::pair<std::string, std::string>> given_;
};

}  // namespace dynslam::cli

#endif  // DYNSLAM_CLI_ARG_PARSER_H_
