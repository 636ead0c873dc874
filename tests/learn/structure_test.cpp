// The structure training adds: a word on a controller's input whose rules copy a neighbour's, the
// controller still of the partition shape and answering as its neighbour did where the new word
// holds; refusals that name what is wrong.
#include "fuzzygait/learn/structure.hpp"

#include <gtest/gtest.h>

#include <string>

#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/partition.hpp"
#include "fuzzygait/learn/network.hpp"
#include "support/walks.hpp"

namespace fuzzygait {
namespace {

const fuzzy::Engine& swing_knee() {
  return test::default_set().at(gait::LegPhase::Swing, gait::Joint::Knee).engine();
}

learn::AddedWord slight(double peak = 15.0) {
  return {
      .slot = 1, .input = "knee", .word = "slight", .peak = peak, .like = "straight", .why = ""};
}

TEST(AddedWord, IsANewPeakBetweenItsNeighboursWithItsNeighboursRules) {
  const fuzzy::Engine e = learn::with_word(swing_knee(), slight());
  const fuzzy::InputVariable& knee = e.inputs[1];
  ASSERT_EQ(knee.terms.size(), 4u);
  EXPECT_EQ(knee.terms[1].name, "slight");
  EXPECT_EQ(knee.terms[1].parameters, (std::vector<double>{0.0, 15.0, 30.0}));
  EXPECT_EQ(knee.terms[0].parameters[2], 15.0);
  EXPECT_EQ(knee.terms[2].parameters[0], 15.0);
  // 4 delta words times 4 knee words, in the partition's order; "slight" concludes as "straight".
  const std::vector<fuzzy::Rule>& rules = e.rule_blocks[0].rules;
  ASSERT_EQ(rules.size(), 16u);
  EXPECT_EQ(rules[1].text(), "if delta is start and knee is slight then velocity is flex_fast");
  EXPECT_EQ(rules[9].text(), "if delta is end and knee is slight then velocity is hold");
  EXPECT_EQ(rules[10].text(), "if delta is end and knee is bent then velocity is extend_fast");
  std::string why;
  ASSERT_TRUE(fuzzy::as_partition(e, &why)) << why;
  // It reads and writes as FLL like any other.
  EXPECT_EQ(fuzzy::write_fll(fuzzy::read_fll(fuzzy::write_fll(e))), fuzzy::write_fll(e));
}

// Up to the new peak the controller answers as with the neighbour's word extended there; past the
// next word, as before.
TEST(AddedWord, LeavesTheAnswerOfTheOtherWordsAsItWas) {
  const gait::Controller before(swing_knee(), "before");
  const gait::Controller after(learn::with_word(swing_knee(), slight()), "after");
  fuzzy::Workspace none;
  for (double delta = -1.0; delta <= 1.5; delta += 0.05) {
    gait::MetricValues m{};
    m[static_cast<std::size_t>(gait::Metric::Delta)] = delta;
    for (const double knee : {0.0, 30.0, 40.0, 60.0}) {
      m[static_cast<std::size_t>(gait::Metric::Knee)] = knee;
      EXPECT_EQ(after.evaluate(m, none), before.evaluate(m, none)) << delta << " " << knee;
    }
    // Between straight and slight: straight's answer.
    m[static_cast<std::size_t>(gait::Metric::Knee)] = 0.0;
    const double straight = before.evaluate(m, none);
    m[static_cast<std::size_t>(gait::Metric::Knee)] = 10.0;
    EXPECT_DOUBLE_EQ(after.evaluate(m, none), straight) << delta;
  }
}

TEST(AddedWord, IsRefusedWhereItCannotGo) {
  auto refused = [](const learn::AddedWord& w, const std::string& expected) {
    try {
      learn::with_word(swing_knee(), w);
      ADD_FAILURE() << w.word << " was added";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("swing_knee"), std::string::npos) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << what;
    }
  };
  learn::AddedWord w = slight();
  w.input = "ankle";
  refused(w, "no input 'ankle'");
  w = slight();
  w.word = "bent";
  refused(w, "has that word already");
  w = slight();
  w.like = "wobbly";
  refused(w, "no word 'wobbly'");
  refused(slight(30.0), "not strictly between");
  refused(slight(75.0), "not strictly between");
  refused(slight(-1.0), "not strictly between");
}

TEST(LearningStructure, AddsASlightKneeToBothKneesOfTheDefault) {
  const std::vector<learn::AddedWord> words = learn::learning_structure(test::default_set());
  ASSERT_EQ(words.size(), 2u);
  EXPECT_EQ(words[0].slot, gait::slot(gait::LegPhase::Swing, gait::Joint::Knee));
  EXPECT_EQ(words[0].peak, 15.0);  // halfway between straight (0) and bent (30)
  EXPECT_EQ(words[1].slot, gait::slot(gait::LegPhase::Stance, gait::Joint::Knee));
  EXPECT_EQ(words[1].peak, 10.0);  // between 0 and 20
  EXPECT_EQ(words[0].like, "straight");
  EXPECT_EQ(words[1].like, "bent");
  for (const learn::AddedWord& w : words) {
    EXPECT_EQ(w.word, "slight");
    EXPECT_FALSE(w.why.empty());
  }
  // The structured set is a network with the new knots as weights; added twice, nothing new.
  const gait::ControllerSet structured = learn::with_words(test::default_set(), words);
  const learn::SetNetwork network(structured);
  EXPECT_LT(network.find("swing_knee.knee.slight"), network.size());
  EXPECT_LT(network.find("stance_knee.knee.slight"), network.size());
  EXPECT_TRUE(learn::learning_structure(structured).empty());
}

}  // namespace
}  // namespace fuzzygait
