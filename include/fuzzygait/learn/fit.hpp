// Fitting a controller set's network to training data by Levenberg-Marquardt (Ceres, automatic
// differentiation through fuzzy::evaluate_partition). Two views of the data:
//   commands      per frame: each controller's command against the one that takes the clip's
//                 joint velocity to the next step's, through the inertia (a quick start);
//   trajectories  the controllers replayed over every phase of every leg, each joint integrated as
//                 the walker integrates it from the clip's state where the phase begins, against
//                 the clip's angles: per joint with the other joints from the clip, or the joints
//                 of a leg together (coupled).
// The result stays readable: knots keep their order a gap apart, the output words keep their
// promises (learn::word_penalty's), and each weight is pulled weakly toward the base set's value,
// which holds where the data say nothing.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/learn/network.hpp"
#include "fuzzygait/learn/training.hpp"

namespace fuzzygait::learn {

enum class FitData { Commands, Trajectories };

struct FitProgress {
  std::string stage;  // FitOptions::stage
  int iteration = 0;
  double cost = 0.0;  // Ceres' cost: half the sum of squared residuals
};

// What the fit charges. The data's residuals are normalised so that their sum of squares is the
// mean squared error in these units; the readability terms are added to it.
struct FitOptions {
  std::string stage = "fit";  // names the fit in progress reports
  int max_iterations = 30;
  double command_unit = 100.0;  // deg/s of per-frame command error that is one unit
  double angle_unit = 1.0;      // deg of trajectory error that is one unit
  // Per squared share of its range that a weight strays from its base value (the weak pull).
  double prior = 1.0;
  // Per squared unit of a broken word promise (in word_unit shares of the output's range).
  double words = 1.0;
  double word_unit = 0.02;
  // Knots closer than this share of their input's range pay `order` per squared share.
  double knot_gap = 0.02;
  double order = 100.0;
  // The inertia stays within these (s).
  double shortest_inertia = 0.005;
  double longest_inertia = 0.2;
  int threads = 1;
  // Asked after every iteration; true ends the fit there, keeping the weights reached.
  std::function<bool()> stop;
  std::function<void(const FitProgress&)> progress;
};

struct FitResult {
  std::vector<double> weights;  // all of the network's, the free ones fitted
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  bool stopped = false;  // FitOptions::stop ended it
};

// Fits the weights `free` (indices into the network) from `start`, the others fixed at start's
// values, to every clip. Trajectories replay the joints of `simulated` (hip, knee, ankle, toe)
// together; Commands reads every driven joint. Throws std::invalid_argument for a start of the
// wrong size, an index out of range, no clips, or clips without a single driven step.
FitResult fit_weights(const SetNetwork& network, std::span<const TrainingClip> clips,
                      std::span<const double> start, std::span<const std::size_t> free,
                      FitData data, const std::array<bool, 4>& simulated,
                      const FitOptions& options);

// RMSE (deg) of each joint (hip, knee, ankle, toe) replayed with weights w over the clips: each
// alone with the others from the clip, or (coupled) the joints of a leg together. 0 for a joint
// no controller drives in the clips.
std::array<double, 4> replay_rmse(const SetNetwork& network, std::span<const TrainingClip> clips,
                                  std::span<const double> w, bool coupled);

// Weights `w` with each input's interior knots moved apart to at least `gap` of its range from
// their neighbours (in order, as little as needed), and the inertia within the options' bounds.
std::vector<double> ordered(const SetNetwork& network, std::span<const double> w, double gap);

// What makes weights readable: values with `digits` significant digits, knots `knot_gap` of
// their input's range apart, every output word's promise kept (word_unit as in FitOptions).
struct Readability {
  int digits = 3;
  double knot_gap = 0.02;
  double word_unit = 0.02;
};

// Weights `w` made readable: rounded, every word's promise kept (a value that breaks one moved
// just far enough: to zero, to its plain word's speed), knots ordered. With them the set's
// word_penalty is 0.
std::vector<double> readable(const SetNetwork& network, std::span<const double> w,
                             const Readability& readability = {});

}  // namespace fuzzygait::learn
