#include "random_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string_view>
#include <utility>

namespace fuzzygait::fuzzy::testing {

std::uint64_t Random::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double Random::unit() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

double Random::uniform(double low, double high) {
  return low + (high - low) * unit();
}

int Random::integer(int low, int high) {
  return low + static_cast<int>(index(static_cast<std::size_t>(high - low) + 1));
}

std::size_t Random::index(std::size_t size) {
  return static_cast<std::size_t>(next() % size);
}

bool Random::chance(double probability) {
  return unit() < probability;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

enum class Flavour { Mamdani, Larsen, TakagiSugeno, Tsukamoto, InverseTsukamoto, Hybrid };
constexpr std::array<std::string_view, 6> kFlavours = {
    "Mamdani", "Larsen", "TakagiSugeno", "Tsukamoto", "InverseTsukamoto", "Hybrid"};

// The 21 term shapes, in three families.
constexpr std::array<std::string_view, 3> kTakagiSugenoShapes = {"Constant", "Linear", "Function"};
constexpr std::array<std::string_view, 5> kMonotonicShapes = {"Concave", "Ramp", "Sigmoid",
                                                              "SShape", "ZShape"};
constexpr std::array<std::string_view, 13> kOtherShapes = {
    "Bell",           "Binary",    "Cosine",
    "Discrete",       "Gaussian",  "GaussianProduct",
    "PiShape",        "Rectangle", "SigmoidDifference",
    "SigmoidProduct", "Spike",     "Trapezoid",
    "Triangle"};

constexpr std::array<std::string_view, 7> kTNorms = {
    "AlgebraicProduct", "BoundedDifference", "DrasticProduct",  "EinsteinProduct",
    "HamacherProduct",  "Minimum",           "NilpotentMinimum"};
constexpr std::array<std::string_view, 9> kSNorms = {
    "AlgebraicSum", "BoundedSum",       "DrasticSum",    "EinsteinSum", "HamacherSum",
    "Maximum",      "NilpotentMaximum", "NormalizedSum", "UnboundedSum"};
constexpr std::array<std::string_view, 5> kHedges = {"not", "extremely", "seldom", "somewhat",
                                                     "very"};
constexpr std::array<std::string_view, 5> kIntegralDefuzzifiers = {
    "Centroid", "Bisector", "SmallestOfMaximum", "MeanOfMaximum", "LargestOfMaximum"};
constexpr std::array<std::string_view, 3> kWeightedTypes = {"Automatic", "TakagiSugeno",
                                                            "Tsukamoto"};
constexpr std::array<int, 7> kResolutions = {1, 10, 51, 100, 200, 333, 500};
constexpr std::array<std::string_view, 6> kComparisons = {"<", "<=", "==", "!=", ">=", ">"};

constexpr std::array<std::string_view, 22> kUnaryFunctions = {
    "acos",  "asin",  "atan", "ceil", "cos",  "cosh", "exp",  "abs",   "fabs",  "floor", "log",
    "log10", "round", "sin",  "sinh", "sqrt", "tan",  "tanh", "log1p", "acosh", "asinh", "atanh"};
constexpr std::array<std::string_view, 11> kBinaryFunctions = {
    "min", "max", "pow", "atan2", "fmod", "gt", "ge", "eq", "neq", "le", "lt"};
constexpr std::array<std::string_view, 8> kBinaryOperators = {"+", "-", "*",   "/",
                                                              "%", "^", "and", "or"};

template <class T, std::size_t N>
const T& pick(Random& random, const std::array<T, N>& items) {
  return items[random.index(N)];
}

std::string_view any_shape(Random& random) {
  std::size_t i =
      random.index(kTakagiSugenoShapes.size() + kMonotonicShapes.size() + kOtherShapes.size());
  if (i < kTakagiSugenoShapes.size()) return kTakagiSugenoShapes[i];
  i -= kTakagiSugenoShapes.size();
  if (i < kMonotonicShapes.size()) return kMonotonicShapes[i];
  return kOtherShapes[i - kMonotonicShapes.size()];
}

// A number as FLL text, with at most three decimals so that both libraries read the same
// double, and the double they read.
struct Number {
  std::string text;
  double value;
};

Number number(double value) {
  if (std::isnan(value)) return {"nan", kNaN};
  if (std::isinf(value)) return {value < 0 ? "-inf" : "inf", value};
  const long long thousandths = std::llround(value * 1000.0);
  const long long magnitude = thousandths < 0 ? -thousandths : thousandths;
  std::string text = (thousandths < 0 ? "-" : "") + std::to_string(magnitude / 1000);
  if (magnitude % 1000 != 0) {
    std::string digits = std::to_string(magnitude % 1000 + 1000).substr(1);
    while (digits.back() == '0') {
      digits.pop_back();
    }
    text += "." + digits;
  }
  return {text, std::strtod(text.c_str(), nullptr)};
}

std::string join(const std::vector<Number>& numbers) {
  std::string out;
  for (const Number& n : numbers) {
    out += (out.empty() ? "" : " ") + n.text;
  }
  return out;
}

struct Variable {
  std::string name;
  bool output = false;
  bool integral = false;  // output with an integral defuzzifier
  std::vector<std::string> terms;
};

// What a rule block needs, learnt while writing its rules.
struct BlockNeeds {
  bool conjunction = false;
  bool disjunction = false;
  bool implication = false;
};

// Writes one engine. Two random draws never share an expression (braced lists and ?: aside,
// which C++ sequences): the order of evaluating operands is unspecified, and the text must not
// depend on the compiler.
class Generator {
 public:
  explicit Generator(std::uint64_t seed) : random_(seed), seed_(seed) {}

  RandomEngine run() {
    const auto flavour = static_cast<Flavour>(random_.index(kFlavours.size()));
    flavour_ = flavour;
    feature("flavour:" + std::string(kFlavours[static_cast<std::size_t>(flavour)]));
    fll_ = "Engine: random" + std::to_string(seed_) + "\n";
    if (random_.chance(0.2)) fll_ += "description: a random engine\n";

    const int input_count = random_.integer(1, 3);
    int output_count = random_.integer(1, 3);
    if (flavour == Flavour::Hybrid) output_count = std::max(output_count, 2);
    for (int i = 0; i < input_count; ++i) {
      Variable v;
      v.name = "in" + std::to_string(i);
      inputs_.push_back(v);
    }
    for (int o = 0; o < output_count; ++o) {
      Variable v;
      v.name = "out" + std::to_string(o);
      v.output = true;
      switch (flavour) {
        case Flavour::Mamdani:
        case Flavour::Larsen:
          v.integral = true;
          break;
        case Flavour::Hybrid:
          v.integral = o < 2 ? (o == 0) : random_.chance(0.5);
          break;
        default:
          v.integral = false;
      }
      outputs_.push_back(v);
    }
    if (flavour == Flavour::Hybrid && random_.chance(0.5)) {
      std::swap(outputs_[0].integral, outputs_[1].integral);
    }

    // Usually inputs first; sometimes interleaved, so that Function terms of inputs can read
    // outputs declared before them.
    std::size_t next_input = 0;
    std::size_t next_output = 0;
    const bool interleave = random_.chance(0.3);
    if (interleave) feature("variables:interleaved");
    while (next_input < inputs_.size() || next_output < outputs_.size()) {
      const bool take_input = next_output == outputs_.size() ||
                              (next_input < inputs_.size() && (!interleave || random_.chance(0.5)));
      if (take_input) {
        input(inputs_[next_input++]);
      } else {
        output(outputs_[next_output++]);
      }
      if (random_.chance(0.05)) {
        feature("comment");
        fll_ += "# a comment line\n";
      }
    }

    const int blocks = random_.integer(1, 3);
    if (blocks > 1) feature("rule-blocks:several");
    for (int b = 0; b < blocks; ++b) {
      rule_block(b);
    }

    result_.fll = std::move(fll_);
    return std::move(result_);
  }

 private:
  void feature(std::string name) { result_.features.insert(std::move(name)); }

  void line(const std::string& key, const std::string& value) {
    fll_ += "  " + key + ": " + value + "\n";
  }

  // Optional lines are sometimes left out when they hold the default.
  void optional_line(const std::string& key, const std::string& value, bool is_default) {
    if (is_default && random_.chance(0.2)) {
      feature("omitted:" + key);
      return;
    }
    line(key, value);
  }

  void header(const Variable& v, double& minimum, double& maximum) {
    fll_ += (v.output ? "OutputVariable: " : "InputVariable: ") + v.name + "\n";
    if (random_.chance(0.1)) line("description", "variable " + v.name);
    const bool enabled = !random_.chance(0.08);
    if (!enabled) feature(v.output ? "disabled:output" : "disabled:input");
    optional_line("enabled", enabled ? "true" : "false", enabled);
    const Number low = number(random_.uniform(-5.0, 5.0));
    constexpr std::array<double, 5> kSpans = {0.5, 1.0, 2.0, 10.0, 100.0};
    const double scale = pick(random_, kSpans);
    const Number high = number(low.value + scale * random_.uniform(0.5, 1.5));
    minimum = low.value;
    maximum = high.value;
    // Terms are laid out over [minimum, maximum] either way.
    if (v.output && random_.chance(0.04)) {
      feature("range:inverted");
      line("range", high.text + " " + low.text);
    } else if (v.output && !v.integral && random_.chance(0.05)) {
      feature("range:infinite");
      line("range", "-inf inf");
    } else {
      line("range", low.text + " " + high.text);
    }
    const bool lock_range = random_.chance(0.3);
    if (lock_range) feature(v.output ? "lock-range:output" : "lock-range:input");
    optional_line("lock-range", lock_range ? "true" : "false", !lock_range);
  }

  void input(Variable& v) {
    RandomInput info;
    info.name = v.name;
    header(v, info.minimum, info.maximum);
    info.landmarks = {info.minimum, info.maximum, 0.5 * (info.minimum + info.maximum)};
    const int term_count = random_.integer(1, 5);
    for (int t = 0; t < term_count; ++t) {
      const std::string_view shape = any_shape(random_);
      feature("input-term:" + std::string(shape));
      add_term(v, shape, info.minimum, info.maximum, &info.landmarks);
    }
    declared_.push_back(v.name);
    result_.inputs.push_back(std::move(info));
  }

  void output(Variable& v) {
    double minimum = 0.0;
    double maximum = 1.0;
    header(v, minimum, maximum);
    std::string aggregation = "none";
    if (v.integral || random_.chance(0.5)) aggregation = std::string(pick(random_, kSNorms));
    feature((v.integral ? "aggregation:" : "weighted-aggregation:") + aggregation);
    if (random_.chance(0.05)) {
      feature("legacy:accumulation");
      line("accumulation", aggregation);  // fuzzylite 5's name
    } else {
      optional_line("aggregation", aggregation, aggregation == "none");
    }
    bool automatic = false;
    if (v.integral) {
      const std::string_view kind = pick(random_, kIntegralDefuzzifiers);
      feature("defuzzifier:" + std::string(kind));
      if (random_.chance(0.15)) {
        line("defuzzifier", std::string(kind));  // the default resolution, 100
      } else {
        const int resolution = pick(random_, kResolutions);
        line("defuzzifier", std::string(kind) + " " + std::to_string(resolution));
      }
    } else {
      const std::string_view kind = random_.chance(0.5) ? "WeightedAverage" : "WeightedSum";
      std::string_view type = pick(random_, kWeightedTypes);
      if (flavour_ == Flavour::TakagiSugeno && type == "Tsukamoto") type = "TakagiSugeno";
      if (flavour_ == Flavour::Tsukamoto && type == "TakagiSugeno") type = "Tsukamoto";
      feature("defuzzifier:" + std::string(kind));
      feature("weighted-type:" + std::string(type));
      automatic = type == "Automatic";
      if (type == "Automatic" && random_.chance(0.2)) {
        line("defuzzifier", std::string(kind));
      } else {
        line("defuzzifier", std::string(kind) + " " + std::string(type));
      }
    }
    Number default_value{"nan", kNaN};
    const double r = random_.unit();
    if (r < 0.4) {
      default_value = number(random_.uniform(minimum, maximum));
    } else if (r < 0.45) {
      default_value = number(maximum + (maximum - minimum));  // outside: lock-range clamps it
    } else if (r < 0.5) {
      default_value = number(random_.chance(0.5) ? kInf : -kInf);
    }
    if (!std::isnan(default_value.value)) feature("default:number");
    optional_line("default", default_value.text, std::isnan(default_value.value));
    const bool lock_previous = random_.chance(0.3);
    if (lock_previous) feature("lock-previous");
    if (random_.chance(0.05)) {
      feature("legacy:lock-valid");
      line("lock-valid", lock_previous ? "true" : "false");  // fuzzylite 5's name
    } else {
      optional_line("lock-previous", lock_previous ? "true" : "false", !lock_previous);
    }

    bool has_takagi_sugeno_term = false;
    bool has_monotonic_term = false;
    const int term_count = random_.integer(1, 5);
    for (int t = 0; t < term_count; ++t) {
      std::string_view shape;
      if (v.integral) {
        shape = any_shape(random_);
      } else if (flavour_ == Flavour::TakagiSugeno) {
        shape = pick(random_, kTakagiSugenoShapes);
      } else if (flavour_ == Flavour::Tsukamoto) {
        shape = pick(random_, kMonotonicShapes);
      } else if (flavour_ == Flavour::InverseTsukamoto && random_.chance(0.5)) {
        shape = pick(random_, kOtherShapes);
      } else {
        shape = any_shape(random_);  // weighted terms of every kind, mixed
      }
      feature("output-term:" + std::string(shape));
      add_term(v, shape, minimum, maximum, nullptr);
      const auto in = [shape](const auto& shapes) {
        return std::find(shapes.begin(), shapes.end(), shape) != shapes.end();
      };
      has_takagi_sugeno_term = has_takagi_sugeno_term || in(kTakagiSugenoShapes);
      has_monotonic_term = has_monotonic_term || in(kMonotonicShapes);
    }
    if (!v.integral && automatic && has_takagi_sugeno_term && has_monotonic_term) {
      feature("weighted:automatic-mixed");
    }
    declared_.push_back(v.name);
    result_.outputs.push_back(v.name);
  }

  void add_term(Variable& v, std::string_view shape, double minimum, double maximum,
                std::vector<double>* landmarks) {
    const std::string name = "t" + std::to_string(v.terms.size());
    v.terms.push_back(name);
    fll_ += "  term: " + name + " " + std::string(shape);
    const std::string parameters = term_parameters(shape, minimum, maximum, landmarks);
    if (!parameters.empty()) fll_ += " " + parameters;
    fll_ += "\n";
  }

  std::string term_parameters(std::string_view shape, double minimum, double maximum,
                              std::vector<double>* landmarks) {
    const double span = maximum - minimum;
    // A position around the range (a little beyond it at times), remembered as a landmark.
    auto point = [&]() {
      Number n = number(minimum + span * random_.uniform(-0.1, 1.1));
      if (landmarks) landmarks->push_back(n.value);
      return n;
    };
    auto width = [&](double low, double high) {
      return number(std::max(0.001, span * random_.uniform(low, high)));
    };
    auto slope = [&](double sign) { return number(sign * random_.uniform(2.0, 30.0) / span); };
    // Sorted positions, except in a few degenerate terms.
    auto points = [&](int count) {
      std::vector<Number> out;
      for (int i = 0; i < count; ++i) {
        out.push_back(point());
      }
      if (random_.chance(0.93)) {
        std::sort(out.begin(), out.end(),
                  [](const Number& a, const Number& b) { return a.value < b.value; });
      } else {
        feature("term:unsorted");
      }
      return out;
    };

    std::vector<Number> p;
    if (shape == "Bell") {
      p = {point(), width(0.05, 0.5), number(random_.uniform(0.5, 4.0))};
    } else if (shape == "Binary") {
      const Number start = point();
      const double r = random_.unit();
      const Number direction = r < 0.45   ? number(start.value + span)
                               : r < 0.9  ? number(start.value - span)
                               : r < 0.95 ? number(kInf)
                                          : number(-kInf);
      p = {start, direction};
    } else if (shape == "Concave") {
      p = {point(), point()};
    } else if (shape == "Constant") {
      p = {landmarks ? number(random_.uniform(-0.2, 1.2)) : point()};
    } else if (shape == "Cosine") {
      p = {point(), width(0.1, 1.0)};
    } else if (shape == "Discrete") {
      const int count = random_.integer(1, 6);
      std::vector<Number> xs;
      for (int i = 0; i < count; ++i) {
        xs.push_back(point());
      }
      if (count > 1 && random_.chance(0.1)) xs[1] = xs[0];  // a vertical step
      std::sort(xs.begin(), xs.end(),
                [](const Number& a, const Number& b) { return a.value < b.value; });
      for (const Number& x : xs) {
        p.push_back(x);
        p.push_back(number(random_.unit()));
      }
    } else if (shape == "Function") {
      return formula(random_.integer(0, 3));
    } else if (shape == "Gaussian") {
      p = {point(), width(0.05, 0.5)};
    } else if (shape == "GaussianProduct") {
      const std::vector<Number> means = points(2);
      p = {means[0], width(0.05, 0.4), means[1], width(0.05, 0.4)};
    } else if (shape == "Linear") {
      const int count = random_.integer(0, static_cast<int>(inputs_.size()) + 1);
      for (int i = 0; i < count; ++i) {
        p.push_back(number(random_.uniform(-2.0, 2.0)));
      }
    } else if (shape == "PiShape") {
      p = points(4);
    } else if (shape == "Ramp") {
      p = {point(), point()};
      if (random_.chance(0.03)) p[1] = p[0];
    } else if (shape == "Rectangle") {
      p = points(2);
    } else if (shape == "SShape" || shape == "ZShape") {
      p = points(2);
    } else if (shape == "Sigmoid") {
      p = {point(), slope(random_.chance(0.5) ? 1.0 : -1.0)};
    } else if (shape == "SigmoidDifference") {
      const std::vector<Number> sides = points(2);
      p = {sides[0], slope(1.0), slope(1.0), sides[1]};
    } else if (shape == "SigmoidProduct") {
      const std::vector<Number> sides = points(2);
      p = {sides[0], slope(1.0), slope(-1.0), sides[1]};
    } else if (shape == "Spike") {
      p = {point(), width(0.05, 0.5)};
    } else if (shape == "Trapezoid") {
      p = points(4);
      if (random_.chance(0.1)) p.front() = number(-kInf);
      if (random_.chance(0.1)) p.back() = number(kInf);
    } else if (shape == "Triangle") {
      p = points(3);
      if (random_.chance(0.1)) p.front() = number(-kInf);
      if (random_.chance(0.1)) p.back() = number(kInf);
    }
    const bool has_height = shape != "Constant" && shape != "Linear";
    if (has_height && random_.chance(0.3)) {
      feature("term:height");
      const double r = random_.unit();
      p.push_back(number(r < 0.1 ? 0.0 : r < 0.2 ? 1.5 : random_.uniform(0.1, 1.0)));
    }
    return join(p);
  }

  // A formula over x and the variables declared so far (fuzzylite resolves a Function's
  // variables when it loads the term). No negative literals: '-' is binary, '~' negates.
  std::string formula(int depth) {
    auto wrap = [this](const std::string& e) { return random_.chance(0.75) ? "(" + e + ")" : e; };
    if (depth <= 0 || random_.chance(0.2)) {
      if (random_.chance(0.6)) {
        const std::size_t choice = random_.index(declared_.size() + 1);
        if (choice == declared_.size()) {
          feature("function:reads-x");
          return "x";
        }
        const std::string& name = declared_[choice];
        feature(name.starts_with("out") ? "function:reads-output" : "function:reads-input");
        return name;
      }
      const double r = random_.unit();
      return r < 0.15 ? "0" : r < 0.25 ? "1" : number(random_.uniform(0.0, 3.0)).text;
    }
    switch (random_.index(4)) {
      case 0: {
        const std::string op = random_.chance(0.7) ? "~" : "!";
        feature("function:operator" + op);
        return op + wrap(formula(depth - 1));
      }
      case 1: {
        const std::string fn(pick(random_, kUnaryFunctions));
        feature("function:" + fn);
        return fn + "(" + formula(depth - 1) + ")";
      }
      case 2: {
        const std::string fn(pick(random_, kBinaryFunctions));
        feature("function:" + fn);
        const std::string first = formula(depth - 1);
        return fn + "(" + first + ", " + formula(depth - 1) + ")";
      }
      default: {
        const std::string op(pick(random_, kBinaryOperators));
        feature("function:operator" + op);
        const std::string left = wrap(formula(depth - 1));
        return left + " " + op + " " + wrap(formula(depth - 1));
      }
    }
  }

  std::string proposition() {
    // Blocks that reuse a few propositions get equal activation degrees: ties for Highest,
    // Lowest and Threshold ==.
    if (!shared_propositions_.empty() && random_.chance(0.7)) {
      return shared_propositions_[random_.index(shared_propositions_.size())];
    }
    const bool chained = random_.chance(0.2);
    const std::vector<Variable>& pool = chained ? outputs_ : inputs_;
    const Variable& v = pool[random_.index(pool.size())];
    if (chained) feature("antecedent:output-variable");
    std::string text = v.name + " is";
    const double r = random_.unit();
    const int hedge_count = r < 0.7 ? 0 : r < 0.9 ? 1 : 2;
    for (int h = 0; h < hedge_count; ++h) {
      const std::string hedge(pick(random_, kHedges));
      feature("hedge:" + hedge);
      text += " " + hedge;
    }
    if (random_.chance(0.05)) {
      feature("hedge:any");
      return text + " any";
    }
    return text + " " + v.terms[random_.index(v.terms.size())];
  }

  struct Expression {
    std::string text;
    bool composite = false;
  };

  Expression antecedent(int leaves, BlockNeeds& needs, bool& uses_and, bool& uses_or) {
    if (leaves == 1) return {proposition()};
    const int split = random_.integer(1, leaves - 1);
    const Expression left = antecedent(split, needs, uses_and, uses_or);
    const Expression right = antecedent(leaves - split, needs, uses_and, uses_or);
    const bool conjunction = random_.chance(0.5);
    (conjunction ? uses_and : uses_or) = true;
    (conjunction ? needs.conjunction : needs.disjunction) = true;
    // Parentheses keep the tree most of the time; without them the parser's precedence
    // (and before or, left to right) decides.
    auto wrap = [this](const Expression& e) {
      if (!e.composite || random_.chance(0.3)) return e.text;
      feature("antecedent:parentheses");
      return random_.chance(0.5) ? "(" + e.text + ")" : "( " + e.text + " )";
    };
    const std::string left_text = wrap(left);
    return {left_text + (conjunction ? " and " : " or ") + wrap(right), true};
  }

  std::string rule(BlockNeeds& needs) {
    bool uses_and = false;
    bool uses_or = false;
    std::string text =
        "if " + antecedent(random_.integer(1, 4), needs, uses_and, uses_or).text + " then ";
    if (uses_and) feature("antecedent:and");
    if (uses_or) feature("antecedent:or");
    if (uses_and && uses_or) feature("antecedent:and-or");
    std::vector<std::size_t> targets = {random_.index(outputs_.size())};
    if (random_.chance(0.25)) {
      feature("consequent:several");
      if (outputs_.size() == 1 || random_.chance(0.3)) {
        feature("consequent:same-output");
        targets.push_back(targets[0]);
      } else {
        targets.push_back((targets[0] + 1 + random_.index(outputs_.size() - 1)) % outputs_.size());
      }
    }
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const Variable& v = outputs_[targets[i]];
      if (v.integral) needs.implication = true;
      text += (i > 0 ? " and " : "") + v.name + " is ";
      if (random_.chance(0.15)) {
        const std::string hedge = random_.chance(0.1) ? "any" : std::string(pick(random_, kHedges));
        feature("consequent-hedge:" + hedge);
        text += hedge + " ";
      }
      text += v.terms[random_.index(v.terms.size())];
    }
    if (random_.chance(0.2)) {
      feature("rule:weight");
      constexpr std::array<double, 6> kWeights = {0.0, 0.25, 0.5, 0.75, 1.0, 1.5};
      const double r = random_.unit();
      const double weight = r < 0.05 ? kNaN : r < 0.5 ? pick(random_, kWeights) : random_.unit();
      text += " with " + number(weight).text;
    }
    return text;
  }

  std::string activation() {
    const double r = random_.unit();
    std::string out;
    if (r < 0.3) {
      out = "General";
    } else if (r < 0.35) {
      out = "none";
    } else if (r < 0.45) {
      out = "Proportional";
    } else if (r < 0.6) {
      out = "Threshold";
      if (random_.chance(0.85)) {
        const std::string comparison(pick(random_, kComparisons));
        feature("activation:Threshold " + comparison);
        const double value = random_.chance(0.3) ? 0.5 : random_.unit();
        out += " " + comparison + " " + number(value).text;
      }
    } else if (r < 0.8) {
      out = random_.chance(0.5) ? "First" : "Last";
      if (random_.chance(0.8)) {
        const int rules = random_.integer(0, 3);
        out += " " + std::to_string(rules) + " " +
               number(random_.chance(0.5) ? 0.0 : random_.uniform(0.0, 0.6)).text;
      }
    } else {
      out = random_.chance(0.5) ? "Highest" : "Lowest";
      out += " " + std::to_string(random_.integer(0, 3));
    }
    feature("activation:" + out.substr(0, out.find(' ')));
    return out;
  }

  void rule_block(int index) {
    BlockNeeds needs;
    std::vector<std::string> rules;
    shared_propositions_.clear();
    if (random_.chance(0.3)) {
      feature("rules:shared-propositions");
      const int shared = random_.integer(1, 3);
      for (int p = 0; p < shared; ++p) {
        shared_propositions_.push_back(proposition());
      }
    }
    const int count = random_.chance(0.03) ? 0 : random_.integer(1, 6);
    if (count == 0) feature("rules:none");
    for (int r = 0; r < count; ++r) {
      rules.push_back(rule(needs));
    }

    fll_ +=
        "RuleBlock: " + (random_.chance(0.2) ? std::string() : "b" + std::to_string(index)) + "\n";
    if (random_.chance(0.1)) line("description", "rules");
    const bool enabled = !random_.chance(0.08);
    if (!enabled) feature("disabled:rule-block");
    optional_line("enabled", enabled ? "true" : "false", enabled);
    // An operator no rule needs is sometimes left out ("none" or no line at all).
    auto tnorm = [this](bool needed, const std::string& role) {
      std::string name =
          (needed || random_.chance(0.6)) ? std::string(pick(random_, kTNorms)) : "none";
      if (role == "implication" && flavour_ == Flavour::Larsen) name = "AlgebraicProduct";
      feature(role + ":" + name);
      return name;
    };
    const std::string conjunction = tnorm(needs.conjunction, "conjunction");
    optional_line("conjunction", conjunction, conjunction == "none");
    {
      const std::string name =
          (needs.disjunction || random_.chance(0.6)) ? std::string(pick(random_, kSNorms)) : "none";
      feature("disjunction:" + name);
      optional_line("disjunction", name, name == "none");
    }
    const std::string implication = tnorm(needs.implication, "implication");
    if (implication != "none" && random_.chance(0.05)) {
      // fuzzylite 5 wrote the implication under 'activation'; the activation is then General.
      feature("legacy:activation-tnorm");
      line("activation", implication);
    } else {
      optional_line("implication", implication, implication == "none");
      const std::string method = activation();
      optional_line("activation", method, method == "General");
    }
    for (const std::string& r : rules) {
      line("rule", r);
    }
  }

  Random random_;
  std::uint64_t seed_;
  Flavour flavour_ = Flavour::Mamdani;
  std::string fll_;
  RandomEngine result_;
  std::vector<Variable> inputs_;
  std::vector<Variable> outputs_;
  std::vector<std::string> declared_;  // variable names in the order the FLL declares them
  std::vector<std::string> shared_propositions_;
};

}  // namespace

RandomEngine random_engine(std::uint64_t seed) {
  return Generator(seed).run();
}

std::vector<double> random_rows(const RandomEngine& engine, std::size_t rows, std::uint64_t seed) {
  Random random(seed);
  std::vector<double> out;
  out.reserve(rows * engine.inputs.size());
  for (std::size_t r = 0; r < rows; ++r) {
    for (const RandomInput& input : engine.inputs) {
      const double span = input.maximum - input.minimum;
      const double choice = random.unit();
      double value;
      if (choice < 0.04) {
        value = kNaN;
      } else if (choice < 0.05) {
        value = random.chance(0.5) ? kInf : -kInf;
      } else if (choice < 0.17) {
        value = input.landmarks[random.index(input.landmarks.size())];
        // Within fuzzylite's tolerance (1e-6) of the landmark, where comparisons call it equal.
        if (random.chance(0.3)) value += random.uniform(-9e-7, 9e-7);
      } else if (choice < 0.32) {
        value = random.chance(0.5) ? input.minimum - span * random.uniform(0.0, 0.5)
                                   : input.maximum + span * random.uniform(0.0, 0.5);
      } else {
        value = random.uniform(input.minimum, input.maximum);
      }
      out.push_back(value);
    }
  }
  return out;
}

}  // namespace fuzzygait::fuzzy::testing
