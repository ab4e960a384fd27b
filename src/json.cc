#include "dynslam/json.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace dynslam {
namespace {

void AppendEscaped(std::string& out, const std::string& text) {
  out += '"';
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out += buffer;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

class Parser {
 public:
  Parser(const std::string& text, const std::string& name) : text_(text), name_(name) {}

  Expected<Json> ParseDocument() {
    Json value;
    if (!ParseValue(value, 0)) return error_;
    SkipSpace();
    if (pos_ != text_.size()) return Fail("unexpected text after the JSON value");
    return value;
  }

 private:
  static constexpr int kMaxDepth = 200;

  Error Fail(const std::string& message) {
    int64_t line = 1;
    for (size_t i = 0; i < pos_ && i < text_.size(); ++i) line += text_[i] == '\n';
    error_ = Error{name_, line, message};
    return error_;
  }

  void SkipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n' ||
                                   text_[pos_] == '\t' || text_[pos_] == '\r')) {
      ++pos_;
    }
  }

  bool Consume(const char* word) {
    const size_t n = std::char_traits<char>::length(word);
    if (text_.compare(pos_, n, word) != 0) return false;
    pos_ += n;
    return true;
  }

  bool ParseString(std::string& out) {
    ++pos_;  // opening quote
    while (pos_ < text_.size() && text_[pos_] != '"') {
      char c = text_[pos_++];
      if (c == '\\') {
        if (pos_ >= text_.size()) break;
        const char e = text_[pos_++];
        switch (e) {
          case 'n': c = '\n'; break;
          case 't': c = '\t'; break;
          case 'r': c = '\r'; break;
          case 'b': c = '\b'; break;
          case 'f': c = '\f'; break;
          case 'u':
            // Only ASCII escapes are produced by our writer; others become '?'.
            if (pos_ + 4 > text_.size()) return Fail("truncated \\u escape"), false;
            c = static_cast<char>(std::strtol(text_.substr(pos_, 4).c_str(), nullptr, 16));
            if (static_cast<unsigned char>(c) >= 0x80) c = '?';
            pos_ += 4;
            break;
          default: c = e;
        }
      }
      out += c;
    }
    if (pos_ >= text_.size()) return Fail("unterminated string"), false;
    ++pos_;  // closing quote
    return true;
  }

  bool ParseValue(Json& out, int depth) {
    if (depth > kMaxDepth) return Fail("nesting too deep"), false;
    SkipSpace();
    if (pos_ >= text_.size()) return Fail("unexpected end of input"), false;
    const char c = text_[pos_];
    if (c == '{') {
      ++pos_;
      out = Json::Object();
      SkipSpace();
      if (pos_ < text_.size() && text_[pos_] == '}') return ++pos_, true;
      while (true) {
        SkipSpace();
        if (pos_ >= text_.size() || text_[pos_] != '"') return Fail("expected a key"), false;
        std::string key;
        if (!ParseString(key)) return false;
        SkipSpace();
        if (pos_ >= text_.size() || text_[pos_] != ':') return Fail("expected ':'"), false;
        ++pos_;
        Json value;
        if (!ParseValue(value, depth + 1)) return false;
        out.Set(key, std::move(value));
        SkipSpace();
        if (pos_ < text_.size() && text_[pos_] == ',') { ++pos_; continue; }
        if (pos_ < text_.size() && text_[pos_] == '}') return ++pos_, true;
        return Fail("expected ',' or '}'"), false;
      }
    }
    if (c == '[') {
      ++pos_;
      out = Json::Array();
      SkipSpace();
      if (pos_ < text_.size() && text_[pos_] == ']') return ++pos_, true;
      while (true) {
        Json value;
        if (!ParseValue(value, depth + 1)) return false;
        out.Push(std::move(value));
        SkipSpace();
        if (pos_ < text_.size() && text_[pos_] == ',') { ++pos_; continue; }
        if (pos_ < text_.size() && text_[pos_] == ']') return ++pos_, true;
        return Fail("expected ',' or ']'"), false;
      }
    }
    if (c == '"') {
      std::string value;
      if (!ParseString(value)) return false;
      out = Json(std::move(value));
      return true;
    }
    if (Consume("true")) return out = Json(true), true;
    if (Consume("false")) return out = Json(false), true;
    if (Consume("null")) return out = Json(), true;
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    const double number = std::strtod(begin, &end);
    if (end == begin) return Fail("expected a value"), false;
    pos_ += static_cast<size_t>(end - begin);
    out = Json(number);
    return true;
  }

  const std::string& text_;
  const std::string& name_;
  size_t pos_ = 0;
  Error error_;
};

}  // namespace

Json Json::Object() {
  Json json;
  json.type_ = Type::kObject;
  return json;
}

Json Json::Array() {
  Json json;
  json.type_ = Type::kArray;
  return json;
}

Json& Json::Set(const std::string& key, Json value) {
  for (auto& member : members_) {
    if (member.first == key) {
      member.second = std::move(value);
      return *this;
    }
  }
  members_.emplace_back(key, std::move(value));
  return *this;
}

Json& Json::Push(Json value) {
  items_.push_back(std::move(value));
  return *this;
}

const Json* Json::Find(const std::string& key) const {
  for (const auto& member : members_) {
    if (member.first == key) return &member.second;
  }
  return nullptr;
}

const Json* Json::FindPath(std::initializer_list<const char*> path) const {
  const Json* node = this;
  for (const char* key : path) {
    node = node->Find(key);
    if (node == nullptr) return nullptr;
  }
  return node;
}

std::string Json::Dump(int indent) const {
  std::string out;
  DumpTo(out, indent, 0);
  return out;
}

void Json::DumpTo(std::string& out, int indent, int depth) const {
  const std::string pad(static_cast<size_t>(indent * (depth + 1)), ' ');
  const std::string close_pad(static_cast<size_t>(indent * depth), ' ');
  switch (type_) {
    case Type::kNull: out += "null"; return;
    case Type::kBool: out += bool_ ? "true" : "false"; return;
    case Type::kNumber: {
      if (!std::isfinite(number_)) {
        out += "null";
        return;
      }
      char buffer[32];
      if (number_ == std::floor(number_) && std::fabs(number_) < 1e15) {
        std::snprintf(buffer, sizeof(buffer), "%.0f", number_);
      } else {
        std::snprintf(buffer, sizeof(buffer), "%.17g", number_);
      }
      out += buffer;
      return;
    }
    case Type::kString: AppendEscaped(out, string_); return;
    case Type::kArray: {
      if (items_.empty()) { out += "[]"; return; }
      out += "[\n";
      for (size_t i = 0; i < items_.size(); ++i) {
        out += pad;
        items_[i].DumpTo(out, indent, depth + 1);
        out += i + 1 < items_.size() ? ",\n" : "\n";
      }
      out += close_pad + "]";
      return;
    }
    case Type::kObject: {
      if (members_.empty()) { out += "{}"; return; }
      out += "{\n";
      for (size_t i = 0; i < members_.size(); ++i) {
        out += pad;
        AppendEscaped(out, members_[i].first);
        out += ": ";
        members_[i].second.DumpTo(out, indent, depth + 1);
        out += i + 1 < members_.size() ? ",\n" : "\n";
      }
      out += close_pad + "}";
      return;
    }
  }
}

Expected<Json> Json::Parse(const std::string& text, const std::string& name) {
  return Parser(text, name).ParseDocument();
}

Expected<Json> Json::ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, 0, "cannot open the file"};
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return Parse(buffer.str(), path);
}

}  // namespace dynslam
