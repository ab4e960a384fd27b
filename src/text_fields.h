// Reading the text files dynslam takes (graphs, ground truth, KITTI's label and pose files):
// a line's blank-separated fields and a field's number, parsed whole by std::from_chars (no
// locale, SPEC §1).
#ifndef DYNSLAM_SRC_TEXT_FIELDS_H_
#define DYNSLAM_SRC_TEXT_FIELDS_H_

#include <charconv>
#include <string_view>
#include <system_error>
#include <vector>

namespace dynslam {

// The part of `line` before its first '#' (the comments of graphs and ground truth).
inline std::string_view BeforeComment(std::string_view line) {
  const size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

// Replaces *fields with the fields of `line`, separated by spaces, tabs and carriage returns.
inline void SplitFields(std::string_view line, std::vector<std::string_view>* fields) {
  fields->clear();
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !blank(line[i])) ++i;
    if (i > start) fields->push_back(line.substr(start, i - start));
  }
}

// The whole of `text` as a number of type T, an optional leading '+' allowed; false when it is
// empty, has anything after the number or is out of T's range. Doubles may be inf or nan: the
// callers that need finite numbers check.
template <typename T>
bool ParseWholeNumber(std::string_view text, T* value) {
  if (!text.empty() && text[0] == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), *value);
  return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace dynslam

#endif  // DYNSLAM_SRC_TEXT_FIELDS_H_
