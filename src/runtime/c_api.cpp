// The C face (include/fuzzygait/fuzzygait.h) over the C++ runtime: each handle owns its C++
// object; every exception stops here and becomes an fg_error.
#include "runtime/c_api.hpp"

#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fuzzygait/rig/rig.hpp"

using namespace fuzzygait;

namespace {

using c_api::guarded;
constexpr double kNaN = c_api::kNaN;

gait::WalkerOptions options_of(const fg_walker_def& def) {
  gait::WalkerOptions o;
  o.segments = {def.thigh, def.shank, def.ankle_height, def.heel, def.ball, def.toe};
  o.step_length = def.step_length;
  o.speed = def.speed;
  o.time_step = def.time_step;
  o.start.random = def.random_start != 0;
  o.start.seed = def.start_seed;
  o.start.standing = def.standing_start != 0;
  o.event_capacity = 0;  // the C face reads no events: no room kept for them
  return o;
}

fg_pose pose_of(const gait::Walker& w) {
  const rig::Pose p = w.pose();
  fg_pose out{};
  out.pelvis_x = p.pelvis.x;
  out.pelvis_y = p.pelvis.y;
  out.pelvis_tilt = p.pelvis_tilt;
  for (std::size_t k = 0; k < 2; ++k) {
    const rig::LegAngles& a = p.legs[k];
    out.legs[k] = {a.hip, a.knee, a.ankle, a.toe};
  }
  return out;
}

rig::Side side_of(int side) {
  return side == FG_LEFT ? rig::Side::Left : rig::Side::Right;
}

}  // namespace

extern "C" {

int fg_segments_from_stature(double stature, fg_walker_def* def) {
  if (!def || !(stature >= 0.5 && stature <= 3.0)) return 0;
  c_api::set_segments(*def, rig::segments_from_stature(stature));
  return 1;
}

fg_walker_def fg_walker_def_default(void) {
  const gait::WalkerOptions o;
  fg_walker_def def{};
  fg_segments_from_stature(1.75, &def);
  def.step_length = o.step_length;
  def.speed = o.speed;
  def.time_step = o.time_step;
  def.random_start = 0;
  def.standing_start = 0;
  def.start_seed = 0;
  return def;
}

fg_set* fg_set_builtin(const char* name, fg_error* error) {
  return guarded(error, [&]() -> fg_set* {
    if (!name) throw std::invalid_argument("fg_set_builtin: no name");
    return new fg_set{gait::ControllerSet::builtin(name)};
  });
}

fg_set* fg_set_load(const char* directory, fg_error* error) {
  return guarded(error, [&]() -> fg_set* {
    if (!directory) throw std::invalid_argument("fg_set_load: no directory");
    return new fg_set{gait::ControllerSet::load(directory)};
  });
}

void fg_set_free(fg_set* set) {
  delete set;
}

fg_ground* fg_ground_flat(fg_error* error) {
  return guarded(error, [&]() -> fg_ground* { return new fg_ground{terrain::Terrain::flat()}; });
}

fg_ground* fg_ground_polyline(const double* xy, size_t count, fg_error* error) {
  return guarded(error, [&]() -> fg_ground* {
    if (!xy && count > 0) throw std::invalid_argument("fg_ground_polyline: no points");
    std::vector<rig::Point> points(count);
    for (std::size_t i = 0; i < count; ++i)
      points[i] = {xy[2 * i], xy[2 * i + 1]};
    return new fg_ground{terrain::Terrain::polyline(std::move(points))};
  });
}

double fg_ground_height(const fg_ground* ground, double x) {
  return ground ? ground->ground.height(x) : kNaN;
}

void fg_ground_free(fg_ground* ground) {
  delete ground;
}

fg_walker* fg_walker_new(const fg_set* set, const fg_walker_def* def, const fg_ground* ground,
                         fg_error* error) {
  return guarded(error, [&]() -> fg_walker* {
    if (!set || !def) throw std::invalid_argument("fg_walker_new: no set or no def");
    std::unique_ptr<terrain::Terrain> own;
    if (!ground) own = std::make_unique<terrain::Terrain>(terrain::Terrain::flat());
    const terrain::Terrain& g = ground ? ground->ground : *own;
    gait::Walker walker(set->set, options_of(*def), g);
    return new fg_walker{std::move(own), std::move(walker)};
  });
}

void fg_walker_free(fg_walker* walker) {
  delete walker;
}

int fg_walker_advance(fg_walker* walker, double dt) {
  return walker && walker->walker.advance(dt) ? 1 : 0;
}

double fg_walker_set_speed(fg_walker* walker, double metres_per_second) {
  return walker ? walker->walker.set_speed(metres_per_second) : kNaN;
}

double fg_walker_set_step_length(fg_walker* walker, double metres) {
  return walker ? walker->walker.set_step_length(metres) : kNaN;
}

double fg_walker_speed(const fg_walker* walker) {
  return walker ? walker->walker.speed() : kNaN;
}

double fg_walker_step_length(const fg_walker* walker) {
  return walker ? walker->walker.step_length() : kNaN;
}

double fg_walker_time(const fg_walker* walker) {
  return walker ? walker->walker.time() : kNaN;
}

void fg_walker_pose(const fg_walker* walker, fg_pose* pose) {
  if (walker && pose) *pose = pose_of(walker->walker);
}

void fg_walker_points(const fg_walker* walker, int side, fg_leg_points* points) {
  if (!walker || !points) return;
  const rig::LegPoints p = walker->walker.points(side_of(side));
  *points = {{p.hip.x, p.hip.y},   {p.knee.x, p.knee.y}, {p.ankle.x, p.ankle.y},
             {p.heel.x, p.heel.y}, {p.ball.x, p.ball.y}, {p.tip.x, p.tip.y}};
}

int fg_walker_in_contact(const fg_walker* walker, int side) {
  return walker && walker->walker.in_contact(side_of(side)) ? 1 : 0;
}

void fg_walker_stop(fg_walker* walker) {
  if (walker) walker->walker.stop();
}

void fg_walker_go(fg_walker* walker) {
  if (walker) walker->walker.go();
}

int fg_walker_standing(const fg_walker* walker) {
  return walker && walker->walker.standing() ? 1 : 0;
}

fg_crowd_def fg_crowd_def_default(void) {
  fg_crowd_def def{};
  def.threads = 1;
  return def;
}

fg_crowd* fg_crowd_new(const fg_set* set, const fg_walker_def* defs, size_t count,
                       const fg_ground* ground, fg_error* error) {
  return fg_crowd_new_with(set, defs, count, ground, nullptr, error);
}

fg_crowd* fg_crowd_new_with(const fg_set* set, const fg_walker_def* defs, size_t count,
                            const fg_ground* ground, const fg_crowd_def* crowd_def,
                            fg_error* error) {
  return guarded(error, [&]() -> fg_crowd* {
    if (!set || (!defs && count > 0)) throw std::invalid_argument("fg_crowd_new: no set or defs");
    gait::CrowdOptions crowd_options;
    if (crowd_def) {
      crowd_options.threads = crowd_def->threads;
      if (const fg_task_system& t = crowd_def->tasks; t.enqueue) {
        gait::TaskSystem tasks;
        tasks.worker_count = t.worker_count;
        tasks.enqueue = t.enqueue;
        tasks.finish = t.finish;
        tasks.user_context = t.user_context;
        crowd_options.tasks = tasks;
      }
    }
    std::vector<gait::WalkerOptions> characters;
    characters.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
      characters.push_back(options_of(defs[i]));
    std::unique_ptr<terrain::Terrain> own;
    if (!ground) own = std::make_unique<terrain::Terrain>(terrain::Terrain::flat());
    const terrain::Terrain& g = ground ? ground->ground : *own;
    gait::Crowd crowd(set->set, g, characters, crowd_options);
    return new fg_crowd{std::move(own), std::move(crowd)};
  });
}

size_t fg_crowd_workers(const fg_crowd* crowd) {
  return crowd ? crowd->crowd.worker_count() : 0;
}

void fg_crowd_free(fg_crowd* crowd) {
  delete crowd;
}

size_t fg_crowd_size(const fg_crowd* crowd) {
  return crowd ? crowd->crowd.size() : 0;
}

int fg_crowd_advance(fg_crowd* crowd, double dt) {
  return crowd && crowd->crowd.advance(dt) ? 1 : 0;
}

void fg_crowd_pose(const fg_crowd* crowd, size_t i, fg_pose* pose) {
  if (crowd && pose && i < crowd->crowd.size()) *pose = pose_of(crowd->crowd[i]);
}

double fg_crowd_set_speed(fg_crowd* crowd, size_t i, double metres_per_second) {
  return crowd ? crowd->crowd.set_speed(i, metres_per_second) : kNaN;
}

int fg_crowd_stop(fg_crowd* crowd, size_t i) {
  return crowd && crowd->crowd.stop(i) ? 1 : 0;
}

int fg_crowd_go(fg_crowd* crowd, size_t i) {
  return crowd && crowd->crowd.go(i) ? 1 : 0;
}

double fg_crowd_set_step_length(fg_crowd* crowd, size_t i, double metres) {
  return crowd ? crowd->crowd.set_step_length(i, metres) : kNaN;
}

}  // extern "C"
