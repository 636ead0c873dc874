// A small XML well-formedness checker for the tests: one root element, tags nested and closed,
// names and attributes well formed, no duplicate attributes, quoted values, known entities,
// valid UTF-8. Returns an empty string when the text is well formed, else the first problem.
#pragma once

#include <cstddef>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace fuzzygait::test {

inline std::string check_xml(std::string_view xml) {
  std::size_t i = 0;
  const auto at = [&](std::string_view what) {
    return std::string(what) + " at byte " + std::to_string(i);
  };
  // UTF-8 first: every later step may then go byte by byte.
  for (std::size_t k = 0; k < xml.size();) {
    const auto lead = static_cast<unsigned char>(xml[k]);
    const std::size_t length = lead < 0x80         ? 1
                               : (lead >> 5) == 6  ? 2
                               : (lead >> 4) == 14 ? 3
                               : (lead >> 3) == 30 ? 4
                                                   : 0;
    if (length == 0 || k + length > xml.size()) return "invalid UTF-8 at byte " + std::to_string(k);
    for (std::size_t j = 1; j < length; ++j) {
      if ((static_cast<unsigned char>(xml[k + j]) & 0xC0) != 0x80) {
        return "invalid UTF-8 at byte " + std::to_string(k);
      }
    }
    if (length == 1 && lead < 0x20 && lead != '\t' && lead != '\n' && lead != '\r') {
      return "control character at byte " + std::to_string(k);
    }
    k += length;
  }
  const auto name_start = [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || c == ':' ||
           static_cast<unsigned char>(c) >= 0x80;
  };
  const auto name_char = [&](char c) {
    return name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
  };
  const auto read_name = [&]() -> std::string {
    if (i >= xml.size() || !name_start(xml[i])) return {};
    const std::size_t start = i;
    while (i < xml.size() && name_char(xml[i]))
      ++i;
    return std::string(xml.substr(start, i - start));
  };
  const auto space = [&]() {
    while (i < xml.size() &&
           (xml[i] == ' ' || xml[i] == '\n' || xml[i] == '\t' || xml[i] == '\r')) {
      ++i;
    }
  };
  // An entity reference starting at xml[i] == '&'.
  const auto entity = [&]() -> bool {
    const std::size_t end = xml.find(';', i);
    if (end == std::string_view::npos) return false;
    const std::string_view body = xml.substr(i + 1, end - i - 1);
    bool ok = body == "amp" || body == "lt" || body == "gt" || body == "quot" || body == "apos";
    if (!ok && body.size() >= 2 && body[0] == '#') {
      const bool hex = body[1] == 'x';
      const std::string_view digits = body.substr(hex ? 2 : 1);
      ok = !digits.empty();
      for (const char c : digits) {
        const bool digit =
            (c >= '0' && c <= '9') || (hex && ((c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F')));
        ok = ok && digit;
      }
    }
    if (ok) i = end + 1;
    return ok;
  };

  if (xml.substr(0, 5) == "<?xml") {
    const std::size_t end = xml.find("?>");
    if (end == std::string_view::npos) return "unterminated XML declaration";
    i = end + 2;
  }
  std::vector<std::string> open;
  bool root_seen = false;
  while (i < xml.size()) {
    if (xml[i] != '<') {
      if (open.empty()) {
        if (xml[i] != ' ' && xml[i] != '\n' && xml[i] != '\t' && xml[i] != '\r') {
          return at("text outside the root element");
        }
        ++i;
        continue;
      }
      if (xml[i] == '&') {
        if (!entity()) return at("bad entity");
        continue;
      }
      if (xml[i] == '>' && i >= 2 && xml.substr(i - 2, 3) == "]]>") return at("]]> in text");
      ++i;
      continue;
    }
    if (xml.substr(i, 4) == "<!--") {
      const std::size_t end = xml.find("-->", i + 4);
      if (end == std::string_view::npos) return at("unterminated comment");
      i = end + 3;
      continue;
    }
    if (xml.substr(i, 2) == "</") {
      i += 2;
      const std::string name = read_name();
      space();
      if (i >= xml.size() || xml[i] != '>') return at("bad end tag");
      ++i;
      if (open.empty() || open.back() != name) return at("end tag </" + name + "> does not match");
      open.pop_back();
      continue;
    }
    ++i;
    const std::string name = read_name();
    if (name.empty()) return at("bad tag name");
    if (open.empty() && root_seen) return at("second root element <" + name + ">");
    root_seen = true;
    std::set<std::string> attributes;
    for (;;) {
      const std::size_t before = i;
      space();
      if (i >= xml.size()) return at("unterminated tag <" + name + ">");
      if (xml[i] == '>') {
        ++i;
        open.push_back(name);
        break;
      }
      if (xml.substr(i, 2) == "/>") {
        i += 2;
        break;
      }
      if (i == before) return at("no space before an attribute of <" + name + ">");
      const std::string attribute = read_name();
      if (attribute.empty()) return at("bad attribute name in <" + name + ">");
      if (!attributes.insert(attribute).second) return at("duplicate attribute " + attribute);
      space();
      if (i >= xml.size() || xml[i] != '=') return at("attribute " + attribute + " has no value");
      ++i;
      space();
      if (i >= xml.size() || (xml[i] != '"' && xml[i] != '\'')) {
        return at("unquoted value of " + attribute);
      }
      const char quote = xml[i++];
      while (i < xml.size() && xml[i] != quote) {
        if (xml[i] == '<') return at("'<' in the value of " + attribute);
        if (xml[i] == '&') {
          if (!entity()) return at("bad entity in the value of " + attribute);
          continue;
        }
        ++i;
      }
      if (i >= xml.size()) return at("unterminated value of " + attribute);
      ++i;
    }
  }
  if (!root_seen) return "no root element";
  if (!open.empty()) return "element <" + open.back() + "> is not closed";
  return {};
}

}  // namespace fuzzygait::test
