// Deterministic random fuzzy engines written in fuzzylite's FLL language, for differential tests
// against fuzzylite. Every engine is valid for both libraries (each rule loads, every operator a
// rule needs is set), and one seed always gives the same text: the generator uses its own
// pseudo-random numbers, never the implementation-defined std distributions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace fuzzygait::fuzzy::testing {

// SplitMix64: tiny, fast, and the same sequence on every platform.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next();
  double unit();                            // uniform in [0, 1)
  double uniform(double low, double high);  // uniform in [low, high)
  int integer(int low, int high);           // uniform in [low, high]
  std::size_t index(std::size_t size);      // uniform in [0, size)
  bool chance(double probability);

 private:
  std::uint64_t state_;
};

struct RandomInput {
  std::string name;
  double minimum = 0.0;
  double maximum = 1.0;
  // Values where memberships change branch (range ends, term parameters): inputs land exactly
  // on them now and then, to exercise the tolerant comparisons.
  std::vector<double> landmarks;
};

struct RandomEngine {
  std::string fll;
  std::vector<RandomInput> inputs;  // in the engine's input order
  std::vector<std::string> outputs;
  // The language features the engine uses ("term:Bell", "hedge:very", "activation:Highest",
  // ...), so that a run can show it covered the whole FLL language.
  std::set<std::string> features;
};

RandomEngine random_engine(std::uint64_t seed);

// `rows` rows of inputs for the engine, row after row: mostly inside the input ranges, some
// outside, some exactly on landmarks, and a few NaN and infinities.
std::vector<double> random_rows(const RandomEngine& engine, std::size_t rows, std::uint64_t seed);

}  // namespace fuzzygait::fuzzy::testing
