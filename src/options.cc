#include "dynslam/options.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "src/number_text.h"

namespace dynslam {

std::string SwitchText(bool on) { return on ? "on" : "off"; }

std::optional<std::string> ParseSwitch(const std::string& text, bool* on) {
  if (text == "on" || text == "true") {
    *on = true;
  } else if (text == "off" || text == "false") {
    *on = false;
  } else {
    return "'" + text + "' is not on or off";
  }
  return std::nullopt;
}

std::string RealText(double value) { return NumberText(value); }

std::optional<std::string> ParseInteger(const std::string& text, int64_t min, int64_t max,
                                        int64_t* value) {
  errno = 0;
  char* end = nullptr;
  const long long parsed = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || errno != 0 || end != text.c_str() + text.size() || parsed < min ||
      parsed > max) {
    return "'" + text + "' is not a whole number from " + std::to_string(min) + " to " +
           std::to_string(max);
  }
  *value = parsed;
  return std::nullopt;
}

// std::from_chars, not strtod: the C locale's decimal point, whatever the process's locale is.
std::optional<std::string> ParseReal(const std::string& text, double min, double max,
                                     double* value) {
  double parsed = 0;
  const char* end = text.data() + text.size();
  const std::from_chars_result result = std::from_chars(text.data(), end, parsed);
  if (text.empty() || result.ec != std::errc() || result.ptr != end || !std::isfinite(parsed) ||
      parsed < min || parsed > max) {
    return "'" + text + "' is not a number from " + RealText(min) + " to " + RealText(max);
  }
  *value = parsed;
  return std::nullopt;
}

std::string FlagName(const std::string& name) {
  std::string flag = name;
  for (char& c : flag) c = c == '_' ? '-' : c;
  return flag;
}

}  // namespace dynslam
