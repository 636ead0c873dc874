// `fuzzygait fuzzy ...`: evaluate, check and export fuzzylite FLL engines.
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "commands.hpp"
#include "fuzzygait/fuzzy/evaluator.hpp"
#include "fuzzygait/fuzzy/fld.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/fuzzy/partition.hpp"
#include "fuzzygait/io/files.hpp"

namespace fuzzygait::cli {
namespace {

using namespace fuzzygait::fuzzy;

struct InputOptions {
  std::string engine_path;
  std::string data_path;
  int grid = 0;
};

// The rows to evaluate: from --data (columns matched to inputs by name, or by position when
// the table has no header) or a --grid of N points per input across its range.
std::vector<double> input_rows(const Engine& engine, const InputOptions& options) {
  const std::size_t n = engine.inputs.size();
  std::vector<double> rows;
  if (!options.data_path.empty()) {
    Table table;
    if (options.data_path == "-") {
      table = read_fld_stream(std::cin, "<stdin>");
    } else {
      std::ifstream in = open_or_throw(options.data_path);
      table = read_fld_stream(in, options.data_path);
    }
    const bool named = !table.columns.empty() && !table.columns.front().empty();
    std::vector<std::size_t> column(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (named) {
        const int c = table.column(engine.inputs[i].name);
        if (c < 0) {
          throw std::runtime_error(options.data_path + ": no column for input variable '" +
                                   engine.inputs[i].name + "'");
        }
        column[i] = static_cast<std::size_t>(c);
      } else {
        if (i >= table.columns.size()) {
          throw std::runtime_error(options.data_path + ": " + std::to_string(n) +
                                   " input columns expected, found " +
                                   std::to_string(table.columns.size()));
        }
        column[i] = i;
      }
    }
    rows.reserve(table.rows.size() * n);
    for (const std::vector<double>& row : table.rows) {
      for (std::size_t i = 0; i < n; ++i)
        rows.push_back(row[column[i]]);
    }
    return rows;
  }
  const int points = options.grid > 0 ? options.grid : 11;
  if (points < 1) throw std::runtime_error("--grid must be at least 1");
  std::size_t total = 1;
  for (const InputVariable& v : engine.inputs) {
    if (!std::isfinite(v.minimum) || !std::isfinite(v.maximum)) {
      throw std::runtime_error("input variable '" + v.name +
                               "' has no finite range; give --data instead of --grid");
    }
    total *= static_cast<std::size_t>(points);
    if (total > 10'000'000) throw std::runtime_error("--grid gives more than 10 million rows");
  }
  std::vector<int> index(n, 0);
  for (std::size_t r = 0; r < total; ++r) {
    for (std::size_t i = 0; i < n; ++i) {
      const InputVariable& v = engine.inputs[i];
      const double t = points == 1 ? 0.0 : static_cast<double>(index[i]) / (points - 1);
      rows.push_back(v.minimum + t * (v.maximum - v.minimum));
    }
    for (std::size_t i = n; i-- > 0;) {  // last input varies fastest, like fuzzylite
      if (++index[i] < points) break;
      index[i] = 0;
    }
  }
  return rows;
}

Table evaluate_table(const Engine& engine, const InputOptions& options) {
  const Evaluator evaluator(engine);
  Workspace workspace = evaluator.make_workspace();
  const std::vector<double> inputs = input_rows(engine, options);
  const std::size_t n_in = engine.inputs.size();
  const std::size_t n_out = engine.outputs.size();
  const std::size_t rows = n_in ? inputs.size() / n_in : 0;
  std::vector<double> outputs(rows * n_out);
  evaluator.evaluate_batch(inputs, outputs, workspace);
  Table table;
  for (const InputVariable& v : engine.inputs)
    table.columns.push_back(v.name);
  for (const OutputVariable& v : engine.outputs)
    table.columns.push_back(v.name);
  table.rows.reserve(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    std::vector<double> row(inputs.begin() + static_cast<std::ptrdiff_t>(r * n_in),
                            inputs.begin() + static_cast<std::ptrdiff_t>((r + 1) * n_in));
    row.insert(row.end(), outputs.begin() + static_cast<std::ptrdiff_t>(r * n_out),
               outputs.begin() + static_cast<std::ptrdiff_t>((r + 1) * n_out));
    table.rows.push_back(std::move(row));
  }
  return table;
}

void print_summary(const Engine& engine, std::ostream& out) {
  out << "engine: " << (engine.name.empty() ? "(unnamed)" : engine.name) << "\n";
  out << "type: " << name(engine.type()) << "\n";
  auto terms = [&out](const std::vector<Term>& list) {
    for (const Term& t : list) {
      out << "    " << t.name << ": " << shape_info(t.kind).name << " " << t.parameter_text()
          << "\n";
    }
  };
  out << "inputs: " << engine.inputs.size() << "\n";
  for (const InputVariable& v : engine.inputs) {
    out << "  " << v.name << " [" << format_scalar(v.minimum) << ", " << format_scalar(v.maximum)
        << "]" << (v.enabled ? "" : " (disabled)") << ", " << v.terms.size() << " terms\n";
    terms(v.terms);
  }
  out << "outputs: " << engine.outputs.size() << "\n";
  for (const OutputVariable& v : engine.outputs) {
    out << "  " << v.name << " [" << format_scalar(v.minimum) << ", " << format_scalar(v.maximum)
        << "]" << (v.enabled ? "" : " (disabled)") << ", defuzzifier ";
    if (v.defuzzifier) {
      out << name(v.defuzzifier->kind) << " "
          << (v.defuzzifier->is_integral() ? std::to_string(v.defuzzifier->resolution)
                                           : std::string(name(v.defuzzifier->type)));
    } else {
      out << "none";
    }
    out << ", aggregation " << name(v.aggregation) << ", " << v.terms.size() << " terms\n";
    terms(v.terms);
  }
  std::size_t rules = 0;
  for (const RuleBlock& b : engine.rule_blocks)
    rules += b.rules.size();
  out << "rule blocks: " << engine.rule_blocks.size() << ", rules: " << rules << "\n";
  for (const RuleBlock& b : engine.rule_blocks) {
    out << "  " << (b.name.empty() ? "(unnamed)" : b.name) << ": conjunction "
        << name(b.conjunction) << ", disjunction " << name(b.disjunction) << ", implication "
        << name(b.implication) << ", activation " << b.activation.text()
        << (b.enabled ? "" : " (disabled)") << "\n";
    for (const Rule& r : b.rules)
      out << "    " << r.text() << "\n";
  }
}

void add_input_options(CLI::App& command, InputOptions& options) {
  command.add_option("--data", options.data_path,
                     "FLD table of input values (columns matched by name; '-' reads stdin)");
  command
      .add_option("--grid", options.grid,
                  "Evaluate N points per input across its range (default 11)")
      ->check(CLI::PositiveNumber);
}

}  // namespace

void add_fuzzy_command(CLI::App& app) {
  CLI::App* fuzzy =
      app.add_subcommand("fuzzy", "Evaluate, check, export and plot fuzzylite FLL engines");
  fuzzy->require_subcommand(1);

  auto eval_options = std::make_shared<InputOptions>();
  CLI::App* eval = fuzzy->add_subcommand("eval", "Evaluate an engine; print an FLD table");
  eval->add_option("engine", eval_options->engine_path, "Engine in FLL")->required();
  add_input_options(*eval, *eval_options);
  eval->callback([eval_options]() {
    const Engine engine = read_fll_file(eval_options->engine_path);
    write_fld(std::cout, evaluate_table(engine, *eval_options));
  });

  auto check_path = std::make_shared<std::string>();
  CLI::App* check = fuzzy->add_subcommand("check", "Validate an engine and summarise it");
  check->add_option("engine", *check_path, "Engine in FLL")->required();
  check->callback([check_path]() {
    // Stricter than the other subcommands: a term whose points are out of order is an error
    // naming its line (fuzzylite reads it, as a shape other than its name says).
    FllOptions strict;
    strict.ordered_points = true;
    const Engine engine = read_fll_file(*check_path, strict);
    print_summary(engine, std::cout);
    // Whether a walker evaluates it by its packed partition (faster than the general engine),
    // and if not, what keeps it off: a shape an author can usually fix (a rule out of order).
    std::string off_fast_path;
    std::cout << "walker fast path: "
              << (fuzzy::as_partition(engine, &off_fast_path) ? "yes"
                                                              : "no (" + off_fast_path + ")")
              << "\n";
    const std::vector<std::string> problems = engine.problems();
    if (problems.empty()) {
      std::cout << "status: ready\n";
      return;
    }
    for (const std::string& p : problems)
      std::cout << "problem: " << p << "\n";
    throw std::runtime_error(*check_path + ": " + std::to_string(problems.size()) +
                             " problem(s) stop the engine from being evaluated");
  });

  auto export_options = std::make_shared<InputOptions>();
  auto export_format = std::make_shared<std::string>("fll");
  auto export_output = std::make_shared<std::string>();
  CLI::App* exporter =
      fuzzy->add_subcommand("export", "Write an engine as normalised FLL, or its FLD table");
  exporter->add_option("engine", export_options->engine_path, "Engine in FLL")->required();
  exporter->add_option("--format", *export_format, "fll or fld")
      ->check(CLI::IsMember({"fll", "fld"}));
  exporter->add_option("-o,--output", *export_output, "Output file (default: stdout)");
  add_input_options(*exporter, *export_options);
  exporter->callback([export_options, export_format, export_output]() {
    const Engine engine = read_fll_file(export_options->engine_path);
    std::ostringstream text;
    if (*export_format == "fll") {
      text << write_fll(engine);
    } else {
      write_fld(text, evaluate_table(engine, *export_options));
    }
    if (export_output->empty()) {
      std::cout << text.str();
    } else {
      io::write_file(*export_output, text.str());
    }
  });

  add_fuzzy_plot_command(*fuzzy);
}

}  // namespace fuzzygait::cli
