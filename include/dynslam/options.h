// Options declared once. Each solver, build and simulation option is one entry of an option
// table (SolverOptionTable in solver_options.h, BuildOptionTable in formulation.h,
// SimulateOptionTable in simulate.h): its name, what it
// does, the values it takes, and how to read and write it as text. The command-line flags and
// their --help, the Python keyword arguments and their docstrings, summary.json's "solver" block
// and docs/OPTIONS.md are all made from the tables, so an option has one spelling everywhere:
// `remaining_chi2` in Python and JSON is the flag --remaining-chi2.
#ifndef DYNSLAM_OPTIONS_H_
#define DYNSLAM_OPTIONS_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dynslam {

enum class OptionType {
  kSwitch,   // on or off (Python: bool; JSON: true or false)
  kInteger,  // within [min, max]
  kReal,     // finite, within [min, max]
  kChoice,   // one of `values`
  kText,     // parsed by the option itself (metavar shows the form)
  kPreset,   // one of `values`, each setting the options named in `sets` (not a value of its own)
};

template <typename Options>
struct Option {
  std::string name;   // snake_case; the flag is --name with '-' for '_'
  std::string group;  // the section of --help and docs/OPTIONS.md
  OptionType type = OptionType::kText;
  std::string help;
  std::vector<std::string> values;  // kChoice, kPreset: the values; kSwitch: on, off
  std::string metavar;              // how the value is shown: N, X, a|b, KIND=TYPE:K,...
  std::vector<std::string> aliases;  // earlier spellings, still accepted
  std::vector<std::string> sets;     // kPreset: the options its values set
  // The value as text (numbers in their shortest exact form), and the text turned into the
  // value: nullopt, or what is wrong with the text.
  std::function<std::string(const Options&)> get;
  std::function<std::optional<std::string>(const std::string& text, Options*)> set;
};

template <typename Options>
using OptionTable = std::vector<Option<Options>>;

// An option without its accessors (get and set): what the helpers below start from, and what an
// option of its own kind (kText, kPreset) starts from before it sets them.
template <typename Options>
Option<Options> Declare(std::string name, std::string group, OptionType type, std::string help,
                        std::string metavar) {
  Option<Options> o;
  o.name = std::move(name);
  o.group = std::move(group);
  o.type = type;
  o.help = std::move(help);
  o.metavar = std::move(metavar);
  return o;
}

// The text forms every table shares.
std::string SwitchText(bool on);                                     // "on", "off"
std::optional<std::string> ParseSwitch(const std::string& text, bool* on);  // on/off/true/false
std::string RealText(double value);                                  // shortest exact
std::optional<std::string> ParseInteger(const std::string& text, int64_t min, int64_t max,
                                        int64_t* value);
std::optional<std::string> ParseReal(const std::string& text, double min, double max,
                                     double* value);
// "remaining_chi2" → "remaining-chi2".
std::string FlagName(const std::string& name);

template <typename Options>
Option<Options> Switch(std::string name, std::string group, bool Options::*member,
                       std::string help) {
  Option<Options> o = Declare<Options>(std::move(name), std::move(group), OptionType::kSwitch,
                                       std::move(help), "on|off");
  o.values = {"on", "off"};
  o.get = [member](const Options& options) { return SwitchText(options.*member); };
  o.set = [member](const std::string& text, Options* options) {
    return ParseSwitch(text, &(options->*member));
  };
  return o;
}

template <typename Options, typename Int>
Option<Options> Integer(std::string name, std::string group, Int Options::*member,
                        std::string help, int64_t min, int64_t max) {
  Option<Options> o = Declare<Options>(std::move(name), std::move(group), OptionType::kInteger,
                                       std::move(help), "N");
  o.get = [member](const Options& options) { return std::to_string(options.*member); };
  o.set = [member, min, max](const std::string& text, Options* options) {
    int64_t value = 0;
    std::optional<std::string> problem = ParseInteger(text, min, max, &value);
    if (!problem) options->*member = static_cast<Int>(value);
    return problem;
  };
  return o;
}

template <typename Options>
Option<Options> Real(std::string name, std::string group, double Options::*member,
                     std::string help, double min, double max) {
  Option<Options> o = Declare<Options>(std::move(name), std::move(group), OptionType::kReal,
                                       std::move(help), "X");
  o.get = [member](const Options& options) { return RealText(options.*member); };
  o.set = [member, min, max](const std::string& text, Options* options) {
    return ParseReal(text, min, max, &(options->*member));
  };
  return o;
}

// An enum spelled by `name_of` (e.g. Name(MinimizerType)); `values` in the order --help shows.
template <typename Options, typename Enum>
Option<Options> Choice(std::string name, std::string group, Enum Options::*member,
                       std::vector<Enum> values, const char* (*name_of)(Enum), std::string help) {
  Option<Options> o = Declare<Options>(std::move(name), std::move(group), OptionType::kChoice,
                                       std::move(help), "");
  for (const Enum value : values) {
    o.values.push_back(name_of(value));
    o.metavar += (o.metavar.empty() ? "" : "|") + o.values.back();
  }
  o.get = [member, name_of](const Options& options) { return std::string(name_of(options.*member)); };
  o.set = [member, values, name_of, metavar = o.metavar](const std::string& text,
                                                         Options* options)
      -> std::optional<std::string> {
    for (const Enum value : values) {
      if (text == name_of(value)) {
        options->*member = value;
        return std::nullopt;
      }
    }
    return "'" + text + "' is not one of " + metavar;
  };
  return o;
}

// `option` that also answers to the earlier spellings `aliases`.
template <typename Options>
Option<Options> Aliased(std::vector<std::string> aliases, Option<Options> option) {
  option.aliases = std::move(aliases);
  return option;
}

// Applies `given` (name or alias → text, in order) to `*options` over their current values:
// presets first, then the rest. Each problem names the option as `spell` writes a name (the
// command line: --flag-name; Python: the keyword). A preset's value may not be contradicted by an
// option given beside it ("--tolerances tight turns --remaining-chi2 off; give one of them").
template <typename Options>
std::optional<std::string> ApplyOptions(
    const OptionTable<Options>& table, const std::vector<std::pair<std::string, std::string>>& given,
    const std::function<std::string(const std::string&)>& spell, Options* options);

// The option named `name` (or one of its aliases, '-' and '_' alike), or null.
template <typename Options>
const Option<Options>* FindOption(const OptionTable<Options>& table, const std::string& name) {
  std::string key = name;
  for (char& c : key) c = c == '-' ? '_' : c;
  for (const Option<Options>& option : table) {
    if (option.name == key) return &option;
    for (const std::string& alias : option.aliases) {
      if (alias == key) return &option;
    }
  }
  return nullptr;
}

template <typename Options>
std::optional<std::string> ApplyOptions(
    const OptionTable<Options>& table, const std::vector<std::pair<std::string, std::string>>& given,
    const std::function<std::string(const std::string&)>& spell, Options* options) {
  std::vector<std::pair<const Option<Options>*, std::string>> presets, others;
  for (const auto& [name, text] : given) {
    const Option<Options>* option = FindOption(table, name);
    if (option == nullptr) return "unknown option " + spell(name);
    (option->type == OptionType::kPreset ? presets : others).emplace_back(option, text);
  }
  for (const auto& group : {presets, others}) {
    for (const auto& [option, text] : group) {
      if (std::optional<std::string> problem = option->set(text, options)) {
        return spell(option->name) + ": " + *problem;
      }
    }
  }
  for (const auto& [preset, text] : presets) {  // does an option given beside it undo it?
    Options redone = *options;
    preset->set(text, &redone);
    for (const std::string& name : preset->sets) {
      const Option<Options>* set = FindOption(table, name);
      if (set->get(redone) != set->get(*options)) {
        return spell(preset->name) + " " + text + " sets " + spell(name) + " " + set->get(redone) +
               "; give one of them";
      }
    }
  }
  return std::nullopt;
}

// The table as Markdown, one section per group (docs/OPTIONS.md): name (Python keyword, JSON
// key), flag, values, default, what it does.
template <typename Options>
std::string OptionsMarkdown(const OptionTable<Options>& table) {
  const Options defaults;
  std::vector<std::string> groups;
  for (const Option<Options>& option : table) {
    bool seen = false;
    for (const std::string& group : groups) seen = seen || group == option.group;
    if (!seen) groups.push_back(option.group);
  }
  std::string md;
  for (const std::string& group : groups) {
    md += "\n### " + group + "\n\n| option | flag | values | default | what it does |\n"
          "|---|---|---|---|---|\n";
    for (const Option<Options>& option : table) {
      if (option.group != group) continue;
      std::string values = option.metavar;
      for (char& c : values) c = c == '|' ? '/' : c;  // a Markdown cell
      std::string help = option.help;
      if (!option.aliases.empty()) {
        help += " (earlier spelling:";
        for (const std::string& alias : option.aliases) help += " `" + alias + "`";
        help += ")";
      }
      const std::string shown = option.get(defaults);
      md += "| `" + option.name + "` | `--" + FlagName(option.name) + "` | " + values + " | " +
            (shown.empty() ? "none" : "`" + shown + "`") + " | " + help + " |\n";
    }
  }
  return md;
}

}  // namespace dynslam

#endif  // DYNSLAM_OPTIONS_H_
