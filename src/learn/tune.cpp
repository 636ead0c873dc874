#include "fuzzygait/learn/tune.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "fuzzygait/gait/motion.hpp"
#include "fuzzygait/learn/cmaes.hpp"

namespace fuzzygait::learn {
namespace {

double round_significant(double v, int digits) {
  if (v == 0.0 || !std::isfinite(v)) return v;
  const double magnitude = std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::abs(v)))));
  return std::round(v * magnitude) / magnitude;
}

gait::ControllerSet rebuild(const gait::ControllerSet& base, const std::vector<fuzzy::Engine>& engines,
                            double inertia) {
  gait::ControllerSet set;
  set.name = base.name;
  set.description = base.description;
  set.pelvis_tilt = base.pelvis_tilt;
  set.inertia = inertia;
  for (std::size_t s = 0; s < engines.size(); ++s) {
    set.controllers.emplace_back(engines[s], base.controllers[s].source());
  }
  return set;
}

}  // namespace

SetParameters::SetParameters(const gait::ControllerSet& base) : base_(base) {
  for (std::size_t s = 0; s < base.controllers.size(); ++s) {
    const fuzzy::Engine& e = base.controllers[s].engine();
    const bool hip = s == static_cast<std::size_t>(gait::slot(gait::LegPhase::Swing, gait::Joint::Hip)) ||
                     s == static_cast<std::size_t>(gait::slot(gait::LegPhase::Stance, gait::Joint::Hip));
    for (const fuzzy::Term& t : e.outputs.at(0).terms) {
      if (t.kind != fuzzy::TermKind::Constant) continue;
      scales_.push_back(hip ? 2.0 : 200.0);
      start_.push_back(t.parameters[0]);
    }
  }
  scales_.push_back(0.02);
  start_.push_back(base.inertia);
}

std::vector<double> SetParameters::values() const {
  std::vector<double> v(start_.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = start_[i] / scales_[i];
  return v;
}

gait::ControllerSet SetParameters::apply(const std::vector<double>& scaled) const {
  std::vector<fuzzy::Engine> engines;
  std::size_t k = 0;
  for (const gait::Controller& c : base_.controllers) {
    fuzzy::Engine e = c.engine();
    for (fuzzy::Term& t : e.outputs.at(0).terms) {
      if (t.kind == fuzzy::TermKind::Constant) t.parameters[0] = scaled[k] * scales_[k], ++k;
    }
    engines.push_back(std::move(e));
  }
  const double inertia = std::clamp(std::abs(scaled[k] * scales_[k]), 0.005, 0.2);
  return rebuild(base_, engines, inertia);
}

gait::ControllerSet SetParameters::rounded(const std::vector<double>& scaled, int significant) const {
  std::vector<double> r(scaled.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    r[i] = round_significant(scaled[i] * scales_[i], significant) / scales_[i];
  }
  return apply(r);
}

double walk_cost(const gait::ControllerSet& set, const TuneOptions& options, std::string* report) {
  const terrain::Terrain ground = terrain::Terrain::flat();
  double total = 0.0;
  for (const WalkCondition& c : options.conditions) {
    double cost = 0.0;
    try {
      gait::WalkerOptions wo;
      wo.segments = rig::segments_from_stature(c.stature);
      wo.step_length = c.step_length;
      gait::Walker walker(set, wo, ground);
      const gait::Motion motion = gait::record(walker, options.duration, options.fps);
      const gait::GaitReport r =
          gait::evaluate(motion, ground, c.realism ? &options.reference : nullptr, c.step_length);
      auto over = [](double value, double low, double high) {
        return std::max(0.0, low - value) + std::max(0.0, value - high);
      };
      cost += 2.0 * r.step_error_percent;
      cost += 200.0 * std::max(0.0, 0.012 - r.min_toe_clearance) / 0.012;
      cost += 100.0 * r.cycle_time_sd + 100.0 * r.step_length_sd / c.step_length;
      cost += 2.0 * over(r.stance_percent, 58.0, 64.0);
      cost += 2.0 * over(r.cycle_time, 0.95, 1.25);
      if (c.realism) {
        cost += r.thigh_score->rmse + r.knee_score->rmse + r.ankle_score->rmse;
        cost += 10.0 * (3.0 - r.thigh_score->pearson - r.knee_score->pearson - r.ankle_score->pearson);
        cost += over(r.knee_peak, 56.0, 68.0) + over(r.knee_peak_percent, 69.0, 77.0);
      }
      if (report) {
        char line[400];
        std::snprintf(line, sizeof line,
                      "stature %.2f step %.2f: cost %.2f | step %.3f (%.1f%%) stance %.1f cycle %.3f "
                      "clear %.1f mm knee %.0f@%.0f%%",
                      c.stature, c.step_length, cost, r.step_length, r.step_error_percent,
                      r.stance_percent, r.cycle_time, 1000.0 * r.min_toe_clearance, r.knee_peak,
                      r.knee_peak_percent);
        *report += line;
        if (c.realism) {
          std::snprintf(line, sizeof line, " | rmse thigh %.1f knee %.1f ankle %.1f, r %.2f %.2f %.2f",
                        r.thigh_score->rmse, r.knee_score->rmse, r.ankle_score->rmse,
                        r.thigh_score->pearson, r.knee_score->pearson, r.ankle_score->pearson);
          *report += line;
        }
        *report += "\n";
      }
    } catch (const std::exception& e) {
      cost = 1000.0;
      if (report) *report += "stature/step " + std::to_string(c.stature) + "/" +
                             std::to_string(c.step_length) + ": failed: " + e.what() + "\n";
    }
    total += std::isfinite(cost) ? cost : 1000.0;
  }
  return total;
}

TuneResult tune(const gait::ControllerSet& start, const TuneOptions& options) {
  const SetParameters parameters(start);
  CmaesOptions cma;
  cma.sigma = options.sigma;
  cma.max_generations = options.generations;
  cma.seed = options.seed;
  cma.threads = options.threads;
  cma.progress = [&options](int generation, double best, const std::vector<double>&) {
    if (options.progress) options.progress(generation, best);
  };
  auto cost = [&](const std::vector<double>& x) {
    return walk_cost(parameters.apply(x), options);
  };
  const CmaesResult r = minimize(cost, parameters.values(), cma);
  TuneResult out{parameters.apply(r.best), r.best_cost, cost(parameters.values()), r.evaluations};
  return out;
}

}  // namespace fuzzygait::learn
