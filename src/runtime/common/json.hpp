// A strict JSON reader for the runtime's small files (a controller set's manifest): RFC 8259
// values, each remembering its line, and errors that name the file, line and column. The runtime
// needs the C++ standard library only, so it does not use nlohmann-json as the tools do. Internal
// to fuzzygait (not installed).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fuzzygait::common::json {

struct Value {
  // Defined in json.cpp: defined here, clang (14, with libstdc++ 12) instantiates the members'
  // destructors while std::pair<std::string, Value> below is still incomplete, and fails.
  Value();

  enum class Kind { Null, Boolean, Number, String, Array, Object };
  Kind kind = Kind::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Value> array;
  std::vector<std::pair<std::string, Value>> object;  // in the file's order, keys unique
  int line = 0;                                       // where the value begins, from 1

  // The member named `key` of an object (null when absent or not an object).
  const Value* find(std::string_view key) const;
};

const char* kind_name(Value::Kind kind);  // "a string", "a number", ...

// Parses one JSON text. Throws std::invalid_argument "SOURCE:LINE:COLUMN: what was expected"
// for anything that is not JSON (a trailing comma, a comment, text after the value), a duplicate
// key, a number a double cannot hold (1e400, 1e-400), and nesting deeper than 64.
Value parse(std::string_view text, const std::string& source);

}  // namespace fuzzygait::common::json
