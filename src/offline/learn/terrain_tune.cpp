#include "fuzzygait/learn/terrain_tune.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/io/terrain_spec.hpp"
#include "fuzzygait/learn/cmaes.hpp"
#include "fuzzygait/learn/tune.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::learn {
namespace {

using common::number_text;

double round_significant(double v, int digits) {
  if (v == 0.0 || !std::isfinite(v)) return v;
  const double scale =
      std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::abs(v)))));
  return std::round(v * scale) / scale;
}

// How far a value lies outside a range (0 inside; NaN counts as 0: no figure, no price).
double outside(double value, Range r) {
  if (std::isnan(value)) return 0.0;
  return std::max(0.0, r.min - value) + std::max(0.0, value - r.max);
}

std::size_t word_index(const gait::ControllerSet::GroundWords& g, const std::string& word) {
  const auto w = std::find(g.words.begin(), g.words.end(), word);
  return static_cast<std::size_t>(w - g.words.begin());
}

// The tuned values: each word's files' output constants and inner delta knots, and its landing
// knee.
class WordParameters {
 public:
  WordParameters(const gait::ControllerSet& base, const std::vector<TerrainWord>& words)
      : base_(base) {
    for (const TerrainWord& tw : words) {
      const auto g = static_cast<std::size_t>(tw.ground);
      const std::size_t w = word_index(base.ground[g], tw.word);
      for (std::size_t s = 0; s < static_cast<std::size_t>(gait::kSlotCount); ++s) {
        const int c = base.ground[g].of_slot[s][w];
        if (c < 0) continue;
        const auto ci = static_cast<std::size_t>(c);
        const fuzzy::Engine& e = base.terrain_controllers[ci].engine();
        const bool hip = s % 4 == static_cast<std::size_t>(gait::Joint::Hip);
        for (std::size_t t = 0; t < e.outputs.at(0).terms.size(); ++t) {
          if (e.outputs[0].terms[t].kind != fuzzy::TermKind::Constant) continue;
          values_.push_back({Kind::Constant, ci, t, 0, hip ? 2.0 : 200.0});
        }
        for (std::size_t i = 0; i < e.inputs.size(); ++i) {
          if (e.inputs[i].name != "delta" && e.inputs[i].name != "other_delta") continue;
          for (std::size_t k = 1; k + 1 < e.inputs[i].terms.size(); ++k) {
            values_.push_back(
                {Kind::Knot, ci, i, k, 0.15 * (e.inputs[i].maximum - e.inputs[i].minimum)});
          }
        }
      }
      values_.push_back({Kind::LandingKnee, g, w, 0, 0.5});
    }
  }

  std::vector<double> start() const {
    std::vector<double> x;
    for (const Value& v : values_)
      x.push_back(read(v) / v.scale);
    return x;
  }

  gait::ControllerSet apply(const std::vector<double>& x, int digits = 0) const {
    gait::ControllerSet set = base_;
    std::vector<fuzzy::Engine> engines;
    for (const gait::Controller& c : base_.terrain_controllers)
      engines.push_back(c.engine());
    for (std::size_t i = 0; i < values_.size(); ++i) {
      const Value& v = values_[i];
      double value = x[i] * v.scale;
      if (digits > 0) value = round_significant(value, digits);
      if (v.kind == Kind::LandingKnee) {
        set.ground[v.a].landing_knee[v.b] = std::clamp(value, 0.0, rig::radians(90.0));
        continue;
      }
      fuzzy::Engine& e = engines[v.a];
      if (v.kind == Kind::Constant) {
        e.outputs[0].terms[v.b].parameters[0] = value;
        continue;
      }
      // A knot stays between its neighbours, the peak of its term and the feet of theirs.
      fuzzy::InputVariable& in = e.inputs[v.b];
      const double gap = 0.02 * (in.maximum - in.minimum);
      const double low = in.terms[v.c - 1].parameters[1] + gap;
      const double high = in.terms[v.c + 1].parameters[1] - gap;
      const double at = std::clamp(value, low, std::max(low, high));
      in.terms[v.c].parameters[1] = at;
      in.terms[v.c - 1].parameters[2] = at;
      in.terms[v.c + 1].parameters[0] = at;
    }
    set.terrain_controllers.clear();
    for (std::size_t c = 0; c < engines.size(); ++c) {
      set.terrain_controllers.emplace_back(std::move(engines[c]),
                                           base_.terrain_controllers[c].source());
    }
    return set;
  }

  std::size_t size() const { return values_.size(); }

 private:
  enum class Kind { Constant, Knot, LandingKnee };
  struct Value {
    Kind kind;
    std::size_t a;  // controller (Constant, Knot) or ground (LandingKnee)
    std::size_t b;  // term (Constant), input (Knot) or word (LandingKnee)
    std::size_t c;  // the knot's term
    double scale;
  };
  double read(const Value& v) const {
    if (v.kind == Kind::LandingKnee) return base_.ground[v.a].landing_knee[v.b];
    const fuzzy::Engine& e = base_.terrain_controllers[v.a].engine();
    return v.kind == Kind::Constant ? e.outputs[0].terms[v.b].parameters[0]
                                    : e.inputs[v.b].terms[v.c].parameters[1];
  }
  gait::ControllerSet base_;
  std::vector<Value> values_;
};

}  // namespace

// The condition's step, or the set's shortest where that is longer (a style that does not walk
// the preset's step walks its own shortest, 1 % longer).
double condition_step(const gait::ControllerSet& set, const TerrainCondition& c) {
  const double shortest =
      gait::Walker::min_step_length(set, rig::segments_from_stature(c.stature)) * 1.01;
  return std::max(c.step_length, shortest);
}

namespace {

double condition_cost(const gait::ControllerSet& set, const TerrainCondition& c,
                      const TerrainTuneOptions& o, std::string* report) {
  const TerrainWeights& wt = o.weights;
  const terrain::Terrain ground = io::terrain_from_spec(c.terrain);
  gait::WalkerOptions options;
  options.segments = rig::segments_from_stature(c.stature);
  options.step_length = condition_step(set, c);
  double cost = 0.0;
  try {
    gait::Walker walker(set, options, ground);
    const eval::Motion motion = eval::record(walker, c.seconds, o.fps);
    const eval::TerrainReport r = eval::evaluate_terrain(motion, ground);
    if (r.nan_frames > 0) return wt.nan_walk;
    // How far the walk got, on ground that ends level (stairs and their landing): its last
    // foothold's height against the landing's. (A ramp goes on for ever.)
    const std::vector<terrain::Point>& points = ground.points();
    const bool ends = points[points.size() - 2].y == points.back().y;
    const double total = ends ? points.back().y - ground.height(0.0) : 0.0;
    const double walked = r.steps.empty() ? 0.0 : r.steps.back().height - ground.height(0.0);
    const double missing =
        ends ? std::max(0.0, std::abs(total) - (total >= 0.0 ? walked : -walked)) : 0.0;
    cost += wt.missing_height * missing;
    for (const eval::PointContact& p : r.points) {
      cost += wt.contact * (std::max(0.0, 1000.0 * p.max_slip - 1.0) +
                            std::max(0.0, 1000.0 * p.max_penetration - 1.0));
    }
    if (!std::isnan(r.min_swing_clearance)) {
      cost += wt.clearance * std::max(0.0, 10.0 - 1000.0 * r.min_swing_clearance);
    }
    double across = 0.0;
    for (const eval::TerrainStep& s : r.steps) {
      if (!std::isnan(s.edge_foot)) across = std::max(across, -1000.0 * s.edge_foot);
    }
    cost += wt.edge_across * across;
    double pop = 0.0;
    for (std::size_t i = 1; i < motion.frames.size(); ++i) {
      const rig::Point a = motion.frames[i - 1].pose.pelvis;
      const rig::Point b = motion.frames[i].pose.pelvis;
      pop = std::max(pop, std::hypot(b.x - a.x, b.y - a.y));
    }
    cost += wt.pop * std::max(0.0, 1000.0 * pop - 80.0);
    // A walk that stops (a foot waiting for ground it never gets) is priced whatever the bounds
    // say of the steps it made before.
    const std::size_t window = static_cast<std::size_t>(std::lround(2.0 * o.fps));
    const double least = 2.0 * options.step_length * 30.0 / 60.0;
    double stalled = 0.0;
    for (std::size_t i = window; i + window < motion.frames.size(); i += window) {
      const double moved = motion.frames[i + window].pose.pelvis.x - motion.frames[i].pose.pelvis.x;
      stalled += std::max(0.0, least - moved);
    }
    cost += wt.stall * stalled;
    const TerrainBounds& b = c.bounds;
    const LevelReference level = c.level ? *c.level : level_reference(set, c, o.fps);
    const bool ramp = b.footing == eval::Footing::RampUp || b.footing == eval::Footing::RampDown;
    bool measured = false;
    for (const eval::TerrainGroup& g : r.groups) {
      if (g.footing != b.footing || (ramp && g.degrees != b.ramp_degrees)) continue;
      measured = true;
      auto price = [&](const eval::Stat& s, Range range) {
        if (s.count == 0) return;
        cost += wt.bound * outside(s.mean, range) +
                wt.bound_range * (outside(s.min, range) + outside(s.max, range));
      };
      price(g.stance_percent, b.stance_percent);
      price(g.hip, b.hip);
      price(g.knee, b.knee);
      price(g.peak_swing_knee, b.peak_swing_knee);
      price(g.peak_swing_hip, b.peak_swing_hip);
      price(g.knee_at_toe_off, b.knee_at_toe_off);
      price(g.hip_range, b.hip_range);
      price(g.cadence, b.cadence);
      cost += wt.bound * outside(g.toe_down_vs_level, b.toe_down_vs_level);
      price(g.mid_stance_sole, b.mid_stance_sole);
      if (g.step_length.count > 0) {
        cost += wt.bound * outside(100.0 * (g.step_length.mean / options.step_length - 1.0),
                                   b.step_error_percent);
      }
      if (ramp) {
        // Shifts from the level walk, per degree of slope.
        const double per = 1.0 / b.ramp_degrees;
        cost += wt.bound *
                (outside((g.hip.mean - level.hip) * per, b.hip_per_degree) +
                 outside((g.knee.mean - level.knee) * per, b.knee_per_degree) +
                 outside((g.mid_stance_ankle.mean - level.mid_stance_ankle) * per,
                         b.mid_stance_ankle_per_degree) +
                 outside((g.early_stance_knee.mean - level.early_stance_knee) * per,
                         b.early_stance_knee_per_degree)) *
                std::abs(b.ramp_degrees);
      }
    }
    // No steps on the ground the condition is for: the walk never got there.
    if (!measured) cost += wt.missing_height;
    if (report) {
      char line[300];
      std::snprintf(
          line, sizeof line,
          "%s at %.2f m, %.2f m steps: cost %.1f (missing %.2f m, stalled %.2f m, pop %.0f "
          "mm, foot across an edge %.1f mm)\n",
          c.terrain.c_str(), c.stature, options.step_length, cost, missing, stalled, 1000.0 * pop,
          across);
      *report += line;
    }
  } catch (const std::exception& e) {
    if (report) *report += c.terrain + ": not walked: " + e.what() + "\n";
    return wt.nan_walk;
  }
  return cost;
}

}  // namespace

TerrainBounds stair_ascent_bounds() {
  return {};
}

TerrainBounds ramp_bounds(int degrees) {
  constexpr double kAny = 1e9;
  TerrainBounds b;
  b.footing = degrees >= 0 ? eval::Footing::RampUp : eval::Footing::RampDown;
  b.ramp_degrees = degrees;
  b.stance_percent = {55.0, 68.0};
  b.hip = b.knee = b.peak_swing_knee = b.peak_swing_hip = {-kAny, kAny};
  b.toe_down_vs_level = {-kAny, kAny};
  b.cadence = {85.0, 130.0};
  b.mid_stance_sole = {-5.0, 5.0};
  b.step_error_percent = {-5.0, 5.0};
  if (degrees > 0) {
    b.hip_per_degree = {0.5, 1.5};
    b.knee_per_degree = {0.5, 1.5};
    b.mid_stance_ankle_per_degree = {0.6, 1.4};
  } else {
    // Per degree of a negative slope: the hip less flexed (a positive ratio), the early knee more
    // (a negative one).
    b.hip_per_degree = {0.1, 1.5};
    b.early_stance_knee_per_degree = {-1.5, -0.1};
  }
  return b;
}

LevelReference level_reference(const gait::ControllerSet& set, const TerrainCondition& c,
                               double fps) {
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::WalkerOptions options;
  options.segments = rig::segments_from_stature(c.stature);
  options.step_length = condition_step(set, c);
  gait::Walker walker(set, options, flat);
  const eval::TerrainReport r = eval::evaluate_terrain(eval::record(walker, 8.0, fps), flat);
  LevelReference level;
  for (const eval::TerrainGroup& g : r.groups) {
    if (g.footing != eval::Footing::Level) continue;
    level = {g.hip.mean, g.knee.mean, g.mid_stance_ankle.mean, g.early_stance_knee.mean};
  }
  return level;
}

TerrainBounds stair_descent_bounds() {
  TerrainBounds b;
  b.footing = eval::Footing::StairDown;
  b.stance_percent = {62.0, 76.0};
  b.hip = {-1e9, 1e9};
  b.knee = {5.0, 25.0};
  b.peak_swing_knee = {85.0, 110.0};
  b.peak_swing_hip = {-1e9, 1e9};
  b.knee_at_toe_off = {80.0, 1e9};
  b.hip_range = {20.0, 40.0};
  b.toe_down_vs_level = {25.0, 45.0};
  b.cadence = {65.0, 110.0};
  return b;
}

void validate(const TerrainTuneOptions& o, const gait::ControllerSet& set) {
  auto within = [](const std::string& field, double value, double low, double high) {
    if (!(value >= low && value <= high)) {
      throw std::invalid_argument("tune-terrain: " + field + " must be between " +
                                  number_text(low) + " and " + number_text(high) + ", got " +
                                  number_text(value));
    }
  };
  if (o.conditions.empty()) throw std::invalid_argument("tune-terrain: no terrain to walk");
  if (o.words.empty()) throw std::invalid_argument("tune-terrain: no terrain word to tune");
  for (const TerrainCondition& c : o.conditions) {
    io::terrain_from_spec(c.terrain);  // throws naming the part
    within("stature", c.stature, 0.5, 3.0);
    within("seconds", c.seconds, 1.0, 600.0);
  }
  for (const TerrainWord& w : o.words) {
    const gait::ControllerSet::GroundWords& g = set.ground[static_cast<std::size_t>(w.ground)];
    const std::size_t i = word_index(g, w.word);
    if (i == g.words.size()) {
      throw std::invalid_argument("tune-terrain: the set has no word '" + w.word +
                                  "' for that ground");
    }
  }
  within("fps", o.fps, 10.0, 2000.0);
  within("generations", o.generations, 1, 1e6);
  within("digits", o.digits, 1, 17);
  within("threads", o.threads, 1, 1024);
  within("sigma", o.sigma, 1e-9, 10.0);
}

double terrain_word_penalty(const gait::ControllerSet& set) {
  // word_penalty() reads a set's controllers: a set holding the terrain words' in their place.
  gait::ControllerSet words;
  words.controllers = set.terrain_controllers;
  return word_penalty(words);
}

double terrain_cost(const gait::ControllerSet& set, const TerrainTuneOptions& options,
                    std::string* report) {
  const double words = terrain_word_penalty(set);
  double cost = options.weights.words * words;
  if (report && words > 0.0) {
    *report += "terrain words' broken promises: " + common::number_text(words, 3) + "\n";
  }
  for (const TerrainCondition& c : options.conditions)
    cost += condition_cost(set, c, options, report);
  return cost;
}

TerrainTuneResult tune_terrain(const gait::ControllerSet& start,
                               const TerrainTuneOptions& options) {
  validate(options, start);
  // The level walks do not change with the terrain words: measured once.
  TerrainTuneOptions o = options;
  for (TerrainCondition& c : o.conditions) {
    if (!c.level) c.level = level_reference(start, c, o.fps);
  }
  const WordParameters parameters(start, o.words);
  TerrainTuneResult result;
  result.start_cost = terrain_cost(start, o);
  CmaesOptions cma;
  cma.sigma = o.sigma;
  cma.max_generations = o.generations;
  cma.seed = o.seed;
  cma.threads = o.threads;
  if (o.progress) {
    cma.progress = [&o](int generation, double cost, const std::vector<double>&) {
      o.progress(generation, cost);
    };
  }
  const CmaesResult found =
      minimize([&](const std::vector<double>& x) { return terrain_cost(parameters.apply(x), o); },
               parameters.start(), cma);
  result.evaluations = found.evaluations;
  // Rounded for people, with more digits where rounding would lose much of what was found (a walk
  // on stairs can hinge on a value's third digit), and never worse than the start.
  const double found_cost = terrain_cost(parameters.apply(found.best), o);
  for (int digits = o.digits; digits <= 8; ++digits) {
    result.set = parameters.apply(found.best, digits);
    result.cost = terrain_cost(result.set, o);
    if (result.cost <= 1.05 * found_cost + 1.0) break;
  }
  if (!(result.cost < result.start_cost)) {
    result.set = start;
    result.cost = result.start_cost;
  }
  return result;
}

}  // namespace fuzzygait::learn
