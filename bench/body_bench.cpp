// `fuzzygait-bench body`: what one character's 60 Hz frame costs with the whole body, as a ratio
// to the walker alone: the walker, then the body bent onto a path (body::PathFollower), then posed
// on a skeleton (body::SkeletonPoser), measured in one run with the three timed in turn.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "fuzzygait/body/follower.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"
#include "timing.hpp"

namespace fuzzygait::bench {
namespace {

struct Options {
  std::string style = "default";
  int repetitions = 7;
  double window = 8.0;  // s walked while timed
};

enum class Work { Walker, Body, Skeleton };

// Wall microseconds a 60 Hz frame over `o.window` simulated seconds of a walk round a circle of
// 2 m, after two seconds.
double us_per_frame(const gait::ControllerSet& set, Work work, const Options& o) {
  const body::Humanoid humanoid = body::humanoid_from_stature(1.75);
  const body::Skeleton skeleton = body::skeleton_of(humanoid);
  const body::SkeletonPoser poser(skeleton, body::map_humanoid(skeleton));
  const terrain::Terrain ground = terrain::Terrain::flat();
  const path::Path circle({0.0, 0.0}, 0.0, {{1000.0, 0.5}});
  gait::WalkerOptions options;
  options.segments = humanoid.segments();
  options.speed = 1.3;
  gait::Walker walker(set, options, ground);
  body::PathFollower follower(humanoid, circle, walker);
  std::vector<body::Quat> rotations(poser.joint_count());
  body::Vec3 root;
  constexpr double kFrame = 1.0 / 60.0;
  for (int i = 0; i < 120; ++i)
    walker.advance(kFrame);
  const auto frames = static_cast<int>(o.window / kFrame);
  volatile double sink = 0.0;
  const double seconds = wall_seconds([&] {
    for (int i = 0; i < frames; ++i) {
      walker.advance(kFrame);
      if (work == Work::Walker) {
        sink = sink + walker.pose().pelvis.y;
      } else {
        const body::BodyPose& pose = follower.update(walker);
        if (work == Work::Skeleton) poser.pose(pose, rotations, root);
        sink = sink + pose.position[0].y;
      }
    }
  });
  return 1e6 * seconds / frames;
}

void run_body_benchmark(const Options& o) {
  const gait::ControllerSet set = gait::ControllerSet::builtin(o.style);
  const std::vector<std::pair<Work, const char*>> works = {
      {Work::Walker, "the walker alone"},
      {Work::Body, "+ the body on a path"},
      {Work::Skeleton, "+ posed on a skeleton"}};
  std::printf(
      "fuzzygait-bench body: controller set '%s', one character at 1.3 m/s round a 2 m circle, "
      "frames of 1/60 s; median of %d repetitions of %.1f s walked, the three in turn (the first "
      "one moved each repetition)\n",
      set.name.c_str(), o.repetitions, o.window);
  std::vector<std::vector<double>> us(works.size());
  for (int r = 0; r < o.repetitions; ++r) {
    for (std::size_t k = 0; k < works.size(); ++k) {
      const std::size_t w = (k + static_cast<std::size_t>(r)) % works.size();
      us[w].push_back(us_per_frame(set, works[w].first, o));
    }
  }
  const double alone = median(us[0]);
  for (std::size_t w = 0; w < works.size(); ++w) {
    const double m = median(us[w]);
    std::printf("%-24s %7.2f us a frame  %5.2fx the walker alone\n", works[w].second, m, m / alone);
  }
}

}  // namespace

void add_body_command(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "body",
      "One character's frame with the whole body on a path and a skeleton, as a ratio to "
      "the walker alone");
  add_walk_options(*command, options->style, options->repetitions, options->window);
  command->callback([options]() { run_body_benchmark(*options); });
}

}  // namespace fuzzygait::bench
