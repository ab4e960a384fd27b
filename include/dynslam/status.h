// Errors on user input are values, never aborts (docs/STYLE.md, SPEC §1.6).
//
// An `Error` names where the problem is (file and 1-based line when known) and says in one
// sentence what is wrong. `Expected<T>` holds either a value or an Error; `Status` is
// `Expected` with no value. The command line prints `Error::ToString()` and exits 2.
#ifndef DYNSLAM_STATUS_H_
#define DYNSLAM_STATUS_H_

#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace dynslam {

struct Error {
  std::string file;   // empty when the problem is not tied to a file
  int64_t line = 0;   // 1-based; 0 when not tied to a line
  std::string message;

  // "file:line: message", "file: message" or "message".
  std::string ToString() const {
    std::string where = file;
    if (!where.empty() && line > 0) where += ":" + std::to_string(line);
    return where.empty() ? message : where + ": " + message;
  }
};

template <typename T>
class Expected {
 public:
  Expected(T value) : state_(std::move(value)) {}        // NOLINT: implicit on purpose
  Expected(Error error) : state_(std::move(error)) {}    // NOLINT: implicit on purpose

  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }

  const T& value() const& { return std::get<T>(state_); }
  T& value() & { return std::get<T>(state_); }
  T&& value() && { return std::get<T>(std::move(state_)); }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

  const Error& error() const { return std::get<Error>(state_); }

 private:
  std::variant<T, Error> state_;
};

class Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit on purpose
  static Status Ok() { return Status(); }

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { return error_; }

 private:
  Error error_;
  bool ok_ = true;
};

}  // namespace dynslam

#endif  // DYNSLAM_STATUS_H_
