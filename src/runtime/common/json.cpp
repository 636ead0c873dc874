#include "runtime/common/json.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace fuzzygait::common::json {
namespace {

constexpr int kMaxDepth = 64;

class Reader {
 public:
  Reader(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  Value document() {
    skip_space();
    Value v = value(0);
    skip_space();
    if (at_ < text_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument(source_ + ":" + std::to_string(line_) + ":" +
                                std::to_string(at_ - line_start_ + 1) + ": " + what);
  }
  bool done() const { return at_ >= text_.size(); }
  char peek() const { return done() ? '\0' : text_[at_]; }
  void skip_space() {
    while (!done()) {
      const char c = text_[at_];
      if (c == '\n') {
        ++line_;
        line_start_ = at_ + 1;
      } else if (c != ' ' && c != '\t' && c != '\r') {
        return;
      }
      ++at_;
    }
  }
  void expect(char c, const char* what) {
    if (peek() != c) fail(std::string("expected ") + what);
    ++at_;
  }
  void literal(std::string_view word) {
    if (text_.substr(at_, word.size()) != word) fail("expected a JSON value");
    at_ += word.size();
  }

  Value value(int depth) {
    if (depth > kMaxDepth) fail("values nested deeper than 64");
    Value v;
    v.line = line_;
    switch (peek()) {
      case '{':
        v.kind = Value::Kind::Object;
        members(v, depth);
        break;
      case '[':
        v.kind = Value::Kind::Array;
        elements(v, depth);
        break;
      case '"':
        v.kind = Value::Kind::String;
        v.string = string();
        break;
      case 't':
        literal("true");
        v.kind = Value::Kind::Boolean;
        v.boolean = true;
        break;
      case 'f':
        literal("false");
        v.kind = Value::Kind::Boolean;
        break;
      case 'n':
        literal("null");
        break;
      default:
        v.kind = Value::Kind::Number;
        v.number = number();
    }
    return v;
  }

  void members(Value& v, int depth) {
    ++at_;  // {
    skip_space();
    if (peek() == '}') {
      ++at_;
      return;
    }
    while (true) {
      skip_space();
      if (peek() != '"') fail("expected a member name in double quotes");
      const std::size_t key_at = at_;
      std::string key = string();
      if (v.find(key)) {
        at_ = key_at;
        fail("duplicate member '" + key + "'");
      }
      skip_space();
      expect(':', "':' after a member name");
      skip_space();
      Value member = value(depth + 1);
      v.object.emplace_back(std::move(key), std::move(member));
      skip_space();
      if (peek() == ',') {
        ++at_;
        continue;
      }
      expect('}', "',' or '}' after a member");
      return;
    }
  }

  void elements(Value& v, int depth) {
    ++at_;  // [
    skip_space();
    if (peek() == ']') {
      ++at_;
      return;
    }
    while (true) {
      skip_space();
      v.array.push_back(value(depth + 1));
      skip_space();
      if (peek() == ',') {
        ++at_;
        continue;
      }
      expect(']', "',' or ']' after an element");
      return;
    }
  }

  unsigned hex4() {
    unsigned code = 0;
    for (int i = 0; i < 4; ++i) {
      const char c = peek();
      unsigned digit;
      if (c >= '0' && c <= '9') {
        digit = static_cast<unsigned>(c - '0');
      } else if (c >= 'a' && c <= 'f') {
        digit = static_cast<unsigned>(c - 'a' + 10);
      } else if (c >= 'A' && c <= 'F') {
        digit = static_cast<unsigned>(c - 'A' + 10);
      } else {
        fail("expected four hexadecimal digits after \\u");
      }
      code = code * 16 + digit;
      ++at_;
    }
    return code;
  }

  static void append_utf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  std::string string() {
    ++at_;  // "
    std::string out;
    while (true) {
      if (done()) fail("the string is not closed");
      const char c = text_[at_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) {
        --at_;
        fail("a control character inside a string");
      }
      if (c != '\\') {
        out += c;
        continue;
      }
      const char e = peek();
      ++at_;
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          unsigned code = hex4();
          if (code >= 0xD800 && code < 0xDC00) {  // a surrogate pair
            if (peek() != '\\' || text_.substr(at_, 2) != "\\u") fail("a lone UTF-16 surrogate");
            at_ += 2;
            const unsigned low = hex4();
            if (low < 0xDC00 || low >= 0xE000) fail("a lone UTF-16 surrogate");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          } else if (code >= 0xDC00 && code < 0xE000) {
            fail("a lone UTF-16 surrogate");
          }
          append_utf8(out, code);
          break;
        }
        default:
          --at_;
          fail("an unknown escape in a string");
      }
    }
  }

  double number() {
    const std::size_t begin = at_;
    auto digits = [this] {
      const std::size_t from = at_;
      while (peek() >= '0' && peek() <= '9')
        ++at_;
      return at_ - from;
    };
    if (peek() == '-') ++at_;
    if (peek() == '0') {
      ++at_;
    } else if (digits() == 0) {
      at_ = begin;
      fail("expected a JSON value");
    }
    if (peek() == '.') {
      ++at_;
      if (digits() == 0) fail("expected digits after the decimal point");
    }
    if (peek() == 'e' || peek() == 'E') {
      ++at_;
      if (peek() == '+' || peek() == '-') ++at_;
      if (digits() == 0) fail("expected digits in the exponent");
    }
    double value = 0.0;
    const auto [end, error] = std::from_chars(text_.data() + begin, text_.data() + at_, value);
    if (error != std::errc() || end != text_.data() + at_ || !std::isfinite(value)) {
      const std::string written(text_.substr(begin, at_ - begin));
      at_ = begin;
      fail("the number " + written + " is beyond what a double holds");
    }
    return value;
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t at_ = 0;
  int line_ = 1;
  std::size_t line_start_ = 0;
};

}  // namespace

Value::Value() = default;

const Value* Value::find(std::string_view key) const {
  for (const auto& [name, value] : object) {
    if (name == key) return &value;
  }
  return nullptr;
}

const char* kind_name(Value::Kind kind) {
  switch (kind) {
    case Value::Kind::Null:
      return "null";
    case Value::Kind::Boolean:
      return "true or false";
    case Value::Kind::Number:
      return "a number";
    case Value::Kind::String:
      return "a string";
    case Value::Kind::Array:
      return "an array";
    case Value::Kind::Object:
      return "an object";
  }
  return "?";
}

Value parse(std::string_view text, const std::string& source) {
  return Reader(text, source).document();
}

}  // namespace fuzzygait::common::json
