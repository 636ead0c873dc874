// Conformance with fuzzylite's own example datasets: every engine that ships with an FLD
// dataset in Debian's fuzzylite package reproduces it within fuzzylite's tolerance (1e-6).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fld.hpp"
#include "fuzzygait/fuzzy/fll.hpp"

namespace fs = std::filesystem;
using namespace fuzzygait::fuzzy;

namespace {

std::vector<fs::path> example_engines() {
  std::vector<fs::path> out;
  const fs::path root = FUZZYLITE_EXAMPLES_DIR;
  if (!fs::exists(root)) return out;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const fs::path& p = entry.path();
    if (p.extension() != ".fld") continue;
    if (p.string().find("/original/") != std::string::npos) continue;
    fs::path fll = p;
    fll.replace_extension(".fll");
    if (fs::exists(fll)) out.push_back(fll);
  }
  std::sort(out.begin(), out.end());
  return out;
}

Table read_table(const fs::path& path) {
  std::ifstream in(path);
  return read_fld_stream(in, path.string());
}

// Evaluates the dataset's inputs in order and compares every row with its outputs; every
// variable must have its column.
void reproduce(const Engine& engine, const Table& data, const std::string& label) {
  const Evaluator evaluator(engine);
  Workspace workspace = evaluator.make_workspace();
  std::vector<std::size_t> input_columns;
  std::vector<std::size_t> output_columns;
  for (const InputVariable& v : engine.inputs) {
    const int column = data.column(v.name);
    ASSERT_GE(column, 0) << label << ": no column for input '" << v.name << "'";
    input_columns.push_back(static_cast<std::size_t>(column));
  }
  for (const OutputVariable& v : engine.outputs) {
    const int column = data.column(v.name);
    ASSERT_GE(column, 0) << label << ": no column for output '" << v.name << "'";
    output_columns.push_back(static_cast<std::size_t>(column));
  }
  std::vector<double> inputs(engine.inputs.size());
  std::vector<double> outputs(engine.outputs.size());
  for (std::size_t r = 0; r < data.rows.size(); ++r) {
    for (std::size_t i = 0; i < inputs.size(); ++i)
      inputs[i] = data.rows[r][input_columns[i]];
    evaluator.evaluate(inputs, outputs, workspace);
    for (std::size_t o = 0; o < outputs.size(); ++o) {
      const double expected = data.rows[r][output_columns[o]];
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(outputs[o])) << label << " row " << r;
      } else if (std::isinf(expected)) {
        EXPECT_EQ(expected, outputs[o]) << label << " row " << r;
      } else {
        EXPECT_NEAR(expected, outputs[o], 1e-6)
            << label << " row " << r << " output " << engine.outputs[o].name;
      }
    }
  }
}

class FuzzyliteExample : public ::testing::TestWithParam<fs::path> {};

TEST_P(FuzzyliteExample, ReproducesItsDataset) {
  const fs::path fll = GetParam();
  fs::path fld = fll;
  fld.replace_extension(".fld");
  const Engine engine = read_fll_file(fll);
  const Table data = read_table(fld);
  ASSERT_EQ(data.rows.size(), 1024u) << fld;
  ASSERT_FALSE(engine.outputs.empty());
  reproduce(engine, data, fll.string());
}

TEST_P(FuzzyliteExample, SurvivesAnFllRoundTrip) {
  const fs::path fll = GetParam();
  fs::path fld = fll;
  fld.replace_extension(".fld");
  const Engine engine = read_fll_file(fll);
  const std::string written = write_fll(engine);
  const Engine again = read_fll(written, "round trip of " + fll.string());
  EXPECT_EQ(engine, again);
  EXPECT_EQ(written, write_fll(again));
  const Table data = read_table(fld);
  ASSERT_EQ(data.rows.size(), 1024u) << fld;
  ASSERT_FALSE(engine.outputs.empty());
  reproduce(again, data, "round trip of " + fll.string());
}

std::string test_name(const ::testing::TestParamInfo<fs::path>& info) {
  std::string name =
      info.param.parent_path().filename().string() + "_" + info.param.stem().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Debian, FuzzyliteExample, ::testing::ValuesIn(example_engines()),
                         test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(FuzzyliteExample);

TEST(FuzzyliteExamples, AllEighteenDatasetsArePresent) {
  // (FUZZYGAIT_REQUIRE_FUZZYLITE stops the configuration instead when they are missing.)
  if (!fs::exists(FUZZYLITE_EXAMPLES_DIR)) GTEST_SKIP() << "fuzzylite examples not installed";
  EXPECT_EQ(example_engines().size(), 18u);
}

}  // namespace
