// A small JSON value: enough to write summary.json / metrics.json (SPEC §4, §5) and to read the
// reference set's JSON files back. Objects keep insertion order so written files are stable.
// Numbers are written with %.17g (bit-exact round trip); non-finite numbers are written as null.
#ifndef DYNSLAM_JSON_H_
#define DYNSLAM_JSON_H_

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "dynslam/status.h"

namespace dynslam {

class Json {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };

  Json() = default;  // null
  Json(bool value) : type_(Type::kBool), bool_(value) {}                        // NOLINT
  Json(double value) : type_(Type::kNumber), number_(value) {}                  // NOLINT
  Json(int value) : Json(static_cast<double>(value)) {}                         // NOLINT
  Json(int64_t value) : Json(static_cast<double>(value)) {}                     // NOLINT
  Json(uint64_t value) : Json(static_cast<double>(value)) {}                    // NOLINT
  Json(const char* value) : type_(Type::kString), string_(value) {}             // NOLINT
  Json(std::string value) : type_(Type::kString), string_(std::move(value)) {}  // NOLINT
  static Json Object();
  static Json Array();

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::kNull; }
  bool is_number() const { return type_ == Type::kNumber; }
  bool is_object() const { return type_ == Type::kObject; }

  // Object: sets (or replaces) a member; returns *this for chaining.
  Json& Set(const std::string& key, Json value);
  // Array: appends.
  Json& Push(Json value);

  // Object member or nullptr.
  const Json* Find(const std::string& key) const;
  // Follows a path of object keys ("time_s", "total"); nullptr when any is missing.
  const Json* FindPath(std::initializer_list<const char*> path) const;

  double number() const { return number_; }
  bool boolean() const { return bool_; }
  const std::string& string() const { return string_; }
  const std::vector<Json>& items() const { return items_; }
  const std::vector<std::pair<std::string, Json>>& members() const { return members_; }

  // Pretty-printed with `indent` spaces per level; a trailing newline is not added.
  std::string Dump(int indent = 2) const;

  // Parses a whole document; errors name `name` and the line.
  static Expected<Json> Parse(const std::string& text, const std::string& name);
  static Expected<Json> ReadFile(const std::string& path);

 private:
  void DumpTo(std::string& out, int indent, int depth) const;

  Type type_ = Type::kNull;
  bool bool_ = false;
  double number_ = 0.0;
  std::string string_;
  std::vector<Json> items_;
  std::vector<std::pair<std::string, Json>> members_;
};

}  // namespace dynslam

#endif  // DYNSLAM_JSON_H_
