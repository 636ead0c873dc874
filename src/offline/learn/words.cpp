#include "offline/learn/words.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace fuzzygait::learn::detail {

std::vector<WordPromise> word_promises(const fuzzy::OutputVariable& out) {
  using Kind = WordPromise::Kind;
  std::vector<WordPromise> promises;
  // The Constant term named `word`, if there is one.
  auto find = [&out](const std::string& word, std::size_t& index) {
    for (std::size_t t = 0; t < out.terms.size(); ++t) {
      if (out.terms[t].name == word && out.terms[t].kind == fuzzy::TermKind::Constant) {
        index = t;
        return true;
      }
    }
    return false;
  };
  for (std::size_t t = 0; t < out.terms.size(); ++t) {
    if (out.terms[t].kind != fuzzy::TermKind::Constant) continue;
    const std::string& w = out.terms[t].name;
    auto has = [&w](const char* part) { return w.find(part) != std::string::npos; };
    if (w == "stay" || w == "hold") promises.push_back({Kind::NearZero, t});
    const bool positive = has("flex") || has("up") || has("roll") || has("settle") ||
                          (w == "slow" || w == "fast" || w == "steady" || w == "late");
    const bool negative =
        has("extend") || has("down") || has("push") || has("lower") || w == "back";
    if (positive) promises.push_back({Kind::Positive, t});
    if (negative) promises.push_back({Kind::Negative, t});
    std::size_t base = 0;
    const std::size_t fast = w.find("_fast");
    if (fast != std::string::npos && find(w.substr(0, fast), base)) {
      promises.push_back({Kind::Faster, t, base});
    }
    const std::size_t slow = w.find("_slow");
    if (slow != std::string::npos && find(w.substr(0, slow), base)) {
      promises.push_back({Kind::Slower, t, base});
    }
  }
  std::size_t slow = 0;
  std::size_t fast = 0;
  std::size_t steady = 0;
  std::size_t late = 0;
  if (find("slow", slow) && find("fast", fast)) promises.push_back({Kind::NotAbove, slow, fast});
  // The body's steady progress is faster than its slow start and its late finish, and slower
  // than its fast start.
  if (find("steady", steady)) {
    if (find("slow", slow)) promises.push_back({Kind::NotAbove, slow, steady});
    if (find("late", late)) promises.push_back({Kind::NotAbove, late, steady});
    if (find("fast", fast)) promises.push_back({Kind::NotAbove, steady, fast});
  }
  return promises;
}

void keep_promises(std::vector<double>& values, const std::vector<WordPromise>& promises,
                   double unit) {
  using Kind = WordPromise::Kind;
  for (int pass = 0; pass < 8; ++pass) {
    bool kept = true;
    for (const WordPromise& p : promises) {
      if (broken_by(p, values.data(), unit) == 0.0) continue;
      kept = false;
      double& v = values[p.term];
      const double other = values[p.other];
      switch (p.kind) {
        case Kind::NearZero:
          v = std::clamp(v, -unit, unit);
          break;
        case Kind::Positive:
          v = 0.0;
          break;
        case Kind::Negative:
          v = 0.0;
          break;
        case Kind::Faster:
        case Kind::Slower:
          // As fast as the plain word, in the direction the word turns the joint.
          v = std::copysign(std::abs(other), v == 0.0 ? other : v);
          break;
        case Kind::NotAbove:
          v = other;
          break;
      }
    }
    if (kept) return;
  }
}

}  // namespace fuzzygait::learn::detail
