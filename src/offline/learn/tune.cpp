#include "fuzzygait/learn/tune.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/eval/recovery.hpp"
#include "fuzzygait/fuzzy/term.hpp"
#include "fuzzygait/learn/cmaes.hpp"
#include "offline/learn/set_edit.hpp"
#include "offline/learn/words.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::learn {

using detail::round_significant;

SetParameters::SetParameters(const gait::ControllerSet& base, double minimum_inertia,
                             bool angle_words)
    : base_(base), minimum_inertia_(minimum_inertia) {
  for (std::size_t s = 0; s < base.controllers.size(); ++s) {
    const fuzzy::Engine& e = base.controllers[s].engine();
    const bool hip =
        s == static_cast<std::size_t>(gait::slot(gait::LegPhase::Swing, gait::Joint::Hip)) ||
        s == static_cast<std::size_t>(gait::slot(gait::LegPhase::Stance, gait::Joint::Hip));
    const std::vector<fuzzy::Term>& terms = e.outputs.at(0).terms;
    for (std::size_t t = 0; t < terms.size(); ++t) {
      if (terms[t].kind != fuzzy::TermKind::Constant) continue;
      values_.push_back({Kind::Output, s, 0, t});
      scales_.push_back(hip ? 2.0 : 200.0);
      start_.push_back(terms[t].parameters[0]);
    }
  }
  values_.push_back({Kind::Inertia, 0, 0, 0});
  scales_.push_back(0.02);
  start_.push_back(std::max(base.inertia, minimum_inertia_));
  // Interior knots of the inputs of partition controllers: when along its progress a joint
  // changes its mind.
  for (std::size_t s = 0; s < base.controllers.size(); ++s) {
    if (!base.controllers[s].fast_path()) continue;
    const fuzzy::Engine& e = base.controllers[s].engine();
    for (std::size_t i = 0; i < e.inputs.size(); ++i) {
      const fuzzy::InputVariable& v = e.inputs[i];
      // Only timing moves, unless asked: the words of angles ("flat" is 0 degrees) keep their
      // meaning.
      if (!angle_words && v.name != "delta" && v.name != "other_delta") continue;
      for (std::size_t k = 1; k + 1 < v.terms.size(); ++k) {
        values_.push_back({Kind::Knot, s, i, k});
        scales_.push_back(0.15 * (v.maximum - v.minimum));
        start_.push_back(v.terms[k].parameters[1]);
      }
    }
  }
}

std::vector<double> SetParameters::values() const {
  std::vector<double> v(start_.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = start_[i] / scales_[i];
  return v;
}

gait::ControllerSet SetParameters::apply(const std::vector<double>& scaled) const {
  std::vector<double> values(scaled.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = scaled[i] * scales_[i];
  return with_values(values);
}

gait::ControllerSet SetParameters::with_values(const std::vector<double>& values) const {
  std::vector<fuzzy::Engine> engines;
  for (const gait::Controller& c : base_.controllers)
    engines.push_back(c.engine());
  double inertia = base_.inertia;
  for (std::size_t k = 0; k < values_.size(); ++k) {
    const Value& p = values_[k];
    switch (p.kind) {
      case Kind::Output:
        engines[p.slot].outputs.at(0).terms[p.index].parameters[0] = values[k];
        break;
      case Kind::Inertia:
        inertia = std::clamp(std::abs(values[k]), minimum_inertia_, 0.2);
        break;
      case Kind::Knot: {
        fuzzy::InputVariable& v = engines[p.slot].inputs[p.input];
        const double gap = 0.02 * (v.maximum - v.minimum);
        const double low = v.terms[p.index - 1].parameters[1] + gap;
        const double high = v.terms[p.index + 1].parameters[1] - gap;
        // The knot is the peak of its term and the feet of its neighbours (a strong partition).
        detail::move_knot(v, p.index, std::clamp(values[k], low, std::max(low, high)));
        break;
      }
    }
  }
  return detail::with_engines(base_, engines, inertia);
}

gait::ControllerSet SetParameters::rounded(const std::vector<double>& scaled,
                                           int significant) const {
  std::vector<double> values(scaled.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = round_significant(scaled[i] * scales_[i], significant);
  }
  return with_values(values);
}

double word_penalty(const gait::ControllerSet& set, const CostWeights& weights) {
  // Each word promises a direction and a size: "stay" is still, "flex" bends the joint, a
  // "fast" word is faster than its plain form, and so on. A tuned value that breaks its word's
  // promise would mislead the artist who reads the rules.
  double penalty = 0.0;
  for (const gait::Controller& c : set.controllers) {
    const fuzzy::OutputVariable& out = c.engine().outputs.at(0);
    const double unit = weights.word_unit * (out.maximum - out.minimum);
    std::vector<double> values(out.terms.size(), 0.0);
    for (std::size_t t = 0; t < out.terms.size(); ++t) {
      if (out.terms[t].kind == fuzzy::TermKind::Constant) values[t] = out.terms[t].parameters[0];
    }
    for (const detail::WordPromise& p : detail::word_promises(out))
      penalty += detail::broken_by(p, values.data(), unit);
  }
  return penalty;
}

namespace {

// A walk whose typical frame-to-frame velocity change (deg/s) is under this counts it as this,
// so that its velocity jump ratio stays finite.
constexpr double kLeastVelocityChange = 1.0;

// The samples of the mean cycle (eval::kCycleSamples, 2 % apart) where the toes rest near
// neutral: while the foot is flat (10-30 %) and before landing (86-100 %).
struct SampleRange {
  int first;
  int last;
};
constexpr SampleRange kToeRestSamples[] = {{5, 15}, {43, 50}};

// Recovery from an awkward start (eval::walk_from_random_start, the acceptance test's check):
// the walk must stay sound and settle into steps of the commanded length within three steps.
// Returns 0 when it does.
double recovery_cost(const gait::ControllerSet& set, std::uint64_t seed, const CostWeights& w,
                     std::string* report) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  const gait::WalkerOptions wo;
  double cost = 0.0;
  try {
    const eval::RecoveryReport r = eval::walk_from_random_start(set, wo, seed, ground);
    if (!r.sound()) cost = w.unsound_start;
    cost += w.unsettled_step * r.unsettled_steps(wo.step_length);
  } catch (const std::exception&) {
    cost = w.unsound_start;
  }
  if (report && cost > 0.0) {
    *report += "random start " + std::to_string(seed) + ": cost " + std::to_string(cost) + "\n";
  }
  return cost;
}

}  // namespace

WalkCondition main_condition(const eval::Normative& reference) {
  return {.stature = 1.75,
          .step_length = 0.70,
          .reference = &reference,
          .realism_weight = 1.0,
          .enforce_bounds = true};
}

std::vector<WalkCondition> grid_conditions(const eval::Normative& reference,
                                           const eval::Normative& slower,
                                           const eval::Normative& faster) {
  std::vector<WalkCondition> conditions = {
      main_condition(reference),
      {.stature = 1.75, .step_length = 0.55, .reference = &slower, .realism_weight = 0.3},
      {.stature = 1.75, .step_length = 0.85, .reference = &faster, .realism_weight = 0.3}};
  // The rest of the acceptance grid, for contact and timing.
  for (const double step : {0.50, 0.60, 0.70, 0.85}) {
    for (const double stature : {1.50, 1.75, 2.00}) {
      if (stature == 1.75 && (step == 0.70 || step == 0.85)) continue;  // walked above
      conditions.push_back({.stature = stature, .step_length = step});
    }
  }
  return conditions;
}

eval::Normative clip_reference(const eval::GaitReport& clip, const std::string& name) {
  eval::Normative n;
  n.name = name;
  n.thigh = clip.thigh;
  n.hip = clip.thigh;
  n.knee = clip.knee;
  n.ankle = clip.ankle;
  return n;
}

WalkCondition clip_condition(const eval::Normative& reference, const eval::GaitReport& clip,
                             const rig::Segments& segments, double step, const ClipTolerances& t) {
  WalkCondition c;
  c.segments = segments;
  c.step_length = step;
  c.reference = &reference;
  c.enforce_bounds = true;
  c.stance = Range{clip.stance_percent - t.stance, clip.stance_percent + t.stance};
  c.cycle_time =
      Range{clip.cycle_time * (1.0 - t.cycle_time), clip.cycle_time * (1.0 + t.cycle_time)};
  c.knee_peak = Range{clip.knee_peak - t.knee_peak, clip.knee_peak + t.knee_peak};
  c.knee_peak_percent = Range{clip.knee_peak_percent - t.knee_peak_percent,
                              clip.knee_peak_percent + t.knee_peak_percent};
  c.toes_rest = false;
  return c;
}

std::vector<std::uint64_t> recovery_seeds(int count) {
  std::vector<std::uint64_t> seeds;
  for (int k = 0; k < count; ++k)
    seeds.push_back(1000 + static_cast<std::uint64_t>(k));
  return seeds;
}

namespace {

void validate_weights(const CostWeights& w) {
  struct Field {
    const char* name;
    double value;
    bool positive;  // divides: 0 is refused too
  };
  const Field fields[] = {
      {"words", w.words, false},
      {"words_over_bound", w.words_over_bound, false},
      {"word_unit", w.word_unit, true},
      {"unsound_start", w.unsound_start, false},
      {"unsettled_step", w.unsettled_step, false},
      // A walk that fails must cost something, and a candidate that makes no set more.
      {"failed_walk", w.failed_walk, true},
      {"step_error", w.step_error, false},
      {"step_error_over_bound", w.step_error_over_bound, false},
      {"toe_scuff", w.toe_scuff, false},
      {"toe_clearance_wanted", w.toe_clearance_wanted, true},
      {"cycle_time_sd", w.cycle_time_sd, false},
      {"step_length_sd", w.step_length_sd, false},
      {"stance_outside_range", w.stance_outside_range, false},
      {"pelvis_outside_range", w.pelvis_outside_range, false},
      {"cycle_time_outside_range", w.cycle_time_outside_range, false},
      {"velocity_jump", w.velocity_jump, false},
      {"velocity_jump_ratio_free", w.velocity_jump_ratio_free, false},
      {"slip", w.slip, false},
      {"slip_free", w.slip_free, false},
      {"slip_over_bound", w.slip_over_bound, false},
      {"penetration", w.penetration, false},
      {"heel_bounce_over_bound", w.heel_bounce_over_bound, false},
      {"curve_rmse", w.curve_rmse, false},
      {"thigh_knee_uncorrelated", w.thigh_knee_uncorrelated, false},
      {"ankle_uncorrelated", w.ankle_uncorrelated, false},
      {"curve_rmse_over_bound", w.curve_rmse_over_bound, false},
      {"acceleration_over_bound", w.acceleration_over_bound, false},
      {"knee_peak_outside_range", w.knee_peak_outside_range, false},
      {"knee_peak_timing_outside_range", w.knee_peak_timing_outside_range, false},
      {"toe_off_neutral", w.toe_off_neutral, false},
      {"anchor", w.anchor, false},
  };
  static_assert(sizeof(fields) / sizeof(fields[0]) * sizeof(double) == sizeof(CostWeights),
                "every field of CostWeights is checked");
  for (const Field& f : fields) {
    if (std::isfinite(f.value) && (f.positive ? f.value > 0.0 : f.value >= 0.0)) continue;
    throw std::invalid_argument("tune: weights." + std::string(f.name) + " must be finite and " +
                                (f.positive ? "above 0" : "at least 0") + ", got " +
                                common::number_text(f.value));
  }
}

}  // namespace

void validate(const TuneOptions& o) {
  auto within = [](const char* field, double value, double low, double high) {
    if (!(value >= low && value <= high)) {
      throw std::invalid_argument("tune: " + std::string(field) + " must be between " +
                                  common::number_text(low) + " and " + common::number_text(high) +
                                  ", got " + common::number_text(value));
    }
  };
  auto ordered = [&within](const char* field, double low, double high, double least, double most) {
    within(field, low, least, most);
    within(field, high, low, most);  // the range's high end: from its low end up
  };
  within("duration", o.duration, 1.0, 3600.0);
  within("warm-up", o.warm_up, 0.0, 3600.0);
  within("fps", o.fps, 1.0, 10000.0);
  ordered("cycle time range", o.cycle_time_min, o.cycle_time_max, 0.1, 10.0);
  ordered("stance range", o.stance_min, o.stance_max, 0.0, 100.0);
  ordered("knee peak range", o.knee_peak_min, o.knee_peak_max, 0.0, 180.0);
  ordered("knee peak timing range", o.knee_peak_percent_min, o.knee_peak_percent_max, 0.0, 100.0);
  ordered("pelvis range", o.pelvis_range_min, o.pelvis_range_max, 0.0, 1e9);
  within("minimum inertia", o.minimum_inertia, 0.001, 1.0);
  within("thigh RMSE bound", o.thigh_rmse_max, 0.0, 180.0);
  within("knee RMSE bound", o.knee_rmse_max, 0.0, 180.0);
  within("ankle RMSE bound", o.ankle_rmse_max, 0.0, 180.0);
  within("slip bound", o.slip_max, 0.0, 1.0);
  within("step error bound", o.step_error_max, 0.0, 1000.0);
  within("word penalty bound", o.word_penalty_max, 0.0, 1e9);
  within("acceleration ratio bound", o.acceleration_ratio_max, 1e-9,
         std::numeric_limits<double>::infinity());
  within("heel bounce bound", o.heel_bounce_max, 0.0, std::numeric_limits<double>::infinity());
  validate_weights(o.weights);
  within("generations", o.generations, 1, 1e6);
  within("polish generations", o.polish_generations, 0, 1e6);
  within("digits", o.digits, 1, 17);
  within("threads", o.threads, 1, 1024);
  within("sigma", o.sigma, 1e-9, 10.0);
  within("population", o.population, 0, 100000);
  within("recovery starts", static_cast<double>(o.recovery_seeds.size()), 0, 10000);
}

double walk_cost(const gait::ControllerSet& set, const TuneOptions& options, std::string* report,
                 int* failed_walks) {
  validate(options);
  const CostWeights& w = options.weights;
  if (failed_walks) *failed_walks = 0;
  const terrain::Terrain ground = terrain::Terrain::flat();
  const double words = word_penalty(set, w);
  double total =
      w.words * words + w.words_over_bound * std::max(0.0, words - options.word_penalty_max);
  if (report && words > 0.0) {
    *report += "words against their meaning: penalty " + std::to_string(words) + "\n";
  }
  if (options.anchor && w.anchor > 0.0) {
    // Both sets' values in SetParameters' scaled units (the same parameters: the same words).
    const std::vector<double> a = SetParameters(*options.anchor, 0.0, options.angle_words).values();
    const std::vector<double> b = SetParameters(set, 0.0, options.angle_words).values();
    double squares = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
      squares += (b[i] - a[i]) * (b[i] - a[i]);
    total += w.anchor * squares;
  }
  for (std::uint64_t seed : options.recovery_seeds)
    total += recovery_cost(set, seed, w, report);
  for (const WalkCondition& c : options.conditions) {
    double cost = 0.0;
    try {
      gait::WalkerOptions wo;
      wo.segments = c.segments.value_or(rig::segments_from_stature(c.stature));
      wo.step_length = c.step_length;
      wo.start.warm_up = options.warm_up;
      gait::Walker walker(set, wo, ground);
      const eval::Motion motion = eval::record(walker, options.duration, options.fps);
      const eval::GaitReport r = eval::evaluate(motion, ground, c.reference, c.step_length);
      auto over = [](double value, double low, double high) {
        return std::max(0.0, low - value) + std::max(0.0, value - high);
      };
      const double step_error = r.step_error_percent.value();  // the step is always given
      cost += w.step_error * step_error +
              w.step_error_over_bound * std::max(0.0, step_error - options.step_error_max);
      cost += w.toe_scuff * std::max(0.0, w.toe_clearance_wanted - r.min_toe_clearance) /
              w.toe_clearance_wanted;
      cost +=
          w.cycle_time_sd * r.cycle_time_sd + w.step_length_sd * r.step_length_sd / c.step_length;
      const Range stance = c.stance.value_or(Range{options.stance_min, options.stance_max});
      const Range cycle =
          c.cycle_time.value_or(Range{options.cycle_time_min, options.cycle_time_max});
      const Range knee_peak =
          c.knee_peak.value_or(Range{options.knee_peak_min, options.knee_peak_max});
      const Range knee_peak_percent = c.knee_peak_percent.value_or(
          Range{options.knee_peak_percent_min, options.knee_peak_percent_max});
      cost += w.stance_outside_range * over(r.stance_percent, stance.min, stance.max);
      cost += w.pelvis_outside_range * over(1000.0 * r.pelvis_vertical_range,
                                            options.pelvis_range_min, options.pelvis_range_max);
      cost += w.cycle_time_outside_range * over(r.cycle_time, cycle.min, cycle.max);
      // Velocities must not jump where a phase hands a joint to another controller.
      const double jump_ratio =
          r.max_velocity_jump / std::max(r.typical_velocity_change, kLeastVelocityChange);
      cost += w.velocity_jump * std::max(0.0, jump_ratio - w.velocity_jump_ratio_free);
      // A foot point near the ground that moves along it is a slip (the walk checker's rule).
      cost += w.slip * std::max(0.0, r.max_slip - w.slip_free) +
              w.slip_over_bound * std::max(0.0, r.max_slip - options.slip_max) +
              w.penetration * r.max_penetration;
      cost += w.heel_bounce_over_bound * std::max(0.0, r.max_heel_bounce - options.heel_bounce_max);
      if (c.reference) {
        double realism =
            w.curve_rmse * (r.thigh_score->rmse + r.knee_score->rmse + r.ankle_score->rmse);
        // (1 - r) + (1 - r) of the thigh and the knee.
        realism +=
            w.thigh_knee_uncorrelated * (2.0 - r.thigh_score->pearson - r.knee_score->pearson) +
            w.ankle_uncorrelated * (1.0 - r.ankle_score->pearson);
        if (c.enforce_bounds) {
          realism += w.curve_rmse_over_bound *
                     (std::max(0.0, r.thigh_score->rmse - options.thigh_rmse_max) +
                      std::max(0.0, r.knee_score->rmse - options.knee_rmse_max) +
                      std::max(0.0, r.ankle_score->rmse - options.ankle_rmse_max));
          for (const eval::JointScore* s : {&*r.thigh_score, &*r.knee_score}) {
            realism += w.acceleration_over_bound *
                       std::max(0.0, s->acceleration_ratio() - options.acceleration_ratio_max);
          }
        }
        realism += w.knee_peak_outside_range * over(r.knee_peak, knee_peak.min, knee_peak.max) +
                   w.knee_peak_timing_outside_range *
                       over(r.knee_peak_percent, knee_peak_percent.min, knee_peak_percent.max);
        // The toes rest near neutral while the foot is flat and again before landing.
        double toe = 0.0;
        for (const SampleRange& rest : kToeRestSamples) {
          for (int k = rest.first; k <= rest.last; ++k)
            toe += std::abs(r.toe.mean[static_cast<std::size_t>(k)]);
        }
        if (c.toes_rest) realism += w.toe_off_neutral * toe;
        cost += c.realism_weight * realism;
      }
      if (report) {
        char line[400];
        std::snprintf(
            line, sizeof line,
            "stature %.2f step %.2f: cost %.2f | step %.3f (%.1f%%) stance %.1f cycle %.3f "
            "clear %.1f mm knee %.0f@%.0f%%",
            c.segments ? c.segments->leg_length() / 0.53 : c.stature, c.step_length, cost,
            r.step_length, step_error, r.stance_percent, r.cycle_time, 1000.0 * r.min_toe_clearance,
            r.knee_peak, r.knee_peak_percent);
        *report += line;
        if (c.reference) {
          std::snprintf(line, sizeof line,
                        " | rmse thigh %.1f knee %.1f ankle %.1f, r %.2f %.2f %.2f, acceleration "
                        "x%.1f x%.1f x%.1f",
                        r.thigh_score->rmse, r.knee_score->rmse, r.ankle_score->rmse,
                        r.thigh_score->pearson, r.knee_score->pearson, r.ankle_score->pearson,
                        r.thigh_score->acceleration_ratio(), r.knee_score->acceleration_ratio(),
                        r.ankle_score->acceleration_ratio());
          *report += line;
        }
        *report += "\n";
      }
    } catch (const std::exception& e) {
      cost = w.failed_walk;
      if (failed_walks) ++*failed_walks;
      if (report)
        *report += "stature/step " + std::to_string(c.stature) + "/" +
                   std::to_string(c.step_length) + ": failed: " + e.what() + "\n";
    }
    total += std::isfinite(cost) ? cost : w.failed_walk;
  }
  return total;
}

namespace {

// The cost of the set `make` builds from a candidate. A candidate that makes no controller set
// (a value the search drove to nan or infinity, which gait::Controller refuses) costs more than
// one whose every walk failed, rather than ending the tuning from a worker thread.
double candidate_cost(const std::function<gait::ControllerSet()>& make,
                      const TuneOptions& options) {
  gait::ControllerSet set;
  try {
    set = make();
  } catch (const std::invalid_argument&) {
    return options.weights.failed_walk *
           static_cast<double>(options.conditions.size() + options.recovery_seeds.size() + 1);
  }
  return walk_cost(set, options);
}

}  // namespace

TuneResult tune(const gait::ControllerSet& start, const TuneOptions& options) {
  validate(options);
  const SetParameters parameters(start, options.minimum_inertia, options.angle_words);
  CmaesOptions cma;
  cma.sigma = options.sigma;
  cma.population = options.population;
  cma.max_generations = options.generations;
  cma.seed = options.seed;
  cma.threads = options.threads;
  cma.progress = [&](int generation, double best, const std::vector<double>& x) {
    if (options.progress) options.progress(generation, best);
    if (options.best) options.best(generation, parameters.apply(x));
  };
  cma.stop = options.stop;
  auto cost = [&](const std::vector<double>& x) {
    return candidate_cost([&] { return parameters.apply(x); }, options);
  };
  const CmaesResult r = minimize(cost, parameters.values(), cma);
  TuneResult out;
  out.set = parameters.apply(r.best);
  out.cost = r.best_cost;
  out.evaluations = r.evaluations;
  if (options.polish_generations <= 0) {
    // The values as the set holds them, rounded.
    const SetParameters tuned(out.set, options.minimum_inertia, options.angle_words);
    out.rounded = tuned.rounded(tuned.values(), options.digits);
  } else {
    // The written values are rounded for the artist: polish the result where the cost sees
    // exactly those rounded values.
    auto rounded_cost = [&](const std::vector<double>& x) {
      return candidate_cost([&] { return parameters.rounded(x, options.digits); }, options);
    };
    CmaesOptions polish = cma;
    polish.sigma = 0.25 * options.sigma;
    polish.max_generations = options.polish_generations;
    polish.seed = options.seed + 1;
    polish.progress = [&](int generation, double best, const std::vector<double>& x) {
      if (options.progress) options.progress(options.generations + generation, best);
      if (options.best) {
        options.best(options.generations + generation, parameters.rounded(x, options.digits));
      }
    };
    const CmaesResult p = minimize(rounded_cost, r.best, polish);
    out.set = parameters.rounded(p.best, options.digits);
    out.cost = p.best_cost;
    out.evaluations += p.evaluations;
    out.rounded = out.set;
  }
  return out;
}

}  // namespace fuzzygait::learn
