#include "fuzzygait/learn/fit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "offline/learn/replay.hpp"
#include "offline/learn/set_edit.hpp"
#include "offline/learn/words.hpp"

namespace fuzzygait::learn {
namespace {

using detail::Run;

// Jets carry this many derivatives at a time: a fit of k free weights evaluates its residuals
// ceil(k / kStride) times per Jacobian.
constexpr int kStride = 8;

// The full weight vector in scalar T: `start` with the free weights from the parameter block.
template <class T>
std::vector<T> full_weights(std::span<const double> start, std::span<const std::size_t> free,
                            const T* parameters) {
  std::vector<T> w(start.size());
  for (std::size_t i = 0; i < start.size(); ++i)
    w[i] = T(start[i]);
  for (std::size_t k = 0; k < free.size(); ++k)
    w[free[k]] = parameters[k];
  return w;
}

// The residuals of one run of one clip: trajectory or command errors, in units.
class DataCost {
 public:
  DataCost(const SetNetwork& network, const TrainingClip& clip, Run run,
           std::span<const double> start, std::span<const std::size_t> free, FitData data,
           const std::array<bool, 4>& simulated, double scale)
      : network_(network),
        clip_(clip),
        run_(run),
        start_(start),
        free_(free),
        data_(data),
        simulated_(simulated),
        scale_(scale) {}

  // Calls residual(value) for each residual, in a fixed order.
  template <class T, class Residual>
  void residuals(const T* parameters, Residual residual) const {
    const std::vector<T> w = full_weights(start_, free_, parameters);
    const T follow = gait::detail::follow_share(clip_.time_step, w[network_.inertia_index()]);
    if (data_ == FitData::Trajectories) {
      detail::replay_run(network_, w.data(), clip_, run_, simulated_, follow,
                         [&](std::size_t, std::size_t, const T& e) { residual(T(e * scale_)); });
    } else {
      detail::command_errors(
          network_, w.data(), clip_, run_, follow,
          [&](std::size_t, std::size_t, const T& e) { residual(T(e * scale_)); });
    }
  }

  template <class T>
  bool operator()(T const* const* parameters, T* out) const {
    std::size_t i = 0;
    residuals(parameters[0], [&](const T& r) { out[i++] = r; });
    return true;
  }

  std::size_t count(const double* parameters) const {
    std::size_t n = 0;
    residuals(parameters, [&n](double) { ++n; });
    return n;
  }

 private:
  const SetNetwork& network_;
  const TrainingClip& clip_;
  Run run_;
  std::span<const double> start_;
  std::span<const std::size_t> free_;
  FitData data_;
  std::array<bool, 4> simulated_;
  double scale_;
};

// The readability terms over the free weights: the pull toward the base, the knots' order, the
// output words' promises.
class ReadabilityCost {
 public:
  ReadabilityCost(const SetNetwork& network, std::span<const double> start,
                  std::span<const std::size_t> free, const FitOptions& o)
      : network_(network), start_(start), free_(free), options_(o) {
    std::vector<bool> is_free(network.size(), false);
    for (std::size_t i : free)
      is_free[i] = true;
    for (int s = 0; s < gait::kSlotCount; ++s) {
      const std::vector<std::size_t>& weights = network.slot_weights(s);
      bool outputs_free = false;
      for (std::size_t i : weights) {
        const NetworkWeight& k = network.weight(i);
        if (k.kind == WeightKind::Output && is_free[i]) outputs_free = true;
        if (k.kind != WeightKind::Knot) continue;
        // Each interior knot against the knot below it, and the last against the range's end;
        // only pairs with a free knot.
        const std::size_t above = network.next_knot(i);
        if (is_free[i] || (above < network.size() && is_free[above])) {
          orders_.push_back({i, above, false});
        }
        if (network.first_knot(i) && is_free[i]) orders_.push_back({i, i, true});
      }
      if (!outputs_free) continue;
      const fuzzy::OutputVariable& out =
          network.base().controllers[static_cast<std::size_t>(s)].engine().outputs.at(0);
      Words words;
      words.unit = o.word_unit * (out.maximum - out.minimum);
      words.promises = detail::word_promises(out);
      for (std::size_t i : weights) {
        if (network.weight(i).kind == WeightKind::Output) words.terms.push_back(i);
      }
      words_.push_back(std::move(words));
    }
  }

  std::size_t count() const {
    std::size_t n = free_.size() + orders_.size();
    for (const Words& w : words_)
      n += w.promises.size();
    return n;
  }

  template <class T>
  bool operator()(T const* const* parameters, T* out) const {
    const std::vector<T> w = full_weights(start_, free_, parameters[0]);
    std::size_t r = 0;
    const double prior = std::sqrt(options_.prior);
    for (std::size_t i : free_) {
      out[r++] = T(w[i] - network_.values()[i]) * (prior / network_.range(i));
    }
    const double order = std::sqrt(options_.order);
    for (const Order& p : orders_) {
      const double range = network_.range(p.knot);
      const double gap = options_.knot_gap * range;
      // (the knot below `knot`, or the range's start) + gap <= knot; knot + gap <= above.
      T low;
      T high;
      if (p.against_start) {
        low = T(network_.knot_below(p.knot, network_.values()));
        high = w[p.knot];
      } else {
        low = w[p.knot];
        high = p.above < network_.size() ? w[p.above]
                                         : T(network_.knot_above(p.knot, network_.values()));
      }
      const T short_by = T(low + gap - high);
      out[r++] = (short_by > 0.0 ? short_by : T(0.0)) * (order / range);
    }
    const double words = std::sqrt(options_.words);
    std::vector<T> values;
    for (const Words& group : words_) {
      values.assign(group.terms.size(), T(0.0));
      for (std::size_t t = 0; t < group.terms.size(); ++t)
        values[t] = w[group.terms[t]];
      for (const detail::WordPromise& p : group.promises)
        out[r++] = detail::broken_by(p, values.data(), group.unit) * words;
    }
    return true;
  }

 private:
  struct Order {
    std::size_t knot;
    std::size_t above;   // the next interior knot, or size() for the range's end
    bool against_start;  // this pair is the range's start and the first interior knot
  };
  struct Words {
    std::vector<std::size_t> terms;  // the output terms' weights, in term order
    std::vector<detail::WordPromise> promises;
    double unit = 1.0;
  };
  const SetNetwork& network_;
  std::span<const double> start_;
  std::span<const std::size_t> free_;
  const FitOptions& options_;
  std::vector<Order> orders_;
  std::vector<Words> words_;
};

class Progress : public ceres::IterationCallback {
 public:
  explicit Progress(const FitOptions& o) : options_(o) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (options_.progress) options_.progress({options_.stage, s.iteration, s.cost});
    if (options_.stop && options_.stop()) {
      stopped = true;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }
  bool stopped = false;

 private:
  const FitOptions& options_;
};

}  // namespace

FitResult fit_weights(const SetNetwork& network, std::span<const TrainingClip> clips,
                      std::span<const double> start, std::span<const std::size_t> free,
                      FitData data, const std::array<bool, 4>& simulated,
                      const FitOptions& options) {
  if (start.size() != network.size()) {
    throw std::invalid_argument("fit_weights: the start has " + std::to_string(start.size()) +
                                " weights, the network " + std::to_string(network.size()));
  }
  if (clips.empty()) throw std::invalid_argument("fit_weights: no training clips");
  for (std::size_t i : free) {
    if (i >= network.size())
      throw std::invalid_argument("fit_weights: no weight " + std::to_string(i));
  }
  FitResult result;
  result.weights.assign(start.begin(), start.end());
  if (free.empty()) return result;
  std::vector<double> x(free.size());
  for (std::size_t k = 0; k < free.size(); ++k)
    x[k] = start[free[k]];

  // Every run of every clip that has residuals, and how many there are in all.
  struct Block {
    const TrainingClip* clip;
    Run run;
    std::size_t count;
  };
  std::vector<Block> blocks;
  std::size_t total = 0;
  for (const TrainingClip& clip : clips) {
    for (const Run& run : detail::phase_runs(clip)) {
      const DataCost probe(network, clip, run, start, free, data, simulated, 1.0);
      const std::size_t n = probe.count(x.data());
      if (n == 0) continue;
      blocks.push_back({&clip, run, n});
      total += n;
    }
  }
  if (total == 0) {
    throw std::invalid_argument("fit_weights: no controller drives a joint in the training clips");
  }
  const double unit = data == FitData::Trajectories ? options.angle_unit : options.command_unit;
  const double scale = 1.0 / (unit * std::sqrt(static_cast<double>(total)));
  const auto k = static_cast<int>(free.size());

  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  for (const Block& b : blocks) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<DataCost, kStride>(
        new DataCost(network, *b.clip, b.run, start, free, data, simulated, scale));
    cost->AddParameterBlock(k);
    cost->SetNumResiduals(static_cast<int>(b.count));
    problem.AddResidualBlock(cost, nullptr, x.data());
  }
  auto* readable = new ReadabilityCost(network, start, free, options);
  auto* readable_cost = new ceres::DynamicAutoDiffCostFunction<ReadabilityCost, kStride>(readable);
  readable_cost->AddParameterBlock(k);
  readable_cost->SetNumResiduals(static_cast<int>(readable->count()));
  problem.AddResidualBlock(readable_cost, nullptr, x.data());
  // Knots within their input's range, outputs within one and a half times theirs, the inertia
  // within its bounds.
  for (std::size_t j = 0; j < free.size(); ++j) {
    const std::size_t i = free[j];
    const NetworkWeight& w = network.weight(i);
    const auto at = static_cast<int>(j);
    double low = 0.0;
    double high = 0.0;
    if (w.kind == WeightKind::Knot) {
      low = network.input_start(i);
      high = network.input_end(i);
    } else if (w.kind == WeightKind::Output) {
      low = -1.5 * network.range(i);
      high = 1.5 * network.range(i);
    } else {
      low = options.shortest_inertia;
      high = options.longest_inertia;
    }
    x[j] = std::clamp(x[j], low, high);
    problem.SetParameterLowerBound(x.data(), at, low);
    problem.SetParameterUpperBound(x.data(), at, high);
  }

  ceres::Solver::Options solver;
  solver.minimizer_type = ceres::TRUST_REGION;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = std::max(1, options.threads);
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  Progress progress(options);
  solver.callbacks.push_back(&progress);
  solver.update_state_every_iteration = false;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  for (std::size_t j = 0; j < free.size(); ++j)
    result.weights[free[j]] = x[j];
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.stopped = progress.stopped;
  return result;
}

std::array<double, 4> replay_rmse(const SetNetwork& network, std::span<const TrainingClip> clips,
                                  std::span<const double> w, bool coupled) {
  std::array<double, 4> squares{};
  std::array<std::size_t, 4> counts{};
  for (const TrainingClip& clip : clips) {
    const double follow = gait::detail::follow_share(clip.time_step, w[network.inertia_index()]);
    for (const Run& run : detail::phase_runs(clip)) {
      for (std::size_t joint = 0; joint < 4; ++joint) {
        if (coupled && joint > 0) break;
        std::array<bool, 4> simulated{};
        if (coupled) {
          simulated.fill(true);
        } else {
          simulated[joint] = true;
        }
        detail::replay_run(network, w.data(), clip, run, simulated, follow,
                           [&](std::size_t, std::size_t j, double e) {
                             squares[j] += e * e;
                             ++counts[j];
                           });
      }
    }
  }
  std::array<double, 4> rmse{};
  for (std::size_t j = 0; j < 4; ++j) {
    rmse[j] = counts[j] == 0 ? 0.0 : std::sqrt(squares[j] / static_cast<double>(counts[j]));
  }
  return rmse;
}

std::vector<double> ordered(const SetNetwork& network, std::span<const double> w, double gap) {
  std::vector<double> out(w.begin(), w.end());
  // Upwards from each input's first interior knot, then downwards from its last.
  for (std::size_t i = 0; i < network.size(); ++i) {
    if (network.weight(i).kind != WeightKind::Knot) continue;
    const double least = network.knot_below(i, out) + gap * network.range(i);
    out[i] = std::max(out[i], least);
  }
  for (std::size_t i = network.size(); i-- > 0;) {
    if (network.weight(i).kind != WeightKind::Knot) continue;
    const double most = network.knot_above(i, out) - gap * network.range(i);
    out[i] = std::min(out[i], most);
  }
  return out;
}

std::vector<double> readable(const SetNetwork& network, std::span<const double> w,
                             const Readability& r) {
  std::vector<double> out(w.begin(), w.end());
  for (double& v : out)
    v = detail::round_significant(v, r.digits);
  for (int s = 0; s < gait::kSlotCount; ++s) {
    const fuzzy::OutputVariable& variable =
        network.base().controllers[static_cast<std::size_t>(s)].engine().outputs.at(0);
    std::vector<std::size_t> terms;
    for (std::size_t i : network.slot_weights(s)) {
      if (network.weight(i).kind == WeightKind::Output) terms.push_back(i);
    }
    std::vector<double> values;
    for (std::size_t i : terms)
      values.push_back(out[i]);
    detail::keep_promises(values, detail::word_promises(variable),
                          r.word_unit * (variable.maximum - variable.minimum));
    for (std::size_t t = 0; t < terms.size(); ++t)
      out[terms[t]] = values[t];
  }
  return ordered(network, out, r.knot_gap);
}

}  // namespace fuzzygait::learn
