// A linguistic term of a fuzzy variable ("start", "fast", ...): its name, shape and parameters.
// This is the editable model; evaluation goes through the compiled Evaluator.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fuzzygait::fuzzy {

enum class TermKind : std::uint8_t {
  Bell,
  Binary,
  Concave,
  Constant,
  Cosine,
  Discrete,
  Function,
  Gaussian,
  GaussianProduct,
  Linear,
  PiShape,
  Ramp,
  Rectangle,
  SShape,
  Sigmoid,
  SigmoidDifference,
  SigmoidProduct,
  Spike,
  Trapezoid,
  Triangle,
  ZShape,
};

inline constexpr int kTermKindCount = 21;

struct TermShapeInfo {
  TermKind kind;
  std::string_view name;  // FLL class name
  int parameter_count;    // fixed count, or -1 (Discrete, Linear, Function)
  bool has_height;        // accepts a trailing height parameter
  bool monotonic;         // usable by Tsukamoto inference
  std::span<const std::string_view> parameter_names;
};

const TermShapeInfo& shape_info(TermKind kind);
std::optional<TermKind> term_kind_from_name(std::string_view name);

struct Term {
  std::string name;
  TermKind kind = TermKind::Triangle;
  // Shape parameters in FLL order. Discrete: x0 y0 x1 y1 ... (sorted by x).
  // Linear: one coefficient per input variable, then an optional constant. Constant: the value.
  std::vector<double> parameters;
  double height = 1.0;  // scales the membership; unused by Constant, Linear and Function
  std::string formula;  // Function only, in fuzzylite's formula language

  // FLL parameter text ("0.5 1 1.5", a formula, ...), shortest exact decimal form.
  std::string parameter_text() const;
  bool operator==(const Term& other) const;  // NaN equals NaN
};

// How messages name parameter i of `term`: "'vertexB'" for shapes of a fixed parameter count,
// its position ("4") for Discrete and Linear.
std::string parameter_label(const Term& term, std::size_t i);
// Empty when the points of a Triangle, Trapezoid, PiShape or Rectangle are in order (each at or
// after the one before); otherwise a sentence naming the term and the first pair out of order
// ("term 'center' (Triangle): 'vertexB' 5 is past 'vertexC' 1.29; its points must be in
// order"). fuzzylite reads such a term, which is then not the shape its name says (a triangle
// 0.9 5 1.29 never reaches 0.1). Other shapes are always in order here.
std::string points_out_of_order(const Term& term);
// The constants written in a Function term's formula, in order; none for other shapes.
std::vector<double> formula_constants(const Term& term);

// Builds a term from its FLL parameter text; throws std::invalid_argument with a message that
// names the term and the offending parameter.
Term make_term(std::string name, TermKind kind, std::string_view parameter_text);

// Shortest decimal text that reads back to exactly the same double, -0 included ("-0": a
// zero's sign can decide a division's infinity); "nan", "inf", "-inf".
std::string format_scalar(double value);
// Parses a scalar as fuzzylite does (decimal, "nan", "inf", "-inf"); nullopt when not a number.
std::optional<double> parse_scalar(std::string_view text);

}  // namespace fuzzygait::fuzzy
