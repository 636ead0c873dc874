#include "fuzzygait/learn/structure.hpp"

#include <map>
#include <stdexcept>
#include <utility>

#include "fuzzygait/fuzzy/partition.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::learn {
namespace {

std::size_t term_index(const fuzzy::InputVariable& v, const std::string& name) {
  for (std::size_t t = 0; t < v.terms.size(); ++t) {
    if (v.terms[t].name == name) return t;
  }
  return v.terms.size();
}

}  // namespace

fuzzy::Engine with_word(const fuzzy::Engine& engine, const AddedWord& word) {
  const std::string where = "cannot add '" + word.word + "' to '" + engine.name + "': ";
  std::string why;
  if (!fuzzy::as_partition(engine, &why)) {
    throw std::invalid_argument(where + "not a partition controller (" + why + ")");
  }
  std::size_t input = engine.inputs.size();
  for (std::size_t i = 0; i < engine.inputs.size(); ++i) {
    if (engine.inputs[i].name == word.input) input = i;
  }
  if (input == engine.inputs.size()) {
    throw std::invalid_argument(where + "it has no input '" + word.input + "'");
  }
  fuzzy::Engine out = engine;
  fuzzy::InputVariable& v = out.inputs[input];
  if (term_index(v, word.word) < v.terms.size()) {
    throw std::invalid_argument(where + "'" + word.input + "' has that word already");
  }
  if (term_index(v, word.like) == v.terms.size()) {
    throw std::invalid_argument(where + "'" + word.input + "' has no word '" + word.like + "'");
  }
  // The first word peaking above the new one: the new word goes before it.
  std::size_t at = 0;
  while (at < v.terms.size() && !(word.peak < v.terms[at].parameters[1]))
    ++at;
  if (at == 0 || at == v.terms.size() || !(v.terms[at - 1].parameters[1] < word.peak)) {
    throw std::invalid_argument(where + "its peak " + common::number_text(word.peak) +
                                " is not strictly between two words of '" + word.input + "'");
  }
  // What each rule concludes, by the words of its inputs.
  std::map<std::pair<std::string, std::string>, std::string> concludes;
  const std::vector<fuzzy::Rule>& rules = engine.rule_blocks.at(0).rules;
  for (const fuzzy::Rule& r : rules) {
    const std::string second = r.propositions.size() > 1 ? r.propositions[1].term : "";
    concludes[{r.propositions[0].term, second}] = r.conclusions.at(0).term;
  }
  fuzzy::Term term;
  term.name = word.word;
  term.kind = fuzzy::TermKind::Triangle;
  term.parameters = {v.terms[at - 1].parameters[1], word.peak, v.terms[at].parameters[1]};
  v.terms[at - 1].parameters[2] = word.peak;
  v.terms[at].parameters[0] = word.peak;
  v.terms.insert(v.terms.begin() + static_cast<std::ptrdiff_t>(at), term);
  // The rules anew, in the partition's order, the new word's as `like`'s.
  const fuzzy::Rule pattern = rules.front();
  std::vector<fuzzy::Rule> anew;
  auto as_known = [&](std::size_t i, const std::string& t) {
    return i == input && t == word.word ? word.like : t;
  };
  const std::vector<fuzzy::Term>& first = out.inputs[0].terms;
  const std::vector<fuzzy::Term> none(1);
  const std::vector<fuzzy::Term>& second = out.inputs.size() > 1 ? out.inputs[1].terms : none;
  for (const fuzzy::Term& a : first) {
    for (const fuzzy::Term& b : second) {
      fuzzy::Rule r = pattern;
      r.propositions[0].term = a.name;
      if (out.inputs.size() > 1) r.propositions[1].term = b.name;
      const std::string key_b = out.inputs.size() > 1 ? as_known(1, b.name) : "";
      r.conclusions[0].term = concludes.at({as_known(0, a.name), key_b});
      anew.push_back(std::move(r));
    }
  }
  out.rule_blocks[0].rules = std::move(anew);
  return out;
}

gait::ControllerSet with_words(const gait::ControllerSet& set,
                               const std::vector<AddedWord>& words) {
  gait::ControllerSet out = set;
  for (const AddedWord& w : words) {
    const auto s = static_cast<std::size_t>(w.slot);
    const gait::Controller& c = out.controllers.at(s);
    out.controllers[s] = gait::Controller(with_word(c.engine(), w), c.source());
  }
  return out;
}

std::vector<AddedWord> learning_structure(const gait::ControllerSet& base) {
  std::vector<AddedWord> words;
  // The swing's slight knee answers as a straight one (it holds: a swing can end on a slightly
  // bent knee, as people land); the stance's as a bent one (it straightens through mid stance,
  // holds late and folds at push-off, as people's do, where a straight knee's words flex it).
  // Measured on the CMU clips (docs/learning.md): the stance word answering as "bent" beat
  // "straight" on 07_01, 07_03 and 08_01 (knee RMSE 4.1, 6.3, 4.5 deg against 5.4, 7.1, 5.2),
  // not on 05_01 (7.2 against 4.3), a walk on a flexed knee.
  const struct {
    gait::LegPhase phase;
    const char* like;
    const char* why;
  } knees[] = {
      {gait::LegPhase::Swing, "straight",
       "a swing can end on a slightly bent knee, which holds as a straight one does, as people "
       "land"},
      {gait::LegPhase::Stance, "bent",
       "a planted knee slightly bent straightens through mid stance, holds late and folds at "
       "push-off as a bent one does, as people's knees do"},
  };
  for (const auto& k : knees) {
    const int slot = gait::slot(k.phase, gait::Joint::Knee);
    const fuzzy::Engine& e = base.controllers.at(static_cast<std::size_t>(slot)).engine();
    for (const fuzzy::InputVariable& v : e.inputs) {
      if (v.name != "knee") continue;
      const std::size_t straight = term_index(v, "straight");
      const std::size_t bent = term_index(v, "bent");
      if (straight == v.terms.size() || bent != straight + 1 ||
          term_index(v, "slight") < v.terms.size()) {
        continue;
      }
      const double peak = 0.5 * (v.terms[straight].parameters[1] + v.terms[bent].parameters[1]);
      words.push_back({slot, "knee", "slight", peak, k.like, k.why});
    }
  }
  return words;
}

}  // namespace fuzzygait::learn
