#include "fuzzygait/learn/train.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>

#include "fuzzygait/eval/recovery.hpp"
#include "fuzzygait/eval/terrain_report.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/learn/network.hpp"
#include "fuzzygait/learn/training.hpp"
#include "offline/learn/set_edit.hpp"

namespace fuzzygait::learn {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The closed-loop cost of weights, and the best weights seen.
class ClosedLoop {
 public:
  ClosedLoop(const SetNetwork& network, const TuneOptions& options)
      : network_(network), options_(options) {}

  // Infinite for weights that make no set or a set that cannot walk a condition: a fit is kept
  // only where it walks (walk_cost prices a failed walk at a fixed cost, which a poor walk can
  // exceed).
  double cost(const std::vector<double>& w) const {
    gait::ControllerSet set;
    try {
      set = network_.apply(w);
    } catch (const std::invalid_argument&) {
      return std::numeric_limits<double>::infinity();
    }
    int failed = 0;
    const double c = walk_cost(set, options_, nullptr, &failed);
    return failed > 0 ? std::numeric_limits<double>::infinity() : c;
  }

  // Keeps from `candidate` what lowers the cost of `current` (cost `current_cost`): the whole of
  // it, or controller by controller (and the inertia). Returns how many controllers changed.
  int keep_better(std::vector<double>& current, double& current_cost,
                  const std::vector<double>& candidate) const {
    std::vector<double> greedy = current;
    double greedy_cost = current_cost;
    int kept = 0;
    for (int s = 0; s <= gait::kSlotCount; ++s) {
      std::vector<double> trial = greedy;
      if (s == gait::kSlotCount) {
        trial[network_.inertia_index()] = candidate[network_.inertia_index()];
      } else {
        for (std::size_t i : network_.slot_weights(s))
          trial[i] = candidate[i];
      }
      if (trial == greedy) continue;
      const double c = cost(trial);
      if (c < greedy_cost) {
        greedy = std::move(trial);
        greedy_cost = c;
        ++kept;
      }
    }
    const double whole = cost(candidate);
    if (whole < greedy_cost) {
      current = candidate;
      current_cost = whole;
      return gait::kSlotCount + 1;
    }
    current = std::move(greedy);
    current_cost = greedy_cost;
    return kept;
  }

 private:
  const SetNetwork& network_;
  const TuneOptions& options_;
};

}  // namespace

namespace {

// The median of `values` (which it reorders); 0 for none.
double median(std::vector<double>& values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Why a clip is no level forward walk to train on, or "" when it is one: its planted feet off
// the fitted floor, feet landing behind the body (a backward walk), or a pace no walk has (a
// slow-motion or sped-up clip).
std::string not_a_level_walk(const eval::Motion& motion, const terrain::Terrain& ground,
                             const eval::GaitReport& report) {
  char line[200];
  // Planted feet: their lowest point (heel or ball) on the floor.
  std::vector<double> heights;
  std::vector<double> ahead;  // a striking heel's distance ahead of the pelvis
  for (std::size_t i = 0; i < motion.frames.size(); ++i) {
    const eval::Frame& f = motion.frames[i];
    for (std::size_t s = 0; s < 2; ++s) {
      if (!f.contact[s]) continue;
      const rig::LegPoints& p = f.points[s];
      heights.push_back(
          std::min(p.heel.y - ground.height(p.heel.x), p.ball.y - ground.height(p.ball.x)));
      if (i > 0 && !motion.frames[i - 1].contact[s]) ahead.push_back(p.heel.x - f.pose.pelvis.x);
    }
  }
  const double floor = median(heights);
  if (std::abs(floor) > kFloorTolerance) {
    std::snprintf(line, sizeof line,
                  "its planted feet sit %.1f cm %s the floor fitted to them (the ground is not "
                  "level and even, or the feet are not where the skeleton says)",
                  100.0 * std::abs(floor), floor < 0.0 ? "below" : "above");
    return line;
  }
  if (!ahead.empty() && median(ahead) < 0.0) {
    std::snprintf(line, sizeof line,
                  "its feet land %.2f m behind the body: a backward walk, not a forward one",
                  -median(ahead));
    return line;
  }
  const double pace = gait::Walker::pace(report.speed, motion.segments);
  if (!(pace >= kSlowestPace && pace <= kFastestPace) ||
      !(report.cadence >= kFewestSteps && report.cadence <= kMostSteps)) {
    std::snprintf(line, sizeof line,
                  "it walks %.2f m/s at %.0f steps a minute (pace %.2f), outside any walk (pace "
                  "%.2f-%.2f, %.0f-%.0f steps a minute): a slowed or sped-up clip?",
                  report.speed, report.cadence, pace, kSlowestPace, kFastestPace, kFewestSteps,
                  kMostSteps);
    return line;
  }
  return {};
}

}  // namespace

TrainClip make_train_clip(std::string name, eval::Motion motion, terrain::Terrain ground) {
  TrainClip clip;
  clip.name = std::move(name);
  motion.captured = true;
  try {
    clip.report = eval::evaluate(motion, ground);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(clip.name + ": cannot train on it: " + e.what());
  }
  if (const std::string why = not_a_level_walk(motion, ground, clip.report); !why.empty()) {
    throw std::invalid_argument(clip.name + ": not a level forward walk to train on: " + why);
  }
  clip.step_length = clip.report.step_length;
  const double longest = gait::Walker::max_step_length(motion.segments);
  if (!(clip.step_length > 0.0 && clip.step_length <= longest)) {
    throw std::invalid_argument(clip.name + ": its step of " + std::to_string(clip.step_length) +
                                " m is beyond what its legs reach (" + std::to_string(longest) +
                                " m)");
  }
  clip.motion = std::move(motion);
  clip.ground = std::move(ground);
  return clip;
}

TrainOptions default_train_options() {
  TrainOptions o;
  o.polish.generations = 800;
  o.polish.polish_generations = 100;
  // Many candidates a generation: the walks answer small changes of the values unevenly (a
  // landing a time step earlier), and a large population averages that out.
  o.polish.population = 48;
  o.polish.digits = 3;
  o.polish.threads = 2;
  o.polish.duration = 5.0;
  o.polish.angle_words = true;
  // The words keep their promises (word_penalty) throughout: any breach costs steeply.
  o.polish.word_penalty_max = 0.0;
  o.polish.minimum_inertia = 0.01;
  o.polish.thigh_rmse_max = 3.7;
  o.polish.knee_rmse_max = 3.7;
  o.polish.ankle_rmse_max = 3.7;
  o.polish.sigma = 0.3;
  // A clip's timing is part of its style: its stance share and cadence are held firmly.
  o.polish.weights.stance_outside_range = 20.0;
  o.polish.weights.cycle_time_outside_range = 2000.0;
  // The weak pull toward the set the polish starts from (the base with the added words): values
  // the clips hardly move stay near the base's.
  o.polish.weights.anchor = 1.0;
  o.fit.threads = 2;
  o.fit.shortest_inertia = o.polish.minimum_inertia;
  return o;
}

ClipScore score_clip(const gait::ControllerSet& set, const TrainClip& clip, double duration) {
  ClipScore score;
  const eval::Normative reference = clip_reference(clip.report, clip.name);
  try {
    gait::WalkerOptions wo;
    wo.segments = clip.motion.segments;
    wo.step_length = clip.step_length;
    const terrain::Terrain flat = terrain::Terrain::flat();
    gait::Walker walker(set, wo, flat);
    const eval::Motion motion = eval::record(walker, duration, 120.0);
    score.report = eval::evaluate(motion, flat, &reference, clip.step_length);
  } catch (const std::exception&) {
    return score;
  }
  score.walked = true;
  score.thigh = score.report.thigh_score->rmse;
  score.knee = score.report.knee_score->rmse;
  score.ankle = score.report.ankle_score->rmse;
  score.stance = score.report.stance_percent;
  score.cadence = score.report.cadence;
  return score;
}

namespace {

// Counts a walk in `check`: within its bounds when `missed` is empty, else a line `walk: missed`.
void count_walk(WalksCheck& check, const std::string& walk,
                const std::vector<std::string>& missed) {
  ++check.walks;
  if (missed.empty()) {
    ++check.within;
    return;
  }
  std::string line = walk + ": ";
  for (std::size_t k = 0; k < missed.size(); ++k)
    line += (k > 0 ? "; " : "") + missed[k];
  check.misses.push_back(std::move(line));
}

// What a terrain walk misses of check_terrain's bounds: the terrain contact bounds
// (eval::missed_contact_bounds), the continuity bound, reaching the end of stairs, and on a ramp
// steps within 5 % of the command.
std::vector<std::string> missed_terrain_bounds(const eval::TerrainReport& r, double fps,
                                               bool stairs, double step) {
  std::vector<std::string> missed = eval::missed_contact_bounds(r);
  if (std::string jump = eval::missed_continuity_bound(r, fps); !jump.empty())
    missed.push_back(std::move(jump));
  char line[160];
  if (stairs && !r.reached_end.value_or(false))
    missed.push_back("stopped on run " + std::to_string(r.last_run) + " of " +
                     std::to_string(r.runs - 1));
  if (!stairs) {
    bool on_ramp = false;
    for (const eval::TerrainGroup& g : r.groups) {
      if (g.footing != eval::Footing::RampUp && g.footing != eval::Footing::RampDown) continue;
      on_ramp = true;
      const double error = g.step_length.mean / step - 1.0;
      if (g.steps < 6 || std::abs(error) >= 0.05) {
        std::snprintf(line, sizeof line, "%d steps on the ramp, %.1f %% from the command", g.steps,
                      error * 100.0);
        missed.emplace_back(line);
      }
    }
    if (!on_ramp) missed.emplace_back("no step on the ramp");
  }
  return missed;
}

}  // namespace

WalksCheck check_grid(const gait::ControllerSet& set) {
  WalksCheck check;
  const terrain::Terrain flat = terrain::Terrain::flat();
  for (const double step : {0.50, 0.60, 0.70, 0.85}) {
    for (const double stature : {1.50, 1.75, 2.00}) {
      char walk[64];
      std::snprintf(walk, sizeof walk, "%.2f m at %.2f m", step, stature);
      std::vector<std::string> missed;
      try {
        gait::WalkerOptions wo;
        wo.segments = rig::segments_from_stature(stature);
        wo.step_length = step;
        gait::Walker walker(set, wo, flat);
        const eval::Motion motion = eval::record(walker, 10.0, 120.0);
        missed = eval::missed_contact_bounds(eval::evaluate(motion, flat, nullptr, step));
      } catch (const std::exception& e) {
        missed = {e.what()};
      }
      count_walk(check, walk, missed);
    }
  }
  return check;
}

WalksCheck check_terrain(const gait::ControllerSet& set, const rig::Segments& body, double step) {
  struct Ground {
    const char* name;
    terrain::Terrain terrain;
    bool stairs;
  };
  const Ground grounds[] = {
      {"stairs up 0.17 x 0.28 m", terrain::Terrain::stairs(0.17, 0.28, 8), true},
      {"stairs down 0.17 x 0.28 m", terrain::Terrain::stairs(-0.17, 0.28, 8), true},
      {"ramp up 10 deg", terrain::Terrain::ramp(10.0), false},
      {"ramp down 10 deg", terrain::Terrain::ramp(-10.0), false},
  };
  WalksCheck check;
  for (const Ground& g : grounds) {
    std::vector<std::string> missed;
    try {
      gait::WalkerOptions wo;
      wo.segments = body;
      wo.step_length = step;
      gait::Walker walker(set, wo, g.terrain);
      const eval::Motion motion = eval::record(walker, g.stairs ? 24.0 : 16.0, 120.0);
      missed = missed_terrain_bounds(eval::evaluate_terrain(motion, g.terrain), motion.fps,
                                     g.stairs, step);
    } catch (const std::exception& e) {
      missed = {e.what()};
    }
    count_walk(check, g.name, missed);
  }
  return check;
}

StartsCheck check_starts(const gait::ControllerSet& set, const rig::Segments& body, double step,
                         int count) {
  StartsCheck check;
  const terrain::Terrain flat = terrain::Terrain::flat();
  gait::WalkerOptions wo;
  wo.segments = body;
  wo.step_length = step;
  for (const std::uint64_t seed : recovery_seeds(count)) {
    ++check.starts;
    try {
      const eval::RecoveryReport r = eval::walk_from_random_start(set, wo, seed, flat);
      if (!r.sound()) continue;
      ++check.sound;
      if (r.unsettled_steps(step) == 0) ++check.settled;
    } catch (const std::exception&) {
    }
  }
  return check;
}

ClipsBody clips_body(std::span<const TrainClip> clips) {
  if (clips.empty()) throw std::invalid_argument("the clips' body: no clips");
  ClipsBody m;
  for (const TrainClip& c : clips) {
    m.names += (m.names.empty() ? "" : ", ") + c.name;
    const rig::Segments& s = c.motion.segments;
    m.body.thigh += s.thigh;
    m.body.shank += s.shank;
    m.body.ankle_height += s.ankle_height;
    m.body.heel += s.heel;
    m.body.ball += s.ball;
    m.body.toe += s.toe;
    m.step += c.step_length;
    m.speed += c.report.speed;
  }
  const auto n = static_cast<double>(clips.size());
  for (double* v : {&m.body.thigh, &m.body.shank, &m.body.ankle_height, &m.body.heel, &m.body.ball,
                    &m.body.toe, &m.step, &m.speed})
    *v /= n;
  return m;
}

std::vector<StridePoint> stride_points(std::span<const TrainClip> clips) {
  std::vector<StridePoint> points;
  for (const TrainClip& c : clips) {
    const rig::Segments& s = c.motion.segments;
    points.push_back({gait::Walker::pace(c.report.speed, s), c.step_length / s.leg_length(), 1.0});
  }
  return points;
}

gait::ControllerSet fit_stride(const gait::ControllerSet& set,
                               std::span<const StridePoint> points) {
  if (!set.stride) throw std::invalid_argument("fit_stride: the set has no stride");
  if (points.empty()) throw std::invalid_argument("fit_stride: no points to fit");
  // Weighted least squares of step = a + b v(pace), v the stride as it is.
  double sw = 0.0, sv = 0.0, ss = 0.0, svv = 0.0, svs = 0.0;
  double slowest = points.front().pace, fastest = points.front().pace;
  for (const StridePoint& p : points) {
    const double v = set.step_at_pace(p.pace);
    sw += p.weight;
    sv += p.weight * v;
    ss += p.weight * p.step;
    svv += p.weight * v * v;
    svs += p.weight * v * p.step;
    slowest = std::min(slowest, p.pace);
    fastest = std::max(fastest, p.pace);
  }
  auto scaled = [&](double a, double b) {
    fuzzy::Engine engine = set.stride->engine();
    for (fuzzy::Term& t : engine.outputs.at(0).terms) {
      if (t.kind == fuzzy::TermKind::Constant) {
        t.parameters[0] = detail::round_significant(a + b * t.parameters[0], 3);
      }
    }
    gait::ControllerSet fitted = set;
    fitted.stride.emplace(std::move(engine), set.stride->source());
    return fitted;
  };
  // Walks at paces this close together show a step, not how it grows: the slope is fitted only
  // across a wider spread, and a slope that makes a stride the loader refuses (two walks at
  // nearby paces can ask for a step that vanishes at a stroll) falls back to the shift alone.
  constexpr double kPaceSpreadForSlope = 0.1;
  const double spread = svv - sv * sv / sw;
  if (fastest - slowest >= kPaceSpreadForSlope && spread > 1e-9 * std::max(1.0, svv)) {
    const double b = (svs - sv * ss / sw) / spread;
    if (!(b > 0.0)) {
      throw std::invalid_argument(
          "fit_stride: the walks' steps shrink as their pace grows; no stride fits them");
    }
    gait::ControllerSet fitted = scaled((ss - b * sv) / sw, b);
    if (fitted.stride_problem().empty()) return fitted;
  }
  gait::ControllerSet shifted = scaled((ss - sv) / sw, 1.0);
  if (shifted.stride_problem().empty()) return shifted;
  return set;
}

TrainResult train(const gait::ControllerSet& base, std::span<const TrainClip> clips,
                  const TrainOptions& options) {
  if (clips.empty()) throw std::invalid_argument("train: no clips");
  const Clock::time_point start = Clock::now();
  TrainResult result;
  if (options.structure) result.added = learning_structure(base);
  // The set the training starts from: the base with the added words, its stride (when it has
  // one) through the clips' steps.
  gait::ControllerSet first = with_words(base, result.added);
  if (first.stride) first = fit_stride(first, stride_points(clips));
  const SetNetwork network(first);
  auto stopped = [&options] { return options.stop && options.stop(); };
  auto scores = [&clips](const gait::ControllerSet& set) {
    std::vector<ClipScore> out;
    for (const TrainClip& clip : clips)
      out.push_back(score_clip(set, clip));
    return out;
  };
  auto report = [&](const std::string& stage, int iteration, double cost,
                    const gait::ControllerSet* set) {
    if (!options.progress) return;
    TrainProgress p{stage, iteration, cost, {}};
    if (set) {
      for (const ClipScore& s : scores(*set))
        p.rmse.push_back({s.thigh, s.knee, s.ankle});
    }
    options.progress(p);
  };

  // The closed loop: each clip's walk against its mean cycle (the references live here).
  std::vector<eval::Normative> references;
  references.reserve(clips.size());
  TuneOptions polish = options.polish;
  polish.conditions.clear();
  for (const TrainClip& clip : clips)
    references.push_back(clip_reference(clip.report, clip.name));
  for (std::size_t k = 0; k < clips.size(); ++k) {
    polish.conditions.push_back(clip_condition(references[k], clips[k].report,
                                               clips[k].motion.segments, clips[k].step_length,
                                               options.tolerances));
  }
  for (const TrainClip& clip : clips) {
    for (const double factor : options.steps_around) {
      // Contact bounds only: timing at another step is not the clip's.
      polish.conditions.push_back({.segments = clip.motion.segments,
                                   .step_length = factor * clip.step_length,
                                   .stance = Range{0.0, 100.0},
                                   .cycle_time = Range{0.1, 10.0}});
    }
  }
  if (options.grid) {
    for (const double step : {0.50, 0.60, 0.70, 0.85}) {
      for (const double stature : {1.50, 1.75, 2.00})
        // Contact bounds only: the clip's timing is its own, not the normative ranges'.
        polish.conditions.push_back({.stature = stature,
                                     .step_length = step,
                                     .stance = Range{0.0, 100.0},
                                     .cycle_time = Range{0.1, 10.0}});
    }
  }
  polish.recovery_seeds = recovery_seeds(options.recovery_starts);
  polish.anchor = &first;
  polish.stop = options.stop;
  validate(polish);
  const ClosedLoop closed(network, polish);
  const Readability style{.digits = polish.digits,
                          .knot_gap = options.fit.knot_gap,
                          .word_unit = options.fit.word_unit};

  result.before = scores(base);
  result.cost_before = walk_cost(base, polish);
  report("base", 0, result.cost_before, &base);
  std::vector<double> best = network.values();
  double best_cost = closed.cost(best);
  if (!result.added.empty()) {
    result.stages.push_back({"structure", best_cost, static_cast<int>(result.added.size()), 0.0});
  }

  if (options.fits) {
    std::vector<TrainingClip> data;
    for (const TrainClip& clip : clips) {
      data.push_back(training_data(clip.motion, clip.ground, clip.step_length, first,
                                   {.time_step = gait::WalkerOptions{}.time_step}));
    }
    FitOptions fit = options.fit;
    fit.stop = options.stop;
    fit.progress = [&](const FitProgress& p) { report(p.stage, p.iteration, p.cost, nullptr); };
    std::vector<std::size_t> every;
    for (std::size_t i = 0; i < network.size(); ++i)
      every.push_back(i);
    auto stage = [&](const std::string& name, const std::vector<double>& candidate) {
      const Clock::time_point at = Clock::now();
      const int kept = closed.keep_better(best, best_cost, readable(network, candidate, style));
      result.stages.push_back({name, best_cost, kept, seconds_since(at)});
      report(name, 0, best_cost, nullptr);
    };
    // 1. Per frame: every controller, the inertia as it is.
    if (!stopped()) {
      const Clock::time_point at = Clock::now();
      fit.stage = "commands";
      std::vector<std::size_t> free(every.begin(), every.end() - 1);
      const FitResult r =
          fit_weights(network, data, best, free, FitData::Commands, {true, true, true, true}, fit);
      result.stages.push_back({"commands fit", r.final_cost, 0, seconds_since(at)});
      stage("commands", ordered(network, r.weights, fit.knot_gap));
    }
    // 2. Joint by joint, each with the other joints from the clips.
    if (!stopped()) {
      const Clock::time_point at = Clock::now();
      std::vector<double> w = best;
      for (std::size_t j = 0; j < 4 && !stopped(); ++j) {
        std::vector<std::size_t> free;
        for (const gait::LegPhase phase : {gait::LegPhase::Swing, gait::LegPhase::Stance}) {
          for (std::size_t i : network.slot_weights(gait::slot(phase, static_cast<gait::Joint>(j))))
            free.push_back(i);
        }
        std::array<bool, 4> simulated{};
        simulated[j] = true;
        fit.stage =
            std::string("joints: ") + std::string(gait::slot_name(static_cast<int>(j))).substr(6);
        w = ordered(
            network,
            fit_weights(network, data, w, free, FitData::Trajectories, simulated, fit).weights,
            fit.knot_gap);
      }
      result.stages.push_back({"joints fit", 0.0, 0, seconds_since(at)});
      stage("joints", w);
    }
    // 3. Coupled: every controller and the inertia, the joints of a leg together.
    if (!stopped()) {
      const Clock::time_point at = Clock::now();
      fit.stage = "coupled";
      const FitResult r = fit_weights(network, data, best, every, FitData::Trajectories,
                                      {true, true, true, true}, fit);
      result.stages.push_back({"coupled fit", r.final_cost, 0, seconds_since(at)});
      stage("coupled", ordered(network, r.weights, fit.knot_gap));
    }
  }
  best = readable(network, best, style);
  gait::ControllerSet trained = network.apply(best);
  best_cost = closed.cost(best);
  report("fitted", 0, best_cost, &trained);

  // 4. The closed loop, by the tuner.
  if (!stopped() && polish.generations > 0) {
    const Clock::time_point at = Clock::now();
    polish.progress = [&](int generation, double cost) {
      report("polish", generation, cost, nullptr);
    };
    polish.best = [&](int generation, const gait::ControllerSet& set) {
      if (generation % 25 == 0) report("polish", generation, 0.0, &set);
    };
    const TuneResult tuned = tune(trained, polish);
    // The tuner's values, rounded, with the words' promises kept.
    const std::vector<double> polished =
        readable(network, SetNetwork(tuned.rounded).values(), style);
    const double polished_cost = closed.cost(polished);
    if (polished_cost < best_cost) {
      best = polished;
      trained = network.apply(best);
      best_cost = polished_cost;
    }
    result.stages.push_back({"polish", best_cost, 0, seconds_since(at)});
  }
  result.set = trained;
  for (AddedWord& w : result.added) {
    const std::string name = std::string(gait::slot_name(w.slot)) + "." + w.input + "." + w.word;
    w.peak = best[network.find(name)];
  }
  result.cost_after = best_cost;
  result.after = scores(trained);
  result.stopped = stopped();
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace fuzzygait::learn
