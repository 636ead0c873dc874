// fuzzylite and fuzzygait fed the same inputs, row after row, must give the same bits. Only for
// test targets that link fuzzylite_oracle.
#pragma once

#include <fl/Headers.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <functional>
#include <iomanip>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "support/bits.hpp"

namespace fuzzygait::test {

struct FuzzyliteComparison {
  std::string label;                        // names the engine in failure messages
  std::vector<std::string> inputs;          // fuzzylite's input variables, in a row's order
  std::vector<std::string> outputs;         // fuzzylite's output variables, in fuzzygait's order
  std::vector<std::vector<double>> values;  // per input: its values; rows are every combination,
                                            // the first input varying fastest
  std::size_t max_reported = 5;             // mismatches reported one by one
};

// Fuzzygait's outputs for one row of inputs.
using FuzzygaitOutputs =
    std::function<void(std::span<const double> inputs, std::span<double> outputs)>;

// Evaluates every row, in order, through fuzzylite's `reference` (inputs set by name) and through
// `fuzzygait`, and compares each output bit for bit (any NaN equals any NaN). The first
// max_reported mismatches fail the test with their row, then it expects no mismatch at all.
// Returns the number of mismatches.
inline std::size_t expect_fuzzylite_outputs(fl::Engine& reference, const FuzzyliteComparison& c,
                                            const FuzzygaitOutputs& fuzzygait) {
  std::vector<fl::InputVariable*> inputs;
  for (const std::string& name : c.inputs)
    inputs.push_back(reference.getInputVariable(name));
  std::vector<fl::OutputVariable*> outputs;
  for (const std::string& name : c.outputs)
    outputs.push_back(reference.getOutputVariable(name));
  bool missing = false;
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    if (inputs[k] != nullptr) continue;
    ADD_FAILURE() << c.label << ": fuzzylite's engine has no input " << c.inputs[k];
    missing = true;
  }
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    if (outputs[k] != nullptr) continue;
    ADD_FAILURE() << c.label << ": fuzzylite's engine has no output " << c.outputs[k];
    missing = true;
  }
  if (missing) return 0;
  std::size_t rows = c.inputs.empty() ? 0 : 1;
  for (const std::vector<double>& v : c.values)
    rows *= v.size();
  EXPECT_EQ(c.values.size(), c.inputs.size()) << c.label;
  EXPECT_GT(rows, 0u) << c.label << ": nothing to compare";
  if (c.values.size() != c.inputs.size()) return 0;
  std::vector<double> row(c.inputs.size());
  std::vector<double> got(c.outputs.size());
  std::size_t mismatches = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    std::size_t rest = r;
    for (std::size_t i = 0; i < row.size(); ++i) {
      row[i] = c.values[i][rest % c.values[i].size()];
      rest /= c.values[i].size();
      inputs[i]->setValue(row[i]);
    }
    reference.process();
    fuzzygait(row, got);
    for (std::size_t o = 0; o < got.size(); ++o) {
      const double expected = outputs[o]->getValue();
      if (!same_bits(expected, got[o]) && ++mismatches <= c.max_reported) {
        std::ostringstream at;
        at << std::setprecision(17);
        for (std::size_t i = 0; i < row.size(); ++i)
          at << (i == 0 ? "" : ", ") << c.inputs[i] << " = " << row[i];
        ADD_FAILURE() << c.label << " row " << r << " (" << at.str() << ") output " << c.outputs[o]
                      << ": fuzzylite " << std::setprecision(17) << expected << ", fuzzygait "
                      << got[o];
      }
    }
  }
  EXPECT_EQ(mismatches, 0u) << c.label << ": " << rows << " rows";
  return mismatches;
}

}  // namespace fuzzygait::test
