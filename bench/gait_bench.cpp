// `fuzzygait-bench gait`: character-steps per second on one core with a controller set, for a lone
// walker and for a crowd stepped together (gait::Crowd), each against the same walk with the same
// controllers evaluated through fuzzylite in the loop (a controller back end). The
// walks must give the same motion before anything is timed: the controllers' outputs agree within
// 1e-9 call by call, the walks' heel strikes (time and place), final pelvis and joint angles are
// identical, and every character of a crowd walks to the bit as it does alone. The last two lines
// are the crowd's (many characters on one core, the way a game steps them), or with --crowd 0 the
// lone walker's.
#include <fl/Headers.h>

#include <malloc.h>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "fuzzygait/fuzzy/fll.hpp"
#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/gait/crowd.hpp"
#include "fuzzygait/gait/walker.hpp"
#include "fuzzygait/rig/rig.hpp"
#include "fuzzygait/terrain/terrain.hpp"
#include "runtime/gait/walker_stages.hpp"
#include "timing.hpp"

namespace fuzzygait::bench {
namespace {

struct Options {
  std::string style = "default";
  std::string controllers;   // a controller set folder instead of a built-in style
  double min_seconds = 0.2;  // wall time per repetition, per side
  int repetitions = 5;
  double warm_up = 2.0;       // simulated seconds walked before timing
  double check_seconds = 20;  // simulated seconds of the motion comparison
  int crowd = 1024;           // characters in the crowd (0: no crowd)
};

// A game advances its characters once per frame; the walker subdivides into time steps.
constexpr double kFrame = 1.0 / 60.0;

// The set's controllers as fuzzylite engines, read from the FLL fuzzygait writes for them.
class FuzzyliteControllers {
 public:
  explicit FuzzyliteControllers(const gait::ControllerSet& set) {
    for (std::size_t s = 0; s < slots_.size(); ++s) {
      const gait::Controller& c = set.controllers[s];
      Slot& slot = slots_[s];
      slot.engine.reset(fl::FllImporter().fromString(fuzzy::write_fll(c.engine())));
      std::string status;
      if (!slot.engine->isReady(&status)) {
        throw std::runtime_error(c.source() + ": fuzzylite cannot run it: " + status);
      }
      slot.input_count = c.input_count();
      for (std::size_t i = 0; i < c.input_count(); ++i) {
        slot.metrics[i] = static_cast<std::size_t>(c.input(i));
        slot.inputs[i] = slot.engine->getInputVariable(std::string(gait::metric_name(c.input(i))));
      }
      slot.output = slot.engine->getOutputVariable(0);
    }
  }

  double evaluate(int slot_index, const gait::MetricValues& metrics) {
    Slot& slot = slots_[static_cast<std::size_t>(slot_index)];
    for (std::size_t i = 0; i < slot.input_count; ++i) {
      slot.inputs[i]->setValue(metrics[slot.metrics[i]]);
    }
    slot.engine->process();
    return slot.output->getValue();
  }

 private:
  struct Slot {
    std::unique_ptr<fl::Engine> engine;
    std::size_t input_count = 0;
    std::array<std::size_t, 2> metrics{};
    std::array<fl::InputVariable*, 2> inputs{};
    fl::OutputVariable* output = nullptr;
  };
  std::array<Slot, gait::kSlotCount> slots_;
};

int steps_per_frame(const gait::WalkerOptions& options) {
  return std::max(1, static_cast<int>(std::ceil(kFrame / options.time_step - 1e-9)));
}

// One side of a comparison: the walkers' options and, for fuzzylite's side, the controller back
// end that evaluates their controllers (null: fuzzygait's own).
struct Side {
  gait::WalkerOptions options;
  const gait::detail::ControllerBackend* backend = nullptr;
};

gait::Walker make_walker(const gait::ControllerSet& set, const Side& side,
                         const terrain::Terrain& ground) {
  return gait::detail::WalkerStages::make_walker(set, side.options, ground, side.backend);
}

// A fresh walker on flat ground, past its warm-up.
gait::Walker walker_after_warm_up(const gait::ControllerSet& set, const Side& side,
                                  const terrain::Terrain& ground, double warm_up) {
  gait::Walker walker = make_walker(set, side, ground);
  for (double t = 0.0; t < warm_up; t += kFrame) {
    walker.advance(kFrame);
    walker.clear_events();
  }
  return walker;
}

// Wall seconds to walk `frames` frames, clearing the events every frame as a game would: a
// Walker, a Crowd, or walkers InTurn.
template <class Walkers>
double seconds_for(Walkers& walkers, long frames) {
  return wall_seconds([&] {
    for (long f = 0; f < frames; ++f) {
      walkers.advance(kFrame);
      walkers.clear_events();
    }
  });
}

// Lone walkers advanced one after another, as a game without a crowd would.
struct InTurn {
  std::vector<gait::Walker> walkers;
  void advance(double dt) {
    for (gait::Walker& w : walkers)
      w.advance(dt);
  }
  void clear_events() {
    for (gait::Walker& w : walkers)
      w.clear_events();
  }
};

// Frames that take about `min_seconds` on a fresh walker, from 16 frames up.
long frames_for(const gait::ControllerSet& set, const Side& side, const terrain::Terrain& ground,
                const Options& o) {
  return calibrate(16, o.min_seconds, [&](long frames) {
    gait::Walker walker = walker_after_warm_up(set, side, ground, o.warm_up);
    return seconds_for(walker, frames);
  });
}

// The walk the motion check compares: heel strikes, and the pose every frame.
struct Trace {
  std::vector<gait::EventRecord> heel_strikes;
  std::vector<rig::Pose> poses;
};

Trace trace(const gait::ControllerSet& set, const Side& side, const terrain::Terrain& ground,
            double seconds) {
  gait::Walker walker = make_walker(set, side, ground);
  Trace t;
  for (double time = 0.0; time < seconds; time += kFrame) {
    walker.advance(kFrame);
    for (const gait::EventRecord& e : walker.events()) {
      if (e.event == gait::Event::HeelStrike) t.heel_strikes.push_back(e);
    }
    walker.clear_events();
    t.poses.push_back(walker.pose());
  }
  return t;
}

// Walks with fuzzylite in the loop while evaluating fuzzygait on the same metrics, and compares
// the walk with fuzzygait's own; prints the figures, then throws std::runtime_error unless the
// controllers' outputs agree within 1e-9 and the walks are identical.
void check_motion(const gait::ControllerSet& set, const gait::WalkerOptions& options,
                  const terrain::Terrain& ground, const Options& o) {
  FuzzyliteControllers fuzzylite(set);
  std::array<fuzzy::Workspace, gait::kSlotCount> workspaces;
  for (std::size_t s = 0; s < workspaces.size(); ++s) {
    workspaces[s] = set.controllers[s].make_workspace();
  }
  double output_difference = 0.0;
  long calls = 0;
  gait::detail::ControllerBackend checked;
  checked.evaluate = [&](int slot, const gait::MetricValues& metrics) {
    const auto s = static_cast<std::size_t>(slot);
    const double reference = fuzzylite.evaluate(slot, metrics);
    const double ours = set.controllers[s].evaluate(metrics, workspaces[s]);
    const double difference = std::isnan(reference) != std::isnan(ours)
                                  ? std::numeric_limits<double>::infinity()
                                  : (std::isnan(reference) ? 0.0 : std::abs(reference - ours));
    output_difference = std::max(output_difference, difference);
    ++calls;
    return reference;
  };
  const Trace expected = trace(set, {options, &checked}, ground, o.check_seconds);
  const Trace got = trace(set, {options}, ground, o.check_seconds);

  // The figures printed, and exact comparisons for the verdict (a NaN compares unequal too).
  double strike_time = 0.0;
  double strike_x = 0.0;
  bool same_strikes = expected.heel_strikes.size() == got.heel_strikes.size();
  const std::size_t strikes = std::min(expected.heel_strikes.size(), got.heel_strikes.size());
  for (std::size_t i = 0; i < strikes; ++i) {
    const gait::EventRecord& a = expected.heel_strikes[i];
    const gait::EventRecord& b = got.heel_strikes[i];
    strike_time = std::max(strike_time, std::abs(a.time - b.time));
    strike_x = std::max(strike_x, std::abs(a.where.x - b.where.x));
    same_strikes =
        same_strikes && a.time == b.time && a.where.x == b.where.x && a.where.y == b.where.y;
  }
  double joint = 0.0;
  bool same_joints = expected.poses.size() == got.poses.size();
  for (std::size_t f = 0; f < std::min(expected.poses.size(), got.poses.size()); ++f) {
    for (std::size_t leg = 0; leg < 2; ++leg) {
      const rig::LegAngles& a = expected.poses[f].legs[leg];
      const rig::LegAngles& b = got.poses[f].legs[leg];
      for (double d : {a.hip - b.hip, a.knee - b.knee, a.ankle - b.ankle, a.toe - b.toe}) {
        joint = std::max(joint, std::abs(rig::degrees(d)));
      }
      same_joints =
          same_joints && a.hip == b.hip && a.knee == b.knee && a.ankle == b.ankle && a.toe == b.toe;
    }
  }
  const rig::Point p = expected.poses.back().pelvis;
  const rig::Point q = got.poses.back().pelvis;
  const bool same_pelvis = p.x == q.x && p.y == q.y;
  const long steps =
      std::lround(static_cast<double>(expected.poses.size()) * kFrame / options.time_step);
  std::printf(
      "motion check, %.0f s walked (%ld steps) with fuzzylite in the loop against fuzzygait:\n"
      "  controller outputs  max |diff| %.3g over %ld calls\n"
      "  heel strikes        %zu vs %zu, max |diff| %.3g s in time, %.3g m in x\n"
      "  pelvis at the end   max |diff| %.3g m (x %.6f m)\n"
      "  joint angles        max |diff| %.3g deg over %zu frames\n",
      o.check_seconds, steps, output_difference, calls, expected.heel_strikes.size(),
      got.heel_strikes.size(), strike_time, strike_x,
      std::max(std::abs(p.x - q.x), std::abs(p.y - q.y)), q.x, joint, got.poses.size());
  std::fflush(stdout);
  if (!(output_difference <= 1e-9)) {
    throw std::runtime_error("fuzzylite and fuzzygait controller outputs differ by more than 1e-9");
  }
  if (!same_strikes) {
    throw std::runtime_error("the walks with fuzzylite and fuzzygait differ in heel strikes");
  }
  if (!same_pelvis) {
    throw std::runtime_error(
        "the walks with fuzzylite and fuzzygait end with the pelvis elsewhere");
  }
  if (!same_joints) {
    throw std::runtime_error("the walks with fuzzylite and fuzzygait differ in joint angles");
  }
}

// A crowd of the default character at phases spread over a stride: warm-ups from 3.0 to 4.1 s (a
// gait cycle is about 1.1 s), stepped by the golden ratio so that neighbours differ.
std::vector<gait::WalkerOptions> crowd_characters(const gait::WalkerOptions& options, int count) {
  std::vector<gait::WalkerOptions> characters(static_cast<std::size_t>(count), options);
  for (std::size_t i = 0; i < characters.size(); ++i) {
    const double golden = 0.6180339887498949 * static_cast<double>(i);
    characters[i].start.warm_up = 3.0 + 1.1 * (golden - std::floor(golden));
  }
  return characters;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Walks a crowd and each of its characters alone side by side, frame by frame: throws
// std::runtime_error unless every pose and every event is the same to the bit.
void check_crowd(const gait::ControllerSet& set, const gait::WalkerOptions& options,
                 const terrain::Terrain& ground, const Options& o) {
  const std::vector<gait::WalkerOptions> characters =
      crowd_characters(options, std::min(o.crowd, 64));
  gait::Crowd crowd(set, ground, characters);
  std::vector<gait::Walker> alone;
  for (const gait::WalkerOptions& c : characters)
    alone.emplace_back(set, c, ground);
  long frames = 0;
  long events = 0;
  bool same = true;
  for (double time = 0.0; time < o.check_seconds; time += kFrame, ++frames) {
    crowd.advance(kFrame);
    for (std::size_t i = 0; i < alone.size(); ++i) {
      gait::Walker& lone = alone[i];
      lone.advance(kFrame);
      const rig::Pose a = crowd[i].pose();
      const rig::Pose b = lone.pose();
      same = same && same_bits(a.pelvis.x, b.pelvis.x) && same_bits(a.pelvis.y, b.pelvis.y);
      for (std::size_t leg = 0; leg < 2; ++leg) {
        const rig::LegAngles& p = a.legs[leg];
        const rig::LegAngles& q = b.legs[leg];
        same = same && same_bits(p.hip, q.hip) && same_bits(p.knee, q.knee) &&
               same_bits(p.ankle, q.ankle) && same_bits(p.toe, q.toe);
      }
      const std::vector<gait::EventRecord>& e = crowd[i].events();
      const std::vector<gait::EventRecord>& f = lone.events();
      same = same && e.size() == f.size();
      for (std::size_t k = 0; same && k < e.size(); ++k) {
        same = same_bits(e[k].time, f[k].time) && e[k].event == f[k].event &&
               e[k].side == f[k].side && same_bits(e[k].where.x, f[k].where.x) &&
               same_bits(e[k].where.y, f[k].where.y);
      }
      events += static_cast<long>(e.size());
      lone.clear_events();
    }
    crowd.clear_events();
  }
  std::printf(
      "crowd check, %.0f s walked by %zu characters stepped together against each alone: %s "
      "(%ld frames, %ld contact events; controllers %s)\n",
      o.check_seconds, alone.size(), same ? "identical to the bit" : "DIFFERENT", frames, events,
      crowd.batched_controllers() ? "evaluated across characters" : "per character");
  std::fflush(stdout);
  if (!same) throw std::runtime_error("a crowd's character walks differently from a lone walker");
}

// The crowd: its characters checked against themselves alone, then walked with the set's
// controllers and with fuzzylite's in turn. Each crowd is built once (a fuzzylite crowd's warm-up
// alone takes seconds) and walks on from one repetition to the next, in its steady gait.
// Returns the medians, ns a character-step: {ours, fuzzylite's}.
std::pair<double, double> run_crowd_benchmark(const gait::ControllerSet& set,
                                              const gait::WalkerOptions& options,
                                              const gait::detail::ControllerBackend& fuzzylite,
                                              const terrain::Terrain& ground, const Options& o) {
  check_crowd(set, options, ground, o);
  const std::vector<gait::WalkerOptions> characters = crowd_characters(options, o.crowd);
  gait::Crowd ours(set, ground, characters);
  const std::vector<const gait::detail::ControllerBackend*> through_fuzzylite(characters.size(),
                                                                              &fuzzylite);
  gait::Crowd theirs =
      gait::detail::WalkerStages::make_crowd(set, ground, characters, through_fuzzylite);
  // The same characters as lone walkers, advanced one after another every frame.
  InTurn in_turn;
  for (const gait::WalkerOptions& c : characters)
    in_turn.walkers.emplace_back(set, c, ground);
  const double steps_in_frame =
      steps_per_frame(options) * static_cast<double>(o.crowd);  // character-steps
  auto frames_to_time = [&](auto& walkers) {
    return calibrate(1, o.min_seconds, [&](long frames) { return seconds_for(walkers, frames); });
  };
  const long our_frames = frames_to_time(ours);
  const long their_frames = frames_to_time(theirs);
  const long in_turn_frames = frames_to_time(in_turn);
  std::vector<double> our_ns;
  std::vector<double> their_ns;
  std::vector<double> in_turn_ns;
  auto time_walk = [&](auto& walkers, long frames, std::vector<double>& ns) {
    const double seconds = seconds_for(walkers, frames);
    ns.push_back(1e9 * seconds / (static_cast<double>(frames) * steps_in_frame));
  };
  for (int r = 0; r < o.repetitions; ++r) {
    run_alternating(
        r,
        [&] {
          time_walk(ours, our_frames, our_ns);
          time_walk(in_turn, in_turn_frames, in_turn_ns);
        },
        [&] { time_walk(theirs, their_frames, their_ns); });
    std::printf(
        "crowd run %d: fuzzygait %8.1f ns per character-step (%ld frames), the same characters "
        "in turn %8.1f ns (%ld frames), fuzzylite %8.1f ns (%ld frames)\n",
        r + 1, our_ns.back(), our_frames, in_turn_ns.back(), in_turn_frames, their_ns.back(),
        their_frames);
    std::fflush(stdout);
  }
  const double a = median(our_ns);
  const double c = median(in_turn_ns);
  const double b = median(their_ns);
  std::printf(
      "crowd of %d characters stepped together (gait::Crowd), one core:\n"
      "  fuzzygait %8.1f ns per character-step, %6.3f M character-steps per second "
      "(%.0f characters in real time)\n"
      "  in turn   %8.1f ns per character-step, %6.3f M (the same walkers advanced one by one)\n"
      "  fuzzylite %8.1f ns per character-step, %6.3f M; speedup %.2f\n",
      o.crowd, a, 1e3 / a, options.time_step * 1e9 / a, c, 1e3 / c, b, 1e3 / b, b / a);
  return {a, b};
}

// Median ns a step of a lone default walker, through the set's controllers and through
// fuzzylite's (timed alternately, each on a fresh walker after its warm-up), printing each run
// when asked.
std::pair<double, double> lone_walker_ns(const gait::ControllerSet& set,
                                         const gait::detail::ControllerBackend& fuzzylite,
                                         const terrain::Terrain& ground, const Options& o,
                                         bool print_runs) {
  const gait::WalkerOptions options;
  const Side own{options};
  const Side through_fuzzylite{options, &fuzzylite};
  const double steps_in_frame = steps_per_frame(options);
  const long fuzzygait_frames = frames_for(set, own, ground, o);
  const long fuzzylite_frames = frames_for(set, through_fuzzylite, ground, o);
  std::vector<double> fuzzygait_ns;
  std::vector<double> fuzzylite_ns;
  auto time_side = [&](const Side& side, long frames, std::vector<double>& ns) {
    gait::Walker walker = walker_after_warm_up(set, side, ground, o.warm_up);
    const double seconds = seconds_for(walker, frames);
    ns.push_back(1e9 * seconds / (static_cast<double>(frames) * steps_in_frame));
  };
  for (int r = 0; r < o.repetitions; ++r) {
    run_alternating(
        r, [&] { time_side(own, fuzzygait_frames, fuzzygait_ns); },
        [&] { time_side(through_fuzzylite, fuzzylite_frames, fuzzylite_ns); });
    if (!print_runs) continue;
    std::printf(
        "run %d: fuzzygait %8.1f ns per step (%ld steps), fuzzylite %8.1f ns per step "
        "(%ld steps)\n",
        r + 1, fuzzygait_ns.back(),
        static_cast<long>(static_cast<double>(fuzzygait_frames) * steps_in_frame),
        fuzzylite_ns.back(),
        static_cast<long>(static_cast<double>(fuzzylite_frames) * steps_in_frame));
    std::fflush(stdout);
  }
  return {median(fuzzygait_ns), median(fuzzylite_ns)};
}

void run_gait_benchmark(const Options& o) {
  const gait::ControllerSet set = o.controllers.empty() ? gait::ControllerSet::builtin(o.style)
                                                        : gait::ControllerSet::load(o.controllers);
  const terrain::Terrain ground = terrain::Terrain::flat();
  const gait::WalkerOptions options;
  FuzzyliteControllers fuzzylite(set);
  const gait::detail::ControllerBackend fuzzylite_backend{
      [&fuzzylite](int slot, const gait::MetricValues& m) { return fuzzylite.evaluate(slot, m); }};

  const double steps_in_frame = steps_per_frame(options);
  std::printf(
      "fuzzygait-bench gait: controller set '%s', flat ground, time step %.6g s, frames of "
      "1/60 s (%g steps); one thread; median of %d repetitions of >= %.2f s per side, each on a "
      "fresh walker after %.1f s of walking; fuzzylite %s\n",
      set.name.c_str(), options.time_step, steps_in_frame, o.repetitions, o.min_seconds, o.warm_up,
      fl::fuzzylite::version().c_str());
  check_motion(set, options, ground, o);

  const auto [ours, theirs] = lone_walker_ns(set, fuzzylite_backend, ground, o, true);
  for (const auto& [label, ns] : {std::pair{"fuzzygait", ours}, std::pair{"fuzzylite", theirs}}) {
    std::printf("%-10s %8.1f ns per step, %6.3f M steps per second, real-time factor %.0f\n", label,
                ns, 1e3 / ns, options.time_step * 1e9 / ns);
  }
  double headline = ours;
  double headline_fuzzylite = theirs;
  if (o.crowd > 0) {
    std::tie(headline, headline_fuzzylite) =
        run_crowd_benchmark(set, options, fuzzylite_backend, ground, o);
  }
  std::printf("headline: %s\n", o.crowd > 0 ? "the crowd's character-steps (a lone walker's above)"
                                            : "the lone walker's steps");
  std::printf("character-steps per second: %.0f\n", 1e9 / headline);
  std::printf("speedup vs fuzzylite: %.2f\n", headline_fuzzylite / headline);
}

// `fuzzygait-bench crowd`'s options.
struct CrowdOptions {
  std::vector<long> sizes{100, 1000, 10000, 100000, 1000000};
  std::vector<std::size_t> threads{1, 2};  // and the machine's hardware threads
  double min_seconds = 0.5;
  int repetitions = 3;
  double spread = 1.1;  // characters' warm-ups spread over this many seconds (a gait cycle)
  double time_step = gait::WalkerOptions{}.time_step;
  // Each frame's events are read and cleared (a step makes at most four a leg): a few suffice.
  std::size_t events = 8;
};

// Bytes the allocator has handed out and not had back (glibc's mallinfo2).
std::size_t heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

void run_crowd_sizes(const CrowdOptions& c) {
  const gait::ControllerSet set = gait::ControllerSet::builtin("default");
  const terrain::Terrain ground = terrain::Terrain::flat();
  gait::WalkerOptions options;
  options.time_step = c.time_step;
  options.event_capacity = c.events;
  const double steps_in_frame = steps_per_frame(options);
  std::vector<std::size_t> thread_counts = c.threads;
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  if (std::find(thread_counts.begin(), thread_counts.end(), cores) == thread_counts.end()) {
    thread_counts.push_back(cores);
  }
  std::printf(
      "fuzzygait-bench crowd: the default set, flat ground, time step %.6g s, frames of 1/60 s "
      "(%g steps), events read and cleared every frame, %zu kept a character; characters' phases "
      "spread over %.2f s; %zu hardware threads; median of %d repetitions of >= %.2f s; "
      "fuzzylite %s\n",
      options.time_step, steps_in_frame, c.events, c.spread, static_cast<std::size_t>(cores),
      c.repetitions, c.min_seconds, fl::fuzzylite::version().c_str());
  FuzzyliteControllers fuzzylite(set);
  const gait::detail::ControllerBackend fuzzylite_backend{
      [&fuzzylite](int slot, const gait::MetricValues& m) { return fuzzylite.evaluate(slot, m); }};
  Options lone;
  lone.min_seconds = c.min_seconds;
  lone.repetitions = c.repetitions;
  const auto [lone_ns, fuzzylite_ns] = lone_walker_ns(set, fuzzylite_backend, ground, lone, false);
  std::printf("lone walker: fuzzygait %.1f ns per step, fuzzylite in the loop %.1f ns (%.2fx)\n",
              lone_ns, fuzzylite_ns, fuzzylite_ns / lone_ns);
  std::printf("%10s %8s %10s %12s %10s %9s %10s %14s\n", "characters", "threads", "bytes/char",
              "ns/char-step", "M steps/s", "vs lone", "vs fzlite", "chars at 60 Hz");
  std::fflush(stdout);
  double best_all_cores = 0.0;  // character-steps a second
  for (const long size : c.sizes) {
    std::vector<gait::WalkerOptions> characters(static_cast<std::size_t>(size), options);
    for (std::size_t i = 0; i < characters.size(); ++i) {
      const double golden = 0.6180339887498949 * static_cast<double>(i);
      characters[i].start.warm_up = c.spread * (golden - std::floor(golden));
    }
    std::vector<std::size_t> walked;  // worker counts of this size's crowds so far
    for (const std::size_t threads : thread_counts) {
      gait::CrowdOptions crowd_options;
      crowd_options.threads = threads;
      const std::size_t before = heap_in_use();
      gait::Crowd crowd(set, ground, characters, crowd_options);
      // A crowd too small for more workers than an earlier one walks as that one did.
      if (std::find(walked.begin(), walked.end(), crowd.worker_count()) != walked.end()) continue;
      walked.push_back(crowd.worker_count());
      const double bytes = static_cast<double>(heap_in_use() - before) / static_cast<double>(size);
      const long frames =
          calibrate(1, c.min_seconds, [&](long n) { return seconds_for(crowd, n); });
      std::vector<double> ns;
      for (int r = 0; r < c.repetitions; ++r) {
        ns.push_back(1e9 * seconds_for(crowd, frames) /
                     (static_cast<double>(frames) * steps_in_frame * static_cast<double>(size)));
      }
      const double a = median(ns);
      const double per_second = 1e9 / a;
      if (crowd.worker_count() == cores || threads == cores) {
        best_all_cores = std::max(best_all_cores, per_second);
      }
      std::printf("%10ld %8zu %10.0f %12.1f %10.3f %8.2fx %9.2fx %14.0f\n", size,
                  crowd.worker_count(), bytes, a, per_second / 1e6, lone_ns / a, fuzzylite_ns / a,
                  per_second / (steps_in_frame * 60.0));
      std::fflush(stdout);
    }
  }
  std::printf("characters at 60 Hz on all cores: %.0f\n", best_all_cores / (steps_in_frame * 60.0));
}

}  // namespace

void add_crowd_command(CLI::App& app) {
  auto options = std::make_shared<CrowdOptions>();
  CLI::App* crowd = app.add_subcommand(
      "crowd",
      "Crowds of 100 to 1,000,000 characters on 1, 2 and all threads: memory and character-steps "
      "per second, against a lone walker and fuzzylite");
  crowd->add_option("--sizes", options->sizes, "Crowd sizes (comma-separated)")
      ->delimiter(',')
      ->check(CLI::Range(1L, 10000000L))
      ->capture_default_str();
  crowd
      ->add_option("--threads", options->threads,
                   "Thread counts, comma-separated (the machine's hardware threads are always "
                   "added)")
      ->delimiter(',')
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  add_timing_options(*crowd, options->min_seconds, options->repetitions,
                     "Wall seconds each crowd walks per repetition, at least");
  crowd
      ->add_option("--spread", options->spread,
                   "Seconds the characters' warm-ups are spread over (their phases)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  crowd
      ->add_option("--time-step", options->time_step,
                   "The characters' time step, s (level walks keep the contact bounds up to "
                   "1/90 s: tests/gait/time_step_test.cpp)")
      ->check(CLI::Range(1e-5, 0.05))
      ->capture_default_str();
  crowd
      ->add_option("--events", options->events,
                   "Contact events each character keeps between clears (WalkerOptions::"
                   "event_capacity; 32 bytes each)")
      ->check(CLI::Range(std::size_t{0}, gait::Walker::kMostEvents))
      ->capture_default_str();
  crowd->callback([options]() { run_crowd_sizes(*options); });
}

void add_gait_command(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* gait = app.add_subcommand(
      "gait",
      "Character-steps per second of a lone walker and of a crowd, against fuzzylite in the loop");
  gait->add_option("--style", options->style, "Built-in controller set")->capture_default_str();
  gait->add_option("--controllers", options->controllers,
                   "Controller set folder (manifest.json + FLL) instead of a built-in set");
  add_timing_options(*gait, options->min_seconds, options->repetitions,
                     "Wall seconds each side walks per repetition, at least");
  gait->add_option("--warm-up", options->warm_up, "Simulated seconds walked before timing")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  gait->add_option("--crowd", options->crowd,
                   "Characters in the crowd walked after the lone walker; the crowd's figures "
                   "end the output (0: no crowd, and the lone walker's end it)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  gait->add_option("--check-time", options->check_seconds,
                   "Simulated seconds of the motion comparison with fuzzylite in the loop")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  gait->callback([options]() { run_gait_benchmark(*options); });
}

}  // namespace fuzzygait::bench
