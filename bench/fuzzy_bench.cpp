// `fuzzygait-bench fuzzy`: evaluates every example engine that ships with a dataset in
// fuzzylite's examples through fuzzylite and through fuzzygait's Evaluator, checks that both give
// the same outputs, and times both, alternating sides so that they share the machine's noise.
#include <fl/Headers.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fld.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "timing.hpp"

namespace fuzzygait::bench {
namespace {

namespace fs = std::filesystem;
using namespace fuzzygait::fuzzy;

struct Options {
  std::string examples_dir = FUZZYLITE_EXAMPLES_DIR;
  double min_seconds = 0.1;  // per repetition, per library
  int repetitions = 5;
  std::string filter;
};

// Example engines with a dataset, outside original/ (kept for fuzzylite's own regressions).
std::vector<fs::path> example_engines(const fs::path& root) {
  std::vector<fs::path> engines;
  if (!fs::is_directory(root)) throw std::runtime_error(root.string() + ": no such directory");
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const fs::path& fld = entry.path();
    if (fld.extension() != ".fld") continue;
    if (fld.string().find("/original/") != std::string::npos) continue;
    fs::path fll = fld;
    fll.replace_extension(".fll");
    if (fs::exists(fll)) engines.push_back(fll);
  }
  std::sort(engines.begin(), engines.end());
  return engines;
}

// The dataset's input columns as rows of input_count() values, in the engine's input order.
std::vector<double> input_rows(const Engine& engine, const fs::path& fld) {
  std::ifstream in(fld);
  if (!in) throw std::runtime_error(fld.string() + ": cannot open the file");
  const Table table = read_fld_stream(in, fld.string());
  std::vector<double> rows;
  rows.reserve(table.rows.size() * engine.inputs.size());
  for (const std::vector<double>& row : table.rows) {
    for (const InputVariable& v : engine.inputs) {
      const int column = table.column(v.name);
      if (column < 0) throw std::runtime_error(fld.string() + ": no column " + v.name);
      rows.push_back(row[static_cast<std::size_t>(column)]);
    }
  }
  return rows;
}

class FuzzyliteSide {
 public:
  FuzzyliteSide(const fs::path& fll, const Engine& model)
      : engine_(fl::FllImporter().fromFile(fll.string())) {
    for (const InputVariable& v : model.inputs) {
      inputs_.push_back(engine_->getInputVariable(v.name));
    }
    for (const OutputVariable& v : model.outputs) {
      outputs_.push_back(engine_->getOutputVariable(v.name));
    }
  }
  void run(const std::vector<double>& rows, std::vector<double>& outputs) {
    const std::size_t row_count = rows.size() / inputs_.size();
    const double* in = rows.data();
    double* out = outputs.data();
    for (std::size_t r = 0; r < row_count; ++r) {
      for (fl::InputVariable* v : inputs_)
        v->setValue(*in++);
      engine_->process();
      for (fl::OutputVariable* v : outputs_)
        *out++ = v->getValue();
    }
  }

 private:
  std::unique_ptr<fl::Engine> engine_;
  std::vector<fl::InputVariable*> inputs_;
  std::vector<fl::OutputVariable*> outputs_;
};

class FuzzygaitSide {
 public:
  explicit FuzzygaitSide(const Engine& engine)
      : evaluator_(engine), workspace_(evaluator_.make_workspace()) {}
  void run(const std::vector<double>& rows, std::vector<double>& outputs) {
    evaluator_.evaluate_batch(rows, outputs, workspace_);
  }

 private:
  Evaluator evaluator_;
  Workspace workspace_;
};

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
}

// "identical" when every value has the same bits (any NaN equals any NaN), else the largest
// absolute difference.
std::string compare_outputs(const std::vector<double>& expected, const std::vector<double>& got) {
  double largest = 0.0;
  bool identical = true;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (same_bits(expected[i], got[i])) continue;
    identical = false;
    const double difference = std::isnan(expected[i]) != std::isnan(got[i])
                                  ? std::numeric_limits<double>::infinity()
                                  : std::abs(expected[i] - got[i]);
    if (!(difference <= largest)) largest = difference;
  }
  if (identical) return "identical";
  char text[48];
  std::snprintf(text, sizeof text, "max |diff| %.3g", largest);
  return text;
}

template <class Side>
double seconds_for(Side& side, long passes, const std::vector<double>& rows,
                   std::vector<double>& outputs) {
  return wall_seconds([&] {
    for (long p = 0; p < passes; ++p)
      side.run(rows, outputs);
  });
}

// Passes over the dataset that take about `min_seconds`, from one pass up.
template <class Side>
long passes_for(Side& side, double min_seconds, const std::vector<double>& rows,
                std::vector<double>& outputs) {
  return calibrate(1, min_seconds,
                   [&](long passes) { return seconds_for(side, passes, rows, outputs); });
}

struct Result {
  std::string label;
  std::string type;
  std::string shape;  // inputs/outputs/rules
  double fuzzylite_ns;
  double fuzzygait_ns;
  std::string outputs;
};

Result measure(const fs::path& fll, const std::string& label, const Options& options) {
  const Engine engine = read_fll_file(fll);
  fs::path fld = fll;
  fld.replace_extension(".fld");
  const std::vector<double> rows = input_rows(engine, fld);
  const std::size_t row_count = engine.inputs.empty() ? 0 : rows.size() / engine.inputs.size();
  if (row_count == 0) throw std::runtime_error(fld.string() + ": no rows");

  Result result;
  result.label = label;
  result.type = std::string(name(engine.type()));
  std::size_t rules = 0;
  for (const RuleBlock& b : engine.rule_blocks)
    rules += b.rules.size();
  result.shape = std::to_string(engine.inputs.size()) + "/" +
                 std::to_string(engine.outputs.size()) + "/" + std::to_string(rules);

  FuzzyliteSide fuzzylite(fll, engine);
  FuzzygaitSide fuzzygait(engine);
  std::vector<double> fuzzylite_outputs(row_count * engine.outputs.size());
  std::vector<double> fuzzygait_outputs(fuzzylite_outputs.size());
  // From the freshly loaded state, as fuzzylite's dataset export.
  fuzzylite.run(rows, fuzzylite_outputs);
  fuzzygait.run(rows, fuzzygait_outputs);
  result.outputs = compare_outputs(fuzzylite_outputs, fuzzygait_outputs);

  const long fuzzylite_passes = passes_for(fuzzylite, options.min_seconds, rows, fuzzylite_outputs);
  const long fuzzygait_passes = passes_for(fuzzygait, options.min_seconds, rows, fuzzygait_outputs);
  const double evaluations = static_cast<double>(row_count);
  std::vector<double> fuzzylite_ns;
  std::vector<double> fuzzygait_ns;
  for (int r = 0; r < options.repetitions; ++r) {
    auto time_fuzzylite = [&] {
      fuzzylite_ns.push_back(1e9 *
                             seconds_for(fuzzylite, fuzzylite_passes, rows, fuzzylite_outputs) /
                             (evaluations * static_cast<double>(fuzzylite_passes)));
    };
    auto time_fuzzygait = [&] {
      fuzzygait_ns.push_back(1e9 *
                             seconds_for(fuzzygait, fuzzygait_passes, rows, fuzzygait_outputs) /
                             (evaluations * static_cast<double>(fuzzygait_passes)));
    };
    run_alternating(r, time_fuzzylite, time_fuzzygait);
  }
  result.fuzzylite_ns = median(fuzzylite_ns);
  result.fuzzygait_ns = median(fuzzygait_ns);
  return result;
}

void run_fuzzy_benchmark(const Options& options) {
  const fs::path root = options.examples_dir;
  std::vector<fs::path> engines;
  std::vector<std::string> labels;
  for (const fs::path& fll : example_engines(root)) {
    fs::path label = fs::relative(fll, root);
    label.replace_extension();
    if (label.string().find(options.filter) == std::string::npos) continue;
    engines.push_back(fll);
    labels.push_back(label.string());
  }
  if (engines.empty()) throw std::runtime_error("no example engine matches");

  std::size_t label_width = 6;
  for (const std::string& label : labels)
    label_width = std::max(label_width, label.size());
  const int w = static_cast<int>(label_width);
  std::printf(
      "fuzzylite %s vs fuzzygait: ns per evaluation over each dataset's rows in order, "
      "median of %d repetitions of >= %.2f s per library\n",
      fl::fuzzylite::version().c_str(), options.repetitions, options.min_seconds);
  std::printf("%-*s  %-17s  %-12s  %13s  %13s  %8s  %s\n", w, "engine", "type", "in/out/rules",
              "fuzzylite ns", "fuzzygait ns", "speedup", "outputs");
  std::fflush(stdout);
  double log_sum = 0.0;
  for (std::size_t i = 0; i < engines.size(); ++i) {
    const Result r = measure(engines[i], labels[i], options);
    const double speedup = r.fuzzylite_ns / r.fuzzygait_ns;
    log_sum += std::log(speedup);
    std::printf("%-*s  %-17s  %-12s  %13.1f  %13.1f  %7.2fx  %s\n", w, r.label.c_str(),
                r.type.c_str(), r.shape.c_str(), r.fuzzylite_ns, r.fuzzygait_ns, speedup,
                r.outputs.c_str());
    std::fflush(stdout);
  }
  std::printf("geomean speedup: %.2f\n", std::exp(log_sum / static_cast<double>(engines.size())));
}

}  // namespace

void add_fuzzy_command(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* fuzzy = app.add_subcommand(
      "fuzzy", "fuzzygait's Evaluator against fuzzylite on fuzzylite's example engines");
  fuzzy
      ->add_option("--examples", options->examples_dir,
                   "fuzzylite's examples folder (engines with FLD datasets)")
      ->capture_default_str();
  add_timing_options(*fuzzy, options->min_seconds, options->repetitions,
                     "Seconds each library runs per repetition, at least");
  fuzzy->add_option("--filter", options->filter,
                    "Only engines whose name (folder/name) contains this text");
  fuzzy->callback([options]() { run_fuzzy_benchmark(*options); });
}

}  // namespace fuzzygait::bench
