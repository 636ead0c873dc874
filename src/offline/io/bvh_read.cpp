// The BVH reader: a tokenizer that knows its line, and a parser of the hierarchy without
// recursion (a joint's depth is bounded, and no depth reaches the stack).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "fuzzygait/io/mocap.hpp"

namespace fuzzygait::io {
namespace {

constexpr double kMaxValue = 1e9;  // larger values are a broken file, not a pose
constexpr double kMinFrameTime = 1e-4;
constexpr double kMaxFrameTime = 1.0;
constexpr std::size_t kMaxShown = 40;  // characters of a token quoted in a message

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// A token as a message quotes it: control characters as '?', long ones cut.
std::string shown(std::string_view token) {
  if (token.empty()) return "the end of the file";
  std::string text = "'";
  for (std::size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    text += (c < 0x20 || c == 0x7f) ? '?' : token[i];
  }
  if (token.size() > kMaxShown) text += "...";
  return text + "'";
}

struct Token {
  std::string_view text;  // empty at the end of the text (or of the line, see next_on_line)
  int line = 0;
};

class Tokenizer {
 public:
  Tokenizer(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  Token next() {
    skip_space(true);
    return take();
  }
  // The next token if it is on the current line; an empty one (and nothing consumed) otherwise.
  Token next_on_line() {
    skip_space(false);
    if (at_ < text_.size() && text_[at_] == '\n') return {{}, line_};
    return take();
  }
  // Whether the current line holds nothing more.
  bool line_ends() {
    skip_space(false);
    return at_ >= text_.size() || text_[at_] == '\n';
  }
  // Moves past the end of the current line (which must hold nothing more).
  void end_line() {
    skip_space(false);
    if (at_ < text_.size()) {
      ++at_;
      ++line_;
    }
  }
  bool at_end() {
    skip_space(true);
    return at_ >= text_.size();
  }
  int line() const { return line_; }

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw MocapError(source_, line, message);
  }
  [[noreturn]] void expected(const std::string& what, const Token& found) const {
    fail(found.line, "expected " + what + " found " + shown(found.text));
  }
  void expect(std::string_view keyword) {
    const Token t = next();
    if (t.text != keyword) expected("'" + std::string(keyword) + "'", t);
  }
  // A finite number of magnitude at most kMaxValue, whole token.
  double number(const Token& t, const std::string& what) const {
    std::string_view s = t.text;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || error != std::errc() || end != s.data() + s.size() || !std::isfinite(value) ||
        std::abs(value) > kMaxValue) {
      expected(what + " (a finite number of magnitude at most 1e9)", t);
    }
    return value;
  }
  double number(const std::string& what) { return number(next(), what); }
  // A whole number from 0 to `most`, digits only.
  std::size_t count(const Token& t, const std::string& what, std::size_t most) const {
    std::size_t value = 0;
    const bool digits = !t.text.empty() && std::all_of(t.text.begin(), t.text.end(),
                                                       [](char c) { return c >= '0' && c <= '9'; });
    const auto [end, error] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), value);
    if (!digits || error != std::errc() || end != t.text.data() + t.text.size() || value > most) {
      expected(what + " (a whole number from 0 to " + std::to_string(most) + ")", t);
    }
    return value;
  }

 private:
  void skip_space(bool newlines) {
    while (at_ < text_.size() && is_space(text_[at_])) {
      if (text_[at_] == '\n') {
        if (!newlines) return;
        ++line_;
      }
      ++at_;
    }
  }
  Token take() {
    const std::size_t begin = at_;
    while (at_ < text_.size() && !is_space(text_[at_]))
      ++at_;
    return {text_.substr(begin, at_ - begin), line_};
  }

  std::string_view text_;
  std::string source_;
  std::size_t at_ = 0;
  int line_ = 1;
};

bool channel_named(std::string_view name, BvhChannel& channel) {
  static constexpr std::pair<std::string_view, BvhChannel> kNames[] = {
      {"Xposition", BvhChannel::Xposition}, {"Yposition", BvhChannel::Yposition},
      {"Zposition", BvhChannel::Zposition}, {"Xrotation", BvhChannel::Xrotation},
      {"Yrotation", BvhChannel::Yrotation}, {"Zrotation", BvhChannel::Zrotation}};
  for (const auto& [text, value] : kNames) {
    if (name == text) {
      channel = value;
      return true;
    }
  }
  return false;
}

class Parser {
 public:
  Parser(std::string_view text, std::string source) : in_(text, std::move(source)) {}

  BvhClip read() {
    in_.expect("HIERARCHY");
    const Token root = in_.next();
    if (root.text != "ROOT") in_.expected("'ROOT'", root);
    hierarchy(root);
    motion();
    return std::move(clip_);
  }

 private:
  // ROOT and its joints. `stack` holds the open joints, innermost last.
  void hierarchy(const Token& root) {
    std::vector<int> stack;
    open_joint(root, -1, stack);
    while (!stack.empty()) {
      const Token t = in_.next();
      if (t.text == "}") {
        stack.pop_back();
      } else if (t.text == "JOINT") {
        open_joint(t, stack.back(), stack);
      } else if (t.text == "End") {
        end_site(t, stack.back(), stack.size());
      } else {
        in_.expected("'JOINT', 'End Site' or '}' in joint '" +
                         clip_.joints[static_cast<std::size_t>(stack.back())].name + "'",
                     t);
      }
    }
    if (clip_.channel_count == 0) in_.fail(root.line, "expected channels: no joint has any");
  }

  void check_depth(std::size_t depth, const Token& at) {
    if (depth >= static_cast<std::size_t>(kMaxBvhDepth)) {
      in_.fail(at.line, "expected joints nested at most " + std::to_string(kMaxBvhDepth) +
                            " deep found a deeper one");
    }
  }

  // After ROOT or JOINT: the name (the rest of the line, a '{' at its end taken as the brace),
  // '{', OFFSET, CHANNELS.
  void open_joint(const Token& keyword, int parent, std::vector<int>& stack) {
    check_depth(stack.size(), keyword);
    std::string name;
    bool brace = false;
    for (Token t = in_.next_on_line(); !t.text.empty(); t = in_.next_on_line()) {
      if (brace) in_.expected("the end of the line after '{'", t);
      if (t.text == "{") {
        brace = true;
      } else {
        name += (name.empty() ? "" : " ") + std::string(t.text);
      }
    }
    if (name.empty()) {
      in_.fail(keyword.line, "expected a joint name after " + std::string(keyword.text) +
                                 " found " + (brace ? "'{'" : "the end of the line"));
    }
    for (char c : name) {
      const auto u = static_cast<unsigned char>(c);
      if (u < 0x20 || u == 0x7f) {
        in_.expected("a joint name (printable characters)", {name, keyword.line});
      }
    }
    if (const auto [known, added] = lines_.emplace(name, keyword.line); !added) {
      in_.fail(keyword.line, "expected a joint name not used before found '" + name +
                                 "' (also on line " + std::to_string(known->second) + ")");
    }
    if (!brace) in_.expect("{");
    BvhJoint joint;
    joint.name = std::move(name);
    joint.parent = parent;
    joint.line = keyword.line;
    offset(joint);
    const Token channels = in_.next();
    if (channels.text != "CHANNELS") {
      in_.expected("'CHANNELS' in joint '" + joint.name + "'", channels);
    }
    const std::size_t n = in_.count(in_.next(), "a channel count", 6);
    for (std::size_t k = 0; k < n; ++k) {
      const Token t = in_.next();
      BvhChannel channel{};
      if (!channel_named(t.text, channel)) {
        in_.expected("channel " + std::to_string(k + 1) + " of " + std::to_string(n) +
                         " (Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation)",
                     t);
      }
      if (std::find(joint.channels.begin(), joint.channels.end(), channel) !=
          joint.channels.end()) {
        in_.expected("a channel not listed before in joint '" + joint.name + "'", t);
      }
      joint.channels.push_back(channel);
    }
    joint.first_column = clip_.channel_count;
    clip_.channel_count += n;
    clip_.joints.push_back(std::move(joint));
    stack.push_back(static_cast<int>(clip_.joints.size() - 1));
  }

  void end_site(const Token& end, int parent, std::size_t depth) {
    check_depth(depth, end);
    const Token site = in_.next();
    if (site.text != "Site") in_.expected("'Site' after 'End'", site);
    in_.expect("{");
    BvhJoint joint;
    joint.name = "End Site";
    joint.parent = parent;
    joint.end_site = true;
    joint.line = end.line;
    joint.first_column = clip_.channel_count;
    offset(joint);
    const Token close = in_.next();
    if (close.text != "}")
      in_.expected("'}' closing the End Site of line " + std::to_string(end.line), close);
    clip_.joints.push_back(std::move(joint));
  }

  void offset(BvhJoint& joint) {
    const Token t = in_.next();
    if (t.text != "OFFSET") in_.expected("'OFFSET' in joint '" + joint.name + "'", t);
    for (double& v : joint.offset)
      v = in_.number("an OFFSET coordinate");
  }

  void motion() {
    in_.expect("MOTION");
    const Token frames = in_.next();
    if (frames.text == "Frames") {
      in_.expect(":");
    } else if (frames.text != "Frames:") {
      in_.expected("'Frames:'", frames);
    }
    const Token count_token = in_.next();
    const std::size_t count = in_.count(count_token, "the frame count", kMaxBvhFrames);
    if (count == 0) in_.expected("at least one frame", count_token);
    in_.expect("Frame");
    const Token time = in_.next();
    if (time.text == "Time") {
      in_.expect(":");
    } else if (time.text != "Time:") {
      in_.expected("'Time:'", time);
    }
    const Token t = in_.next();
    clip_.frame_time = in_.number(t, "the frame time");
    if (!(clip_.frame_time >= kMinFrameTime && clip_.frame_time <= kMaxFrameTime)) {
      in_.expected("a frame time from 0.0001 to 1 s", t);
    }
    if (!in_.line_ends()) in_.expected("the end of the line after the frame time", in_.next());
    in_.end_line();
    // Rows: one a line, blank lines between them ignored. The vector grows with the rows read,
    // never with the count claimed.
    std::size_t read = 0;
    while (read < count) {
      if (in_.at_end()) {
        in_.fail(in_.line(), "expected " + std::to_string(count) +
                                 " frames (the 'Frames:' count) found " + std::to_string(read));
      }
      const int line = in_.line();
      std::size_t values = 0;
      for (Token v = in_.next_on_line(); !v.text.empty(); v = in_.next_on_line()) {
        if (values == clip_.channel_count) {
          in_.fail(line, "expected " + std::to_string(clip_.channel_count) + " values in frame " +
                             std::to_string(read + 1) + " (the channels' count) found more");
        }
        clip_.values.push_back(in_.number(
            v, "value " + std::to_string(values + 1) + " of frame " + std::to_string(read + 1)));
        ++values;
      }
      if (values != clip_.channel_count) {
        in_.fail(line, "expected " + std::to_string(clip_.channel_count) + " values in frame " +
                           std::to_string(read + 1) + " (the channels' count) found " +
                           std::to_string(values));
      }
      in_.end_line();
      ++read;
    }
    if (!in_.at_end()) {
      const Token extra = in_.next();
      in_.expected("the end of the file after " + std::to_string(count) +
                       (count == 1 ? " frame" : " frames") + " (the 'Frames:' count)",
                   extra);
    }
  }

  Tokenizer in_;
  BvhClip clip_;
  std::unordered_map<std::string, int> lines_;  // joint names and where each is declared
};

}  // namespace

MocapError::MocapError(std::string source, int line, const std::string& message)
    : std::invalid_argument(source + (line > 0 ? ":" + std::to_string(line) : std::string()) +
                            ": " + message),
      source_(std::move(source)),
      line_(line) {}

bool is_rotation(BvhChannel channel) {
  return channel == BvhChannel::Xrotation || channel == BvhChannel::Yrotation ||
         channel == BvhChannel::Zrotation;
}

int axis_of(BvhChannel channel) {
  return static_cast<int>(channel) % 3;
}

int BvhClip::find(std::string_view name) const {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (!joints[i].end_site && joints[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

BvhClip read_bvh(std::string_view text, std::string_view source) {
  return Parser(text, std::string(source)).read();
}

BvhClip read_bvh_file(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw MocapError(path.string(), 0, "is a directory, not a BVH file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MocapError(path.string(), 0, "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw MocapError(path.string(), 0, "cannot read the file");
  return read_bvh(text.str(), path.string());
}

}  // namespace fuzzygait::io
