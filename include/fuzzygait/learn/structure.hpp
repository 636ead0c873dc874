// Structure that training adds to a controller set where its rules cannot follow motion capture:
// another word on an input of a partition controller ("the knee is slight", between "straight"
// and "bent"), with one rule per word of the other input that answers as a neighbouring word's
// rule does. At the moment it is added the controller answers nearly as before (the new word's
// rules are its neighbour's); training then moves its peak and the outputs. The result is still a
// partition controller: the same shape, one more word, readable as before.
#pragma once

#include <string>
#include <vector>

#include "fuzzygait/fuzzy/engine.hpp"
#include "fuzzygait/gait/controllers.hpp"

namespace fuzzygait::learn {

struct AddedWord {
  int slot = 0;       // the controller's slot
  std::string input;  // the input variable it is added to ("knee")
  std::string word;   // its name ("slight")
  double peak = 0.0;  // where it holds fully, strictly between two neighbouring words' peaks
  std::string like;   // the word whose rules its own rules copy ("straight")
  std::string why;    // one sentence for the report
};

// The engine with the word added: a Triangle term peaking at `peak` between its neighbours (whose
// feet move to it), and its rules (one per word of the other input, in the partition's order)
// concluding what the rules of `like` conclude. Throws std::invalid_argument naming the engine
// when it is not a partition controller, the input or `like` is not there, the word exists
// already, or the peak is not strictly between two words' peaks.
fuzzy::Engine with_word(const fuzzy::Engine& engine, const AddedWord& word);

// The set with each word added to its slot's controller.
gait::ControllerSet with_words(const gait::ControllerSet& set, const std::vector<AddedWord>& words);

// The words `fuzzygait train` adds where a set lacks them: a "slight" knee between "straight" and
// "bent" in the swing knee, answering as "straight" (so that a swing can end on a slightly bent
// knee, as people land), and in the stance knee, answering as "bent" (a slightly bent planted
// knee straightens through mid stance and folds at push-off). Only where the controller reads the
// knee with words "straight" and "bent" and has no "slight".
std::vector<AddedWord> learning_structure(const gait::ControllerSet& base);

}  // namespace fuzzygait::learn
