#include "arg_parser.h"

#include <algorithm>
#include <iostream>
#include <sstream>

namespace dynslam::cli {
namespace {

// `text` in lines of at most `width` characters (longer words stay whole), each indented.
std::string Wrapped(const std::string& text, size_t indent, size_t width) {
  std::istringstream words(text);
  std::string out, line, word;
  while (words >> word) {
    if (!line.empty() && indent + line.size() + 1 + word.size() > width) {
      out += std::string(indent, ' ') + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty()) out += std::string(indent, ' ') + line + "\n";
  return out;
}

}  // namespace

bool ReportedProblem(const std::optional<std::string>& problem) {
  if (problem) ErrorExit(*problem, kExitBadInput);
  return problem.has_value();
}

int ErrorExit(const Error& error, int exit_code) { return ErrorExit(error.ToString(), exit_code); }

int ErrorExit(const std::string& message, int exit_code) {
  std::cerr << "error: " << message << "\n";
  return exit_code;
}

ArgParser::ArgParser(std::string usage, std::string description)
    : usage_(std::move(usage)), description_(std::move(description)) {}

ArgParser::Option& ArgParser::Add(const std::string& name, const std::string& metavar,
                                  const std::string& help, const std::string& default_text,
                                  Setter set) {
  Option option;
  option.name = name;
  option.metavar = metavar;
  option.help = help;
  option.default_text = default_text;
  option.set = std::move(set);
  option.group = group_;
  options_.push_back(std::move(option));
  return options_.back();
}

void ArgParser::AddFlag(const std::string& name, bool* target, const std::string& help) {
  Add(name, "", help, *target ? "on" : "off", [target](const std::string&) {
    *target = true;
    return std::optional<std::string>();
  });
}

void ArgParser::AddValue(const std::string& name, const std::string& metavar,
                         const std::string& help, const std::string& default_text, Setter set) {
  Add(name, metavar, help, default_text, std::move(set));
}

void ArgParser::AddSwitch(const std::string& name, const std::string& help,
                          const std::string& default_text, Setter set) {
  Add(name, "[on|off]", help, default_text, std::move(set)).value_optional = true;
}

void ArgParser::AddAlias(const std::string& name, const std::string& alias) {
  if (Option* option = FindOption(name)) option->aliases.push_back(alias);
}

void ArgParser::AddString(const std::string& name, std::string* target, const std::string& help,
                          const std::string& metavar) {
  AddValue(name, metavar, help, target->empty() ? "none" : *target, [target](const std::string& value) {
    *target = value;
    return std::optional<std::string>();
  });
}

void ArgParser::AddChoice(const std::string& name, std::string* target,
                          const std::vector<std::string>& choices, const std::string& help) {
  std::string metavar;
  for (const std::string& choice : choices) metavar += (metavar.empty() ? "" : "|") + choice;
  AddValue(name, metavar, help, *target,
           [target, choices, metavar](const std::string& value) -> std::optional<std::string> {
             for (const std::string& choice : choices) {
               if (value == choice) {
                 *target = value;
                 return std::nullopt;
               }
             }
             return "'" + value + "' is not one of " + metavar;
           });
}

void ArgParser::AddDouble(const std::string& name, double* target, const std::string& help,
                          double min_value, double max_value) {
  AddValue(name, "X", help, RealText(*target), [=](const std::string& value) {
    return ParseReal(value, min_value, max_value, target);
  });
}

void ArgParser::AddPositional(const std::string& name, std::string* target,
                              const std::string& help, bool required) {
  positionals_.push_back({name, target, help, required});
}

ArgParser::Option* ArgParser::FindOption(const std::string& name) {
  for (Option& option : options_) {
    if (option.name == name) return &option;
    for (const std::string& alias : option.aliases) {
      if (alias == name) return &option;
    }
  }
  return nullptr;
}

bool ArgParser::Given(const std::string& name) const {
  for (const Option& option : options_) {
    if (option.name == name) return option.given;
  }
  return false;
}

std::optional<int> ArgParser::Parse(int argc, char** argv, int first) {
  auto usage_error = [this](const std::string& message) {
    std::cerr << "error: " << message << "\nusage: " << usage_
              << "\n(see --help for every option)\n";
    return std::optional<int>(kExitBadInput);
  };
  size_t next_positional = 0;
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << Help();
      return kExitOk;
    }
    if (arg.size() > 2 && arg.compare(0, 2, "--") == 0) {
      std::string name = arg.substr(2);
      std::optional<std::string> inline_value;
      if (const size_t eq = name.find('='); eq != std::string::npos) {
        inline_value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      Option* option = FindOption(name);
      if (option == nullptr) return usage_error("unknown option --" + name);
      std::string value;
      if (option->value_optional) {
        const auto is_switch_value = [](const std::string& text) {
          return text == "on" || text == "off" || text == "true" || text == "false";
        };
        value = inline_value ? *inline_value : "on";
        if (!inline_value && i + 1 < argc && is_switch_value(argv[i + 1])) value = argv[++i];
      } else if (!option->metavar.empty()) {
        if (inline_value) {
          value = *inline_value;
        } else if (i + 1 < argc) {
          value = argv[++i];
        } else {
          return usage_error("--" + name + " needs a value (" + option->metavar + ")");
        }
      } else if (inline_value) {
        return usage_error("--" + name + " takes no value");
      }
      if (std::optional<std::string> problem = option->set(value)) {
        return usage_error("--" + name + ": " + *problem);
      }
      option->given = true;
      continue;
    }
    if (next_positional >= positionals_.size()) {
      return usage_error("unexpected argument '" + arg + "'");
    }
    *positionals_[next_positional++].target = arg;
  }
  for (size_t i = next_positional; i < positionals_.size(); ++i) {
    if (positionals_[i].required) return usage_error("missing " + positionals_[i].name);
  }
  return std::nullopt;
}

std::string ArgParser::Help() const {
  std::ostringstream out;
  out << "usage: " << usage_ << "\n\n" << description_ << "\n";
  if (!positionals_.empty()) {
    out << "\narguments:\n";
    for (const Positional& positional : positionals_) {
      out << "  " << positional.name << "\n      " << positional.help << "\n";
    }
  }
  std::vector<std::string> groups;
  for (const Option& option : options_) {
    if (std::find(groups.begin(), groups.end(), option.group) == groups.end()) {
      groups.push_back(option.group);
    }
  }
  for (const std::string& group : groups) {
    out << "\n" << group << ":\n";
    for (const Option& option : options_) {
      if (option.group != group) continue;
      out << "  --" << option.name;
      if (!option.metavar.empty()) out << " " << option.metavar;
      const std::string shown = option.default_text.empty() ? "none" : option.default_text;
      out << "\n" << Wrapped(option.help + " (default: " + shown + ")", 6, 80);
    }
  }
  out << "\n";
  out << "  --help\n      print this help and exit\n";
  if (!examples_.empty()) {
    out << "\nexamples:\n";
    for (const std::string& example : examples_) out << "  " << example << "\n";
  }
  return out.str();
}

}  // namespace dynslam::cli
