// The compiled, read-only form of an Engine (offline/runtime split in the manner of
// ozz-animation): flat arrays, no virtual call per membership sample, no allocation while
// evaluating, const and thread-safe. Everything that changes during evaluation lives in a
// caller-owned Workspace, one per thread or per character.
//
// Work that does not depend on the inputs is done when compiling: the output terms of integral
// defuzzifiers are sampled once over their grid, so an evaluation only applies implication and
// aggregation to stored samples, and only over the samples where the activated terms are not
// zero. Input terms are fuzzified once per evaluation, however many rules read them.
//
// Results equal fuzzylite 6's (same operations in the same order), including its statefulness:
// an output's previous value (lock-previous) and the values Function terms read carry from one
// evaluation to the next inside the Workspace, as they do inside a fuzzylite Engine.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/engine.hpp"
#include "fuzzygait/fuzzy/formula.hpp"

namespace fuzzygait::fuzzy {

class Evaluator;

// Mutable state and scratch for evaluating one Evaluator. Create it with
// Evaluator::make_workspace(); all allocation happens there.
class Workspace {
 public:
  Workspace() = default;
  // Forgets previous outputs, as fuzzylite's Engine::restart().
  void reset();

 private:
  friend class Evaluator;
  struct Activated {
    std::uint32_t term;  // global term index
    double degree;
    TNorm implication;
  };
  struct WeightedSums {  // a weighted defuzzifier's sums, accumulated as its rules fire
    double sum;
    double weights;
  };
  std::vector<double> input_values_;
  std::vector<double> output_values_;
  std::vector<double> previous_values_;
  std::vector<Activated> activated_;            // per output, a slice of capacity entries
  std::vector<std::uint32_t> activated_count_;  // per output, also of eager ones
  std::vector<WeightedSums> weighted_sums_;     // per output, eager ones
  std::vector<double> rule_degrees_;
  std::vector<std::uint32_t> heap_;
  std::vector<double> stack_;
  std::vector<double> formula_values_;
  std::vector<double> formula_stack_;
  // Fixed while rules fire: memberships of the input terms (by term index), then the values of
  // input propositions with hedges.
  std::vector<double> proposition_values_;
  std::vector<double> samples_;       // integral defuzzifiers: aggregated membership
  std::vector<double> term_samples_;  // one term sampled during evaluation (reads variables)
  std::vector<double> implied_;       // one activated term after its implication
};

class Evaluator {
 public:
  // Compiles the engine. Throws std::invalid_argument listing Engine::problems() when the
  // engine cannot be evaluated.
  explicit Evaluator(const Engine& engine);

  std::size_t input_count() const { return inputs_.size(); }
  std::size_t output_count() const { return outputs_.size(); }
  const std::string& input_name(std::size_t i) const { return inputs_[i].name; }
  const std::string& output_name(std::size_t i) const { return outputs_[i].name; }
  double input_minimum(std::size_t i) const { return inputs_[i].minimum; }
  double input_maximum(std::size_t i) const { return inputs_[i].maximum; }
  double output_minimum(std::size_t i) const { return outputs_[i].minimum; }
  double output_maximum(std::size_t i) const { return outputs_[i].maximum; }

  Workspace make_workspace() const;

  // One evaluation: inputs.size() == input_count(), outputs.size() == output_count().
  void evaluate(std::span<const double> inputs, std::span<double> outputs,
                Workspace& workspace) const;
  // Many rows, in order (state carries from row to row as in fuzzylite's FLD export):
  // `inputs` holds rows of input_count() values, `outputs` receives rows of output_count().
  void evaluate_batch(std::span<const double> inputs, std::span<double> outputs,
                      Workspace& workspace) const;

  // Membership of a variable's term at x, with the workspace's current values for terms that
  // read other variables (Linear, Function). For plots and inspection.
  double input_membership(std::size_t input, std::size_t term, double x,
                          Workspace& workspace) const;
  double output_membership(std::size_t output, std::size_t term, double x,
                           Workspace& workspace) const;
  std::size_t input_term_count(std::size_t i) const { return inputs_[i].term_count; }
  std::size_t output_term_count(std::size_t i) const { return outputs_[i].term_count; }

 private:
  struct CompiledTerm {
    TermKind kind;
    std::uint32_t variable;           // index of its input or output variable
    std::uint32_t parameters;         // offset into parameters_
    std::uint32_t count;              // number of parameters (Discrete: points)
    std::int32_t formula = -1;        // index into formulas_
    bool parameters_not_nan = false;  // allows the shortcut comparisons of the linear shapes
    // Output terms that depend on x alone are sampled once over their variable's grid:
    // offset into grid_values_, or -1 when sampled during evaluation.
    std::int32_t grid_values = -1;
    bool grid_values_finite = false;
    bool grid_values_nonnegative = false;  // finite and >= 0
    std::uint32_t grid_first = 0;          // the samples outside [grid_first, grid_last) are zero
    std::uint32_t grid_last = 0;
    double height;
  };
  struct CompiledFormula {
    FormulaProgram program;
    std::vector<std::int32_t> bindings;  // >= 0 input index, < 0: -(output + 1); kX for x
  };
  static constexpr std::int32_t kX = INT32_MIN;
  struct CompiledInput {
    std::string name;
    double minimum;
    double maximum;
    bool enabled;
    bool lock_range;
    std::uint32_t first_term;
    std::uint32_t term_count;
  };
  struct CompiledOutput {
    std::string name;
    double minimum;
    double maximum;
    bool enabled;
    bool lock_range;
    SNorm aggregation;
    Defuzzifier defuzzifier;
    double default_value;
    bool lock_previous;
    std::uint32_t first_term;
    std::uint32_t term_count;
    std::uint32_t activated_offset;  // slice of Workspace::activated_
    // A weighted defuzzifier whose terms read no output and which no rule reads: each
    // activated term adds to its sums at once (the same order), no Activated list.
    bool eager = false;
    // Integral defuzzifiers over a finite range: offset into grid_x_ of the sample positions
    // (Bisector: the grid from the left end, then the one from the right end), or -1.
    std::int32_t grid = -1;
    std::uint32_t grid_size = 0;
  };
  struct CompiledProposition {
    std::uint32_t variable;
    std::int32_t term;  // global term index; -1 for "any"
    bool output;
    bool variable_enabled;
    std::uint32_t hedges;  // offset into hedges_
    std::uint32_t hedge_count;
  };
  struct CompiledRule {
    std::uint32_t antecedent;  // offset into antecedent_
    std::uint32_t antecedent_length;
    std::uint32_t conclusions;  // offset into conclusions_ (propositions)
    std::uint32_t conclusion_count;
    bool left_deep = false;  // proposition values folded from the left: v0 v1 op v2 op ...
    double weight;
  };
  struct CompiledBlock {
    bool enabled;
    TNorm conjunction;
    SNorm disjunction;
    TNorm implication;
    Activation activation;
    std::uint32_t first_rule;
    std::uint32_t rule_count;
  };

  double membership(const CompiledTerm& term, double x, Workspace& w) const;
  double fuzzify(const CompiledTerm& term, double x, Workspace& w) const;
  double general_membership(const CompiledTerm& term, double x, Workspace& w) const;
  double linear(const CompiledTerm& term, const Workspace& w) const;
  double tsukamoto(const CompiledTerm& term, double w, double minimum, double maximum,
                   Workspace& ws) const;
  double antecedent(const CompiledRule& rule, const CompiledBlock& block, Workspace& w) const;
  double activation_degree(const CompiledRule& rule, const CompiledBlock& block,
                           Workspace& w) const;
  double hedge(const CompiledProposition& p, double degree) const;
  double proposition(const CompiledProposition& p, Workspace& w) const;
  double fuzzy_output_degree(std::uint32_t output, std::int32_t term, const Workspace& w) const;
  void trigger(const CompiledRule& rule, double degree, TNorm implication, Workspace& w) const;
  double weighted_value(const CompiledOutput& o, const CompiledTerm& term, double degree,
                        Workspace& w) const;
  void activate(const CompiledBlock& block, Workspace& w) const;
  void activate_general(const CompiledBlock& block, Workspace& w) const;
  void defuzzify(std::uint32_t output, Workspace& w) const;
  double integral(const CompiledOutput& o, Workspace& w) const;
  double weighted(const CompiledOutput& o, Workspace& w) const;
  struct Aggregate {
    std::size_t first;  // mu is zero outside [first, last)
    std::size_t last;
    // The last activated term, left for the caller to fold in (see integral()), or nullptr.
    const double* deferred = nullptr;
    double deferred_degree = 0.0;
    TNorm deferred_implication = TNorm::None;
  };
  Aggregate aggregate(const CompiledOutput& o, bool defer_last, Workspace& w) const;
  void sample_grids();

  std::vector<CompiledInput> inputs_;
  std::vector<CompiledOutput> outputs_;
  std::vector<CompiledTerm> terms_;
  std::vector<double> parameters_;
  std::vector<CompiledFormula> formulas_;
  std::vector<CompiledProposition> propositions_;
  std::vector<Hedge> hedges_;
  // Antecedents in postfix: >= 0 an index into Workspace::proposition_values_, Rule::kAnd,
  // Rule::kOr, or kOutputProposition - p for the output proposition propositions_[p].
  static constexpr std::int32_t kOutputProposition = -3;
  std::vector<std::int32_t> antecedent_;
  std::vector<CompiledProposition> conclusions_;
  std::vector<CompiledRule> rules_;
  std::vector<CompiledBlock> blocks_;
  std::vector<std::uint32_t> fuzzified_terms_;      // input terms some proposition reads
  std::vector<std::uint32_t> hedged_propositions_;  // input propositions with their own slot
  std::vector<double> grid_x_;
  std::vector<double> grid_values_;
  std::size_t activated_total_ = 0;
  std::size_t stack_size_ = 1;
  std::size_t formula_values_size_ = 0;
  std::size_t formula_stack_size_ = 0;
  std::size_t max_block_rules_ = 0;
  std::size_t max_grid_size_ = 0;
};

}  // namespace fuzzygait::fuzzy
