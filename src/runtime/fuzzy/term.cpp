#include "fuzzygait/fuzzy/term.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "fuzzygait/fuzzy/compare.hpp"
#include "fuzzygait/fuzzy/formula.hpp"
#include "runtime/common/format.hpp"
#include "text.hpp"

namespace fuzzygait::fuzzy {
namespace {

using Names = std::span<const std::string_view>;

constexpr std::string_view kBell[] = {"center", "width", "slope"};
constexpr std::string_view kBinary[] = {"start", "direction"};
constexpr std::string_view kConcave[] = {"inflection", "end"};
constexpr std::string_view kConstant[] = {"value"};
constexpr std::string_view kCosine[] = {"center", "width"};
constexpr std::string_view kDiscrete[] = {"x0", "y0", "..."};
constexpr std::string_view kFunction[] = {"formula"};
constexpr std::string_view kGaussian[] = {"mean", "standardDeviation"};
constexpr std::string_view kGaussianProduct[] = {"meanA", "standardDeviationA", "meanB",
                                                 "standardDeviationB"};
constexpr std::string_view kLinear[] = {"coefficients..."};
constexpr std::string_view kPiShape[] = {"bottomLeft", "topLeft", "topRight", "bottomRight"};
constexpr std::string_view kStartEnd[] = {"start", "end"};
constexpr std::string_view kSigmoid[] = {"inflection", "slope"};
constexpr std::string_view kSigmoidPair[] = {"left", "rising", "falling", "right"};
constexpr std::string_view kSpike[] = {"center", "width"};
constexpr std::string_view kTrapezoid[] = {"vertexA", "vertexB", "vertexC", "vertexD"};
constexpr std::string_view kTriangle[] = {"vertexA", "vertexB", "vertexC"};

// Ordered as TermKind.
const std::array<TermShapeInfo, kTermKindCount> kShapes = {{
    {TermKind::Bell, "Bell", 3, true, false, Names(kBell)},
    {TermKind::Binary, "Binary", 2, true, false, Names(kBinary)},
    {TermKind::Concave, "Concave", 2, true, true, Names(kConcave)},
    {TermKind::Constant, "Constant", 1, false, false, Names(kConstant)},
    {TermKind::Cosine, "Cosine", 2, true, false, Names(kCosine)},
    {TermKind::Discrete, "Discrete", -1, true, false, Names(kDiscrete)},
    {TermKind::Function, "Function", -1, false, false, Names(kFunction)},
    {TermKind::Gaussian, "Gaussian", 2, true, false, Names(kGaussian)},
    {TermKind::GaussianProduct, "GaussianProduct", 4, true, false, Names(kGaussianProduct)},
    {TermKind::Linear, "Linear", -1, false, false, Names(kLinear)},
    {TermKind::PiShape, "PiShape", 4, true, false, Names(kPiShape)},
    {TermKind::Ramp, "Ramp", 2, true, true, Names(kStartEnd)},
    {TermKind::Rectangle, "Rectangle", 2, true, false, Names(kStartEnd)},
    {TermKind::SShape, "SShape", 2, true, true, Names(kStartEnd)},
    {TermKind::Sigmoid, "Sigmoid", 2, true, true, Names(kSigmoid)},
    {TermKind::SigmoidDifference, "SigmoidDifference", 4, true, false, Names(kSigmoidPair)},
    {TermKind::SigmoidProduct, "SigmoidProduct", 4, true, false, Names(kSigmoidPair)},
    {TermKind::Spike, "Spike", 2, true, false, Names(kSpike)},
    {TermKind::Trapezoid, "Trapezoid", 4, true, false, Names(kTrapezoid)},
    {TermKind::Triangle, "Triangle", 3, true, false, Names(kTriangle)},
    {TermKind::ZShape, "ZShape", 2, true, true, Names(kStartEnd)},
}};

// Parameters split on spaces, tabs and carriage returns.
constexpr std::string_view kParameterSeparators = " \t\r";

std::string join_words(std::string_view text) {
  std::string out;
  for (std::string_view word : split_words(text, kParameterSeparators)) {
    if (!out.empty()) out += ' ';
    out += word;
  }
  return out;
}

}  // namespace

const TermShapeInfo& shape_info(TermKind kind) {
  return kShapes.at(static_cast<int>(kind));
}

std::optional<TermKind> term_kind_from_name(std::string_view name) {
  for (const TermShapeInfo& info : kShapes) {
    if (info.name == name) return info.kind;
  }
  return std::nullopt;
}

std::string parameter_label(const Term& term, std::size_t i) {
  const TermShapeInfo& shape = shape_info(term.kind);
  return shape.parameter_count >= 0 && i < shape.parameter_names.size()
             ? "'" + std::string(shape.parameter_names[i]) + "'"
             : std::to_string(i + 1);
}

std::string points_out_of_order(const Term& term) {
  // How many leading parameters are points along the input, in order.
  const TermKind k = term.kind;
  const std::size_t count = k == TermKind::Rectangle                               ? 2
                            : k == TermKind::Triangle                              ? 3
                            : (k == TermKind::Trapezoid || k == TermKind::PiShape) ? 4
                                                                                   : 0;
  for (std::size_t i = 1; i < count && i < term.parameters.size(); ++i) {
    if (term.parameters[i] < term.parameters[i - 1]) {
      return "term '" + term.name + "' (" + std::string(shape_info(term.kind).name) +
             "): " + parameter_label(term, i - 1) + " " + format_scalar(term.parameters[i - 1]) +
             " is past " + parameter_label(term, i) + " " + format_scalar(term.parameters[i]) +
             "; its points must be in order";
    }
  }
  return {};
}

std::vector<double> formula_constants(const Term& term) {
  std::vector<double> constants;
  if (term.kind != TermKind::Function) return constants;
  for (const FormulaInstruction& i : compile_formula(term.formula).code) {
    if (i.kind == FormulaInstruction::Kind::Constant) constants.push_back(i.value);
  }
  return constants;
}

std::string format_scalar(double value) {
  return common::number_text(value);
}

std::optional<double> parse_scalar(std::string_view text) {
  if (text == "nan") return std::nan("");
  if (text == "inf") return HUGE_VAL;
  if (text == "-inf") return -HUGE_VAL;
  if (text.empty()) return std::nullopt;
  std::string_view digits = text;
  if (digits.front() == '+') digits.remove_prefix(1);
  if (digits.empty() || digits.front() == '+') return std::nullopt;
  // std::from_chars also reads "infinity" and "nan(...)": fuzzylite does not, so neither do we.
  for (char c : digits) {
    const bool ok =
        (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '-' || c == '+';
    if (!ok) return std::nullopt;
  }
  double value = 0.0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value,
                                      std::chars_format::general);
  if (result.ec != std::errc() || result.ptr != digits.data() + digits.size()) {
    return std::nullopt;
  }
  return value;
}

bool Term::operator==(const Term& other) const {
  if (name != other.name || kind != other.kind || formula != other.formula) return false;
  if (!is_same_value(height, other.height) || parameters.size() != other.parameters.size())
    return false;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (!is_same_value(parameters[i], other.parameters[i])) return false;
  }
  return true;
}

std::string Term::parameter_text() const {
  if (kind == TermKind::Function) return formula;
  std::string out;
  for (double p : parameters) {
    if (!out.empty()) out += ' ';
    out += format_scalar(p);
  }
  const TermShapeInfo& info = shape_info(kind);
  if (info.has_height && !(height == 1.0)) {
    if (!out.empty()) out += ' ';
    out += format_scalar(height);
  }
  return out;
}

Term make_term(std::string name, TermKind kind, std::string_view parameter_text) {
  const TermShapeInfo& info = shape_info(kind);
  const std::string label = "term '" + name + "' (" + std::string(info.name) + ")";
  Term term;
  term.name = std::move(name);
  term.kind = kind;
  if (kind == TermKind::Function) {
    term.formula = join_words(parameter_text);
    if (term.formula.empty()) throw std::invalid_argument(label + ": the formula is empty");
    try {
      compile_formula(term.formula);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(label + ": " + error.what());
    }
    return term;
  }
  std::vector<double> values;
  for (std::string_view word : split_words(parameter_text, kParameterSeparators)) {
    const std::optional<double> value = parse_scalar(word);
    if (!value) {
      throw std::invalid_argument(label + ": parameter " + std::to_string(values.size() + 1) +
                                  " '" + std::string(word) + "' is not a number");
    }
    values.push_back(*value);
  }
  auto describe = [&info]() {
    std::string names;
    for (std::string_view n : info.parameter_names) {
      names += names.empty() ? "" : " ";
      names += n;
    }
    return names;
  };
  switch (kind) {
    case TermKind::Linear:
      term.parameters = std::move(values);
      return term;
    case TermKind::Discrete: {
      if (values.size() < 2) {
        throw std::invalid_argument(label + ": needs at least one point 'x y', found " +
                                    std::to_string(values.size()) + " values");
      }
      if (values.size() % 2 == 1) {
        term.height = values.back();
        values.pop_back();
      }
      for (std::size_t i = 0; i < values.size(); i += 2) {
        // Every x, a lone point's too: the shape's binary search needs ordered coordinates.
        if (std::isnan(values[i])) {
          throw std::invalid_argument(label + ": x" + std::to_string(i / 2) +
                                      " is nan; point x coordinates must be numbers");
        }
        if (i >= 2 && values[i] < values[i - 2]) {
          throw std::invalid_argument(label + ": points must be sorted by x, but x" +
                                      std::to_string(i / 2) + " = " + format_scalar(values[i]) +
                                      " comes after " + format_scalar(values[i - 2]));
        }
      }
      term.parameters = std::move(values);
      return term;
    }
    default:
      break;
  }
  const auto required = static_cast<std::size_t>(info.parameter_count);
  const std::size_t allowed = required + (info.has_height ? 1 : 0);
  if (values.size() < required || values.size() > allowed) {
    throw std::invalid_argument(label + ": needs " + std::to_string(required) + " parameters (" +
                                describe() + ")" +
                                (info.has_height ? " and an optional height" : "") + ", found " +
                                std::to_string(values.size()));
  }
  if (values.size() > required) {
    term.height = values.back();
    values.pop_back();
  }
  term.parameters = std::move(values);
  return term;
}

}  // namespace fuzzygait::fuzzy
