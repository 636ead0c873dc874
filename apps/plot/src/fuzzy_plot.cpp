#include "fuzzygait/plot/fuzzy_plot.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzzygait/fuzzy/evaluator.hpp"

namespace fuzzygait::plot {
namespace {

using namespace fuzzygait::fuzzy;

constexpr double kCellWidth = 520.0;
constexpr double kCellHeight = 300.0;

struct Range {
  double min;
  double max;
};

bool formula_kind(TermKind kind) {
  return kind == TermKind::Linear || kind == TermKind::Function;
}

// Where the term's parameters sit on the variable's axis (for ranges and for sampling corners).
std::vector<double> term_positions(const Term& term) {
  std::vector<double> positions;
  if (term.kind == TermKind::Discrete) {
    for (std::size_t i = 0; i < term.parameters.size(); i += 2) {
      positions.push_back(term.parameters[i]);
    }
  } else if (!formula_kind(term.kind)) {
    positions = term.parameters;
  }
  std::erase_if(positions, [](double v) { return !std::isfinite(v); });
  return positions;
}

// The variable's range when finite, otherwise one that holds its terms.
Range plot_range(double minimum, double maximum, const std::vector<Term>& terms) {
  if (std::isfinite(minimum) && std::isfinite(maximum) && maximum > minimum) {
    return {minimum, maximum};
  }
  double lo = kInfinity;
  double hi = -kInfinity;
  for (const Term& t : terms) {
    for (const double p : term_positions(t)) {
      lo = std::min(lo, p);
      hi = std::max(hi, p);
    }
  }
  if (std::isfinite(minimum)) lo = minimum;
  if (std::isfinite(maximum)) hi = maximum;
  if (!(lo < hi)) {
    const double centre = std::isfinite(lo) ? lo : (std::isfinite(hi) ? hi : 0.5);
    return {centre - 0.5, centre + 0.5};
  }
  return {lo, hi};
}

// Evenly spaced samples plus each corner of the terms (and either side of it), so that kinks
// and jumps (Rectangle, Discrete, Spike) are drawn where they are.
std::vector<double> sample_positions(Range range, int samples, const std::vector<Term>& terms) {
  std::vector<double> xs;
  const int n = std::max(samples, 2);
  for (int i = 0; i < n; ++i) {
    xs.push_back(range.min + (range.max - range.min) * i / (n - 1));
  }
  const double epsilon = 1e-9 * (range.max - range.min);
  for (const Term& t : terms) {
    for (const double p : term_positions(t)) {
      for (const double x : {p - epsilon, p, p + epsilon}) {
        if (x > range.min && x < range.max) xs.push_back(x);
      }
    }
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  return xs;
}

svg::LineStyle term_style(std::size_t index) {
  static constexpr svg::Dash kDashes[] = {svg::Dash::Solid, svg::Dash::Dashed, svg::Dash::Dotted};
  return {.color = svg::palette_color(index), .width = 1.9, .dash = kDashes[(index / 7) % 3]};
}

// The middle of the highest stretch of the curve: where its name goes.
std::optional<svg::Point> peak(const std::vector<double>& xs, const std::vector<double>& ys) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < ys.size(); ++i) {
    if (std::isfinite(ys[i]) && (!best || ys[i] > ys[*best])) best = i;
  }
  if (!best) return std::nullopt;
  const double top = ys[*best];
  const double tolerance = 1e-9 * std::max(1.0, std::abs(top));
  std::size_t end = *best;
  while (end + 1 < ys.size() && std::abs(ys[end + 1] - top) <= tolerance)
    ++end;
  return svg::Point{0.5 * (xs[*best] + xs[end]), top};
}

std::string join_words(const std::vector<std::string>& words, std::string_view last) {
  std::string text;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i) text += i + 1 == words.size() ? std::string(last) : ", ";
    text += words[i];
  }
  return text;
}

std::string plural(std::size_t count, std::string_view word) {
  return std::to_string(count) + " " + std::string(word) + (count == 1 ? "" : "s");
}

// "0.5 service + 0.2 food + 3": a Linear term as the artist reads it.
std::string linear_text(const Term& term, const Engine& engine) {
  std::string text;
  const std::size_t n = engine.inputs.size();
  for (std::size_t i = 0; i < n && i < term.parameters.size(); ++i) {
    const double c = term.parameters[i];
    if (c == 0.0) continue;
    std::string factor = std::abs(c) == 1.0 ? "" : format_scalar(std::abs(c)) + " ";
    text += text.empty() ? (c < 0 ? "\xE2\x88\x92" : "") : (c < 0 ? " \xE2\x88\x92 " : " + ");
    text += factor + engine.inputs[i].name;
  }
  if (term.parameters.size() > n) {
    const double k = term.parameters[n];
    if (k != 0.0 || text.empty()) {
      if (text.empty()) {
        text = format_scalar(k);
      } else {
        text += (k < 0 ? " \xE2\x88\x92 " : " + ") + format_scalar(std::abs(k));
      }
    }
  }
  return text.empty() ? "0" : text;
}

// Stands in for a term that cannot be compiled: it draws nothing.
Term undrawable(const std::string& name) {
  Term term;
  term.name = name;
  term.kind = TermKind::Constant;
  term.parameters = {kNaN};
  return term;
}

// A Takagi-Sugeno term's value as text: "0.5 service + 3", a formula, or a number.
std::string term_value_text(const Term& term, const Engine& engine) {
  switch (term.kind) {
    case TermKind::Linear:
      return linear_text(term, engine);
    case TermKind::Function:
      return term.formula;
    case TermKind::Constant:
      return term.parameters.empty() ? "nan" : format_scalar(term.parameters[0]);
    default:
      return std::string(shape_info(term.kind).name) + " " + term.parameter_text();
  }
}

// Whether the curve misses values over more than 1 % of its range: a lone missing sample at an
// end (no rule fires exactly on the border) does not show.
bool visible_gap(const std::vector<double>& xs, const std::vector<double>& ys) {
  const double span = xs.back() - xs.front();
  std::size_t i = 0;
  while (i < ys.size()) {
    if (!std::isnan(ys[i])) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < ys.size() && std::isnan(ys[end]))
      ++end;
    const double from = i > 0 ? xs[i - 1] : xs.front();
    const double to = end < ys.size() ? xs[end] : xs.back();
    if (to - from > 0.01 * span) return true;
    i = end;
  }
  return false;
}

class EnginePlotter {
 public:
  EnginePlotter(const Engine& engine, const EnginePlotOptions& options)
      : engine_(engine),
        options_(options),
        figure_(engine.name.empty() ? "fuzzy engine" : engine.name) {}

  svg::Figure plot() {
    header();
    const std::optional<Evaluator> evaluator = make_evaluator();
    if (evaluator) {
      Workspace workspace = evaluator->make_workspace();
      for (std::size_t i = 0; i < engine_.inputs.size(); ++i)
        input_panel(*evaluator, workspace, i);
      for (std::size_t o = 0; o < engine_.outputs.size(); ++o) {
        output_panel(*evaluator, workspace, o);
      }
      if (evaluable_) {
        if (engine_.inputs.size() == 1) {
          for (std::size_t o = 0; o < engine_.outputs.size(); ++o) {
            curve_panel(*evaluator, workspace, o);
          }
        } else if (engine_.inputs.size() == 2) {
          for (std::size_t o = 0; o < engine_.outputs.size(); ++o) {
            surface_panel(*evaluator, workspace, o);
          }
        } else if (!engine_.outputs.empty()) {
          figure_.note(
              "This engine has " + plural(engine_.inputs.size(), "input") +
              ": input-output curves are drawn for engines with one input and surfaces for "
              "engines with two, so only the terms are shown.");
        }
      }
    }
    if (no_value_) {
      figure_.note(
          "Gaps in curves and grey areas in surfaces: no rule fires there and the "
          "output's default value is nan.");
    }
    rules();
    return std::move(figure_);
  }

 private:
  void header() {
    if (!engine_.description.empty()) figure_.subtitle(engine_.description);
    std::size_t rules = 0;
    for (const RuleBlock& b : engine_.rule_blocks)
      rules += b.rules.size();
    const EngineType type = engine_.type();
    figure_.subtitle(
        (type == EngineType::Unknown ? std::string("fuzzy") : std::string(name(type))) +
        " engine \xC2\xB7 " + plural(engine_.inputs.size(), "input") + " \xC2\xB7 " +
        plural(engine_.outputs.size(), "output") + " \xC2\xB7 " + plural(rules, "rule"));
    figure_.columns(options_.columns).panel_size(kCellWidth, kCellHeight);
  }

  // The engine compiled; when it cannot be evaluated, a copy without rules that still draws
  // the terms, and a note with the problems.
  std::optional<Evaluator> make_evaluator() {
    try {
      return Evaluator(engine_);
    } catch (const std::invalid_argument&) {
    }
    evaluable_ = false;
    figure_.note("Not evaluated, so only the terms are drawn: " +
                 join_words(engine_.problems(), "; ") + ".");
    Engine terms_only = engine_;
    terms_only.rule_blocks.clear();
    for (OutputVariable& v : terms_only.outputs) {
      v.defuzzifier = Defuzzifier{.kind = Defuzzifier::Kind::WeightedAverage};
      for (Term& t : v.terms) {
        if (t.kind == TermKind::Function) t = undrawable(t.name);
      }
    }
    for (InputVariable& v : terms_only.inputs) {
      for (Term& t : v.terms) {
        if (t.kind == TermKind::Function) t = undrawable(t.name);
      }
    }
    try {
      return Evaluator(terms_only);
    } catch (const std::invalid_argument&) {
      return std::nullopt;
    }
  }

  // A variable's terms get a whole row when their names would not fit side by side in a cell.
  svg::Panel& variable_panel(const std::vector<Term>& terms) {
    double names = 0.0;
    for (const Term& t : terms) {
      names += svg::text_width(t.name, 11.0) + 8.0;
    }
    const bool crowded = names > 0.8 * kCellWidth || terms.size() > 12;
    return figure_.add_panel(crowded ? options_.columns : 1);
  }

  template <class Membership>
  void draw_terms(svg::Panel& panel, Range range, const std::vector<Term>& terms,
                  Membership membership) {
    const std::vector<double> xs = sample_positions(range, options_.curve_samples, terms);
    double top = 1.0;
    for (std::size_t t = 0; t < terms.size(); ++t) {
      const Term& term = terms[t];
      const svg::LineStyle style = term_style(t);
      if (term.kind == TermKind::Constant) {
        const double value = term.parameters.empty() ? kNaN : term.parameters[0];
        if (!std::isfinite(value)) continue;
        const svg::Point stem[] = {{value, 0.0}, {value, 1.0}};
        const svg::Point dot[] = {{value, 1.0}};
        panel.line(stem, style);
        panel.line(dot, {.color = style.color,
                         .width = 0.0,
                         .marker = svg::Marker::Circle,
                         .marker_size = 7.0});
        panel.label(value, 1.0, term.name, {.color = style.color, .dy = -10.0});
        continue;
      }
      std::vector<double> ys(xs.size());
      for (std::size_t i = 0; i < xs.size(); ++i)
        ys[i] = membership(t, xs[i]);
      panel.line(xs, ys, style);
      if (const std::optional<svg::Point> p = peak(xs, ys)) {
        top = std::max(top, p->y);
        panel.label(p->x, p->y, term.name, {.color = style.color, .dy = -9.0});
      }
    }
    panel.x_range(range.min, range.max).y_range(0.0, 1.12 * top).y_label("membership");
  }

  void input_panel(const Evaluator& evaluator, Workspace& workspace, std::size_t i) {
    const InputVariable& v = engine_.inputs[i];
    svg::Panel& panel = variable_panel(v.terms);
    panel.title("input: " + v.name + (v.enabled ? "" : " (disabled)"))
        .x_label(v.description.empty() ? v.name : v.name + ": " + v.description);
    draw_terms(
        panel, plot_range(v.minimum, v.maximum, v.terms), v.terms,
        [&](std::size_t t, double x) { return evaluator.input_membership(i, t, x, workspace); });
  }

  void output_panel(const Evaluator& evaluator, Workspace& workspace, std::size_t o) {
    const OutputVariable& v = engine_.outputs[o];
    const bool formulas = std::any_of(v.terms.begin(), v.terms.end(),
                                      [](const Term& t) { return formula_kind(t.kind); });
    if (formulas && formulas_in_legend(o)) return;
    svg::Panel& panel = formulas ? figure_.add_panel() : variable_panel(v.terms);
    panel.title("output: " + v.name + (v.enabled ? "" : " (disabled)"));
    if (formulas) {
      formula_list(panel, v);
      return;
    }
    panel.x_label(v.description.empty() ? v.name : v.name + ": " + v.description);
    Range range = plot_range(v.minimum, v.maximum, v.terms);
    // Constant terms show even outside the range, and not on its edges, where the axes would
    // hide their stems.
    bool constants = false;
    for (const Term& t : v.terms) {
      if (t.kind == TermKind::Constant && !t.parameters.empty() && std::isfinite(t.parameters[0])) {
        range.min = std::min(range.min, t.parameters[0]);
        range.max = std::max(range.max, t.parameters[0]);
        constants = true;
      }
    }
    if (constants) {
      const double margin = 0.04 * (range.max - range.min);
      range = {range.min - margin, range.max + margin};
    }
    draw_terms(panel, range, v.terms, [&](std::size_t t, double x) {
      return evaluator.output_membership(o, t, x, workspace);
    });
  }

  // A few Linear and Function terms of a one-input engine are named in its curve panel's
  // legend rather than in a panel of their own.
  bool formulas_in_legend(std::size_t o) const {
    const std::vector<Term>& terms = engine_.outputs[o].terms;
    return evaluable_ && engine_.inputs.size() == 1 && terms.size() <= 4 &&
           std::all_of(terms.begin(), terms.end(), [](const Term& t) {
             return formula_kind(t.kind) || t.kind == TermKind::Constant;
           });
  }

  // Linear and Function terms depend on the inputs, not on the output's axis: they are written
  // out (and drawn against the input in the curve panel when there is one input).
  void formula_list(svg::Panel& panel, const OutputVariable& v) {
    panel.hide_axes().x_range(0.0, 1.0).y_range(0.0, 1.0);
    const double row = 17.0;
    const auto fits = static_cast<std::size_t>(std::max(1.0, (kCellHeight - 50.0) / row));
    std::size_t shown = 0;
    for (std::size_t t = 0; t < v.terms.size(); ++t) {
      const Term& term = v.terms[t];
      const std::string value = term_value_text(term, engine_);
      if (shown + 1 == fits && t + 1 < v.terms.size()) {
        panel.text(0.0, 1.0, "\xE2\x80\xA6 and " + plural(v.terms.size() - t, "more term"),
                   {.color = svg::Color{85, 85, 85},
                    .anchor = svg::Anchor::Start,
                    .dx = 4.0,
                    .dy = 6.0 + row * static_cast<double>(shown)});
        break;
      }
      panel.text(0.0, 1.0, term.name + " = " + value,
                 {.color = svg::palette_color(t),
                  .anchor = svg::Anchor::Start,
                  .dx = 4.0,
                  .dy = 6.0 + row * static_cast<double>(shown)});
      ++shown;
    }
  }

  // Evaluates every output at one input row, from a fresh state so that lock-previous and
  // Function terms do not carry values from the previous sample.
  void evaluate(const Evaluator& evaluator, Workspace& workspace, std::span<const double> inputs,
                std::vector<double>& outputs) const {
    outputs.resize(evaluator.output_count());
    workspace.reset();
    evaluator.evaluate(inputs, outputs, workspace);
  }

  void curve_panel(const Evaluator& evaluator, Workspace& workspace, std::size_t o) {
    const InputVariable& in = engine_.inputs[0];
    const OutputVariable& out = engine_.outputs[o];
    const Range range = plot_range(in.minimum, in.maximum, in.terms);
    const std::vector<double> xs = sample_positions(range, options_.curve_samples, in.terms);
    std::vector<double> ys(xs.size());
    std::vector<std::vector<double>> formula_values(out.terms.size());
    std::vector<double> outputs;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      evaluate(evaluator, workspace, std::span<const double>(&xs[i], 1), outputs);
      ys[i] = outputs[o];
      for (std::size_t t = 0; t < out.terms.size(); ++t) {
        if (formula_kind(out.terms[t].kind)) {
          formula_values[t].push_back(evaluator.output_membership(o, t, xs[i], workspace));
        }
      }
    }
    svg::Panel& panel = figure_.add_panel();
    panel.title(out.name + " against " + in.name).x_label(in.name).y_label(out.name);
    panel.x_range(range.min, range.max);

    // The output's own range when it holds the curve, so the picture keeps its scale.
    double lo = kInfinity;
    double hi = -kInfinity;
    for (const double y : ys) {
      if (std::isfinite(y)) {
        lo = std::min(lo, y);
        hi = std::max(hi, y);
      }
    }
    if (std::isfinite(out.minimum) && std::isfinite(out.maximum) && out.maximum > out.minimum) {
      lo = std::min(lo, out.minimum);
      hi = std::max(hi, out.maximum);
    }
    if (lo < hi) panel.y_range(lo - 0.04 * (hi - lo), hi + 0.04 * (hi - lo));

    bool formula_drawn = false;
    const bool named = formulas_in_legend(o);
    const auto constants = static_cast<std::size_t>(
        std::count_if(out.terms.begin(), out.terms.end(),
                      [](const Term& t) { return t.kind == TermKind::Constant; }));
    for (std::size_t t = 0; t < out.terms.size(); ++t) {
      const Term& term = out.terms[t];
      // A few constants are reference levels; many would bury the curve (their stems show them).
      if (term.kind == TermKind::Constant && !term.parameters.empty() && constants <= 5) {
        const svg::Color color = svg::palette_color(t);
        panel.horizontal_line(
            term.parameters[0],
            {.color = color, .width = 1.0, .dash = svg::Dash::Dashed, .opacity = 0.8});
        panel.label(range.max, term.parameters[0], term.name,
                    {.color = color, .anchor = svg::Anchor::End, .dx = -4.0, .dy = -8.0});
      } else if (formula_kind(term.kind)) {
        panel.line(xs, formula_values[t],
                   {.color = svg::palette_color(t),
                    .width = 1.0,
                    .dash = svg::Dash::Dashed,
                    .opacity = 0.7},
                   named           ? term.name + " = " + term_value_text(term, engine_)
                   : formula_drawn ? std::string()
                                   : "its Linear and Function terms");
        formula_drawn = true;
      }
    }
    if (visible_gap(xs, ys)) no_value_ = true;
    panel.line(xs, ys, {.color = svg::Color{34, 34, 34}, .width = 2.4},
               formula_drawn ? out.name : std::string());
  }

  void surface_panel(const Evaluator& evaluator, Workspace& workspace, std::size_t o) {
    const InputVariable& a = engine_.inputs[0];
    const InputVariable& b = engine_.inputs[1];
    const Range x = plot_range(a.minimum, a.maximum, a.terms);
    const Range y = plot_range(b.minimum, b.maximum, b.terms);
    const auto n = static_cast<std::size_t>(options_.surface_samples);
    svg::Grid grid{x.min, x.max, y.min, y.max, n, n, std::vector<double>(n * n)};
    std::vector<double> outputs;
    for (std::size_t r = 0; r < n; ++r) {
      for (std::size_t c = 0; c < n; ++c) {
        const double row[] = {grid.x(c), grid.y(r)};
        evaluate(evaluator, workspace, row, outputs);
        grid.values[r * n + c] = outputs[o];
      }
    }
    const OutputVariable& out = engine_.outputs[o];
    svg::Panel& panel = figure_.add_panel();
    panel.title(out.name + " over " + a.name + " and " + b.name)
        .x_label(a.name)
        .y_label(b.name)
        .heat_map(grid, out.name)
        .contours(grid);
    if (std::any_of(grid.values.begin(), grid.values.end(),
                    [](double v) { return std::isnan(v); })) {
      no_value_ = true;
    }
  }

  void rules() {
    constexpr std::size_t kMaxRules = 40;
    std::size_t listed = 0;
    std::size_t total = 0;
    for (const RuleBlock& block : engine_.rule_blocks) {
      const std::string prefix =
          engine_.rule_blocks.size() > 1 && !block.name.empty() ? block.name + ": " : "";
      for (const Rule& rule : block.rules) {
        ++total;
        if (listed == kMaxRules) continue;
        figure_.note("rule: " + prefix + rule.text() + (block.enabled ? "" : " (block disabled)"));
        ++listed;
      }
    }
    if (total > listed) {
      figure_.note("\xE2\x80\xA6 and " + plural(total - listed, "more rule") +
                   " (fuzzygait fuzzy check lists them all)");
    }
  }

  const Engine& engine_;
  const EnginePlotOptions& options_;
  svg::Figure figure_;
  bool evaluable_ = true;
  bool no_value_ = false;  // some output has no value somewhere
};

}  // namespace

svg::Figure plot_engine(const Engine& engine, const EnginePlotOptions& options) {
  if (options.curve_samples < 2 || options.curve_samples > 100'000) {
    throw std::invalid_argument("plot: curve samples must be between 2 and 100000");
  }
  if (options.surface_samples < 2 || options.surface_samples > 1'000) {
    throw std::invalid_argument("plot: surface samples must be between 2 and 1000 per input");
  }
  if (options.columns < 1 || options.columns > 8) {
    throw std::invalid_argument("plot: columns must be between 1 and 8");
  }
  return EnginePlotter(engine, options).plot();
}

}  // namespace fuzzygait::plot
