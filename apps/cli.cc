#include "cli.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace dynslam::cli {
namespace {

std::string FormatDouble(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", value);
  return buffer;
}

std::optional<int64_t> ParseInt(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return std::nullopt;
  return static_cast<int64_t>(value);
}

std::optional<double> ParseDouble(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

}  // namespace

bool ReportedProblem(const std::optional<std::string>& problem) {
  if (problem) std::cerr << "error: " << *problem << "\n";
  return problem.has_value();
}

ArgParser::ArgParser(std::string usage, std::string description)
    : usage_(std::move(usage)), description_(std::move(description)) {}

void ArgParser::AddFlag(const std::string& name, bool* target, const std::string& help) {
  options_.push_back({name, "", help, *target ? "on" : "off",
                      [target](const std::string&) -> std::optional<std::string> {
                        *target = true;
                        return std::nullopt;
                      }});
}

void ArgParser::AddString(const std::string& name, std::string* target, const std::string& help,
                          const std::string& metavar) {
  options_.push_back({name, metavar, help, target->empty() ? "none" : *target,
                      [target](const std::string& value) -> std::optional<std::string> {
                        *target = value;
                        return std::nullopt;
                      }});
}

void ArgParser::AddChoice(const std::string& name, std::string* target,
                          const std::vector<std::string>& choices, const std::string& help) {
  std::string metavar;
  for (const std::string& choice : choices) metavar += (metavar.empty() ? "" : "|") + choice;
  options_.push_back({name, metavar, help, *target,
                      [target, choices, metavar](const std::string& value)
                          -> std::optional<std::string> {
                        for (const std::string& choice : choices) {
                          if (value == choice) {
                            *target = value;
                            return std::nullopt;
                          }
                        }
                        return "'" + value + "' is not one of " + metavar;
                      }});
}

void ArgParser::AddInt(const std::string& name, int64_t* target, const std::string& help,
                       int64_t min_value, int64_t max_value) {
  options_.push_back({name, "N", help, std::to_string(*target),
                      [=](const std::string& value) -> std::optional<std::string> {
                        const std::optional<int64_t> parsed = ParseInt(value);
                        if (!parsed || *parsed < min_value || *parsed > max_value) {
                          return "'" + value + "' is not a whole number from " +
                                 std::to_string(min_value) + " to " + std::to_string(max_value);
                        }
                        *target = *parsed;
                        return std::nullopt;
                      }});
}

void ArgParser::AddDouble(const std::string& name, double* target, const std::string& help,
                          double min_value, double max_value) {
  options_.push_back({name, "X", help, FormatDouble(*target),
                      [=](const std::string& value) -> std::optional<std::string> {
                        const std::optional<double> parsed = ParseDouble(value);
                        if (!parsed || *parsed < min_value || *parsed > max_value) {
                          return "'" + value + "' is not a number from " +
                                 FormatDouble(min_value) + " to " + FormatDouble(max_value);
                        }
                        *target = *parsed;
                        return std::nullopt;
                      }});
}

void ArgParser::AddPositional(const std::string& name, std::string* target,
                              const std::string& help, bool required) {
  positionals_.push_back({name, target, help, required});
}

ArgParser::Option* ArgParser::FindOption(const std::string& name) {
  for (Option& option : options_) {
    if (option.name == name) return &option;
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
      if (!option->metavar.empty()) {
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
  out << "\noptions:\n";
  for (const Option& option : options_) {
    out << "  --" << option.name;
    if (!option.metavar.empty()) out << " " << option.metavar;
    out << "\n      " << option.help << " (default: " << option.default_text << ")\n";
  }
  out << "  --help\n      print this help and exit\n";
  return out.str();
}

}  // namespace dynslam::cli
