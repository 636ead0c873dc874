// A walking clip's sagittal leg angles, contacts and gait events by forward kinematics of its
// BVH skeleton (io/mocap.hpp states the method).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "fuzzygait/io/mocap.hpp"
#include "offline/io/leg_chains.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::io {
namespace {

using common::number_text;
using Vec3 = std::array<double, 3>;
using Mat3 = std::array<double, 9>;  // row-major

// Anthropometry (Winter 2009, Fig. 4.1), as rig::segments_from_stature uses it.
constexpr double kHipToAnkleShare = 0.530 - 0.039;  // of stature
constexpr double kAnkleHeightShare = 0.039;
constexpr double kFootShare = 0.152;
constexpr double kHeelShare = 0.25;  // of foot length, heel to ankle
constexpr double kToeShare = 0.27;   // of foot length, MTP joint to tip
// The unit guess: candidates (m, cm, mm, inch, CMU) and the rest leg they aim at.
constexpr std::array<double, 5> kUnits = {1.0, 0.01, 0.001, 0.0254, 0.0254 / 0.45};
constexpr std::array<const char*, 5> kUnitNames = {"m", "cm", "mm", "inch", "CMU"};
constexpr double kTypicalHipToAnkle = 0.80;  // m
// A walking direction from less root travel than this is unreliable.
constexpr double kShortTravel = 0.2;  // m
constexpr int kSpeedHalfWindow = 2;   // frames each side of a central difference
constexpr std::size_t kFewestStillSamples = 10;
// Positions farther out are a wrong unit or a broken file; this keeps a clip's whole path, and
// its ground, within terrain::Terrain::kMaxCoordinate.
constexpr double kFarthest = 1e5;  // m
// A ground line steeper than this is no floor a walk crosses.
constexpr double kSteepestGround = 0.5;  // rise per metre, 27 deg
// The rig's least ankle height (rig::validate); a skeleton's foot dropping less gets Winter's.
constexpr double kLowestAnkle = 0.005;  // m

Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
Vec3 operator*(double s, const Vec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
// The 3-D angle between two vectors, radians; a zero vector gives a right angle, never NaN.
double angle_between(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(a, b) / (norm(a) * norm(b) + 1e-12), -1.0, 1.0));
}

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 m{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k)
        s += a[3 * r + k] * b[3 * k + c];
      m[3 * r + c] = s;
    }
  }
  return m;
}
Vec3 transform(const Mat3& m, const Vec3& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}
// Right-handed rotation about axis 0, 1 or 2 (X, Y, Z) by `degrees`.
Mat3 rotation(int axis, double degrees) {
  const double c = std::cos(rig::radians(degrees));
  const double s = std::sin(rig::radians(degrees));
  switch (axis) {
    case 0:
      return {1, 0, 0, 0, c, -s, 0, s, c};
    case 1:
      return {c, 0, s, 0, 1, 0, -s, 0, c};
    default:
      return {c, -s, 0, s, c, 0, 0, 0, 1};
  }
}

// World positions (file units) of the joints marked in `needed` (their ancestors marked too)
// for one frame's values; a zero frame gives the rest pose.
void forward_kinematics(const BvhClip& bvh, std::span<const double> frame,
                        const std::vector<char>& needed, std::vector<Vec3>& position,
                        std::vector<Mat3>& orientation) {
  for (std::size_t j = 0; j < bvh.joints.size(); ++j) {
    if (!needed[j]) continue;
    const BvhJoint& joint = bvh.joints[j];
    Vec3 t = joint.offset;
    Mat3 r = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (std::size_t k = 0; k < joint.channels.size(); ++k) {
      const double v = frame[joint.first_column + k];
      const int axis = axis_of(joint.channels[k]);
      if (is_rotation(joint.channels[k])) {
        r = multiply(r, rotation(axis, v));
      } else {
        t[static_cast<std::size_t>(axis)] += v;
      }
    }
    if (joint.parent < 0) {
      position[j] = t;
      orientation[j] = r;
    } else {
      const auto p = static_cast<std::size_t>(joint.parent);
      position[j] = position[p] + transform(orientation[p], t);
      orientation[j] = multiply(orientation[p], r);
    }
  }
}

// The points of one frame the analysis reads, metres, in the file's axes.
struct LegPositions {
  Vec3 hip, knee, ankle, toe, tip;
};
struct FramePositions {
  Vec3 root;
  std::array<LegPositions, 2> legs;
};

struct Line {
  double intercept = 0.0;
  double slope = 0.0;
  double at(double x) const { return intercept + slope * x; }
};

// Ground height through (distance along f, height, horizontal speed) samples taken while still;
// with too few still samples, the 5th percentile of the heights, level.
Line ground_line(const std::vector<std::array<double, 3>>& samples, double still_speed) {
  std::vector<std::pair<double, double>> still;
  for (const auto& [x, h, v] : samples) {
    if (v < still_speed) still.emplace_back(x, h);
  }
  if (still.size() < kFewestStillSamples) {
    std::vector<double> heights;
    for (const auto& s : samples)
      heights.push_back(s[1]);
    std::sort(heights.begin(), heights.end());
    return {heights[heights.size() / 20], 0.0};
  }
  double mx = 0.0;
  double mh = 0.0;
  for (const auto& [x, h] : still) {
    mx += x;
    mh += h;
  }
  mx /= static_cast<double>(still.size());
  mh /= static_cast<double>(still.size());
  double sxx = 0.0;
  double sxh = 0.0;
  for (const auto& [x, h] : still) {
    sxx += (x - mx) * (x - mx);
    sxh += (x - mx) * (h - mh);
  }
  const double slope = sxx > 1e-9 ? sxh / sxx : 0.0;
  return {mh - slope * mx, slope};
}

// Merges inner runs shorter than `shortest` frames into the state before them.
std::vector<bool> debounce(const std::vector<bool>& flags, std::size_t shortest) {
  std::vector<std::pair<bool, std::size_t>> runs;
  for (bool f : flags) {
    if (runs.empty() || runs.back().first != f) {
      runs.emplace_back(f, 1);
    } else {
      ++runs.back().second;
    }
  }
  std::vector<bool> out;
  out.reserve(flags.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const auto [state, length] = runs[k];
    const bool inner = k > 0 && k + 1 < runs.size();
    out.insert(out.end(), length, inner && length < shortest ? out.back() : state);
  }
  return out;
}

double mean_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

void check_options(const ClipOptions& o, const std::string& source) {
  auto positive = [&](const char* name, double value, double most) {
    if (!(value > 0.0 && value <= most)) {
      throw MocapError(source, 0,
                       std::string("expected ") + name + " above 0 and at most " +
                           number_text(most) + " found " + number_text(value));
    }
  };
  positive("contact_height (m)", o.contact_height, 10.0);
  positive("contact_speed (m/s)", o.contact_speed, 100.0);
  positive("still_speed (m/s)", o.still_speed, 100.0);
  positive("ground_speed (m/s)", o.ground_speed, 100.0);
  positive("min_run (s)", o.min_run, 10.0);
  positive("min_cycle (s)", o.min_cycle, 100.0);
  positive("max_cycle (s)", o.max_cycle, 100.0);
  if (o.metres_per_unit) positive("a unit (metres per unit)", *o.metres_per_unit, 1000.0);
  if (o.min_cycle > o.max_cycle) {
    throw MocapError(source, 0,
                     "expected min_cycle at most max_cycle found " + number_text(o.min_cycle) +
                         " > " + number_text(o.max_cycle));
  }
}

// A calibration pose: every rotation a whole number of degrees, more than 80 % of them zero.
bool is_calibration_pose(const BvhClip& bvh, std::span<const double> frame) {
  std::size_t rotations = 0;
  std::size_t zeros = 0;
  for (const BvhJoint& joint : bvh.joints) {
    for (std::size_t k = 0; k < joint.channels.size(); ++k) {
      if (!is_rotation(joint.channels[k])) continue;
      const double v = frame[joint.first_column + k];
      if (v != std::round(v)) return false;
      ++rotations;
      zeros += v == 0.0 ? 1 : 0;
    }
  }
  return static_cast<double>(zeros) > 0.8 * static_cast<double>(rotations);
}

// The guess of the unit: the candidate that makes the rest leg (hip to ankle, file units)
// closest to a typical one, the first of equals.
double guess_unit(double rest_leg) {
  double best = kUnits[0];
  for (double unit : kUnits) {
    if (std::abs(std::log(rest_leg * unit / kTypicalHipToAnkle)) <
        std::abs(std::log(rest_leg * best / kTypicalHipToAnkle))) {
      best = unit;
    }
  }
  return best;
}

// Of +Y and +Z, the axis along which the hips stand above the ankles over the clip.
UpAxis detect_up(const std::vector<FramePositions>& frames, const std::string& where) {
  Vec3 rise{};
  for (const FramePositions& f : frames) {
    rise = rise + 0.5 * ((f.legs[0].hip + f.legs[1].hip) - (f.legs[0].ankle + f.legs[1].ankle));
  }
  if (!(std::max(rise[1], rise[2]) > 0.5 * norm(rise))) {
    throw MocapError(where, 0,
                     "cannot tell the up axis: the hips do not stand above the ankles along +Y "
                     "or +Z; give it (--up y or --up z)");
  }
  return rise[1] >= rise[2] ? UpAxis::Y : UpAxis::Z;
}

// The sagittal plane: up u and walking direction f, unit vectors in the file's axes.
struct Sagittal {
  Vec3 up;
  Vec3 forward;
  Vec3 horizontal(const Vec3& v) const { return v - dot(v, up) * up; }
};

// The ankles (part 0) and toe bases (part 1) of both feet over the frames, and their speeds.
class FootTracks {
 public:
  FootTracks(const std::vector<FramePositions>& frames, const Sagittal& plane, double dt)
      : frames_(frames), plane_(plane), dt_(dt) {}
  std::size_t size() const { return frames_.size(); }
  const Vec3& at(std::size_t i, std::size_t side, int part) const {
    const LegPositions& p = frames_[i].legs[side];
    return part == 0 ? p.ankle : p.toe;
  }
  // m/s by central differences over 5 frames (fewer at the ends); `flat`: horizontal only.
  double speed(std::size_t i, std::size_t side, int part, bool flat) const {
    const std::size_t a = i >= kSpeedHalfWindow ? i - kSpeedHalfWindow : 0;
    const std::size_t b = std::min(frames_.size() - 1, i + kSpeedHalfWindow);
    const Vec3 d = at(b, side, part) - at(a, side, part);
    return norm(flat ? plane_.horizontal(d) : d) / (static_cast<double>(b - a) * dt_);
  }

 private:
  const std::vector<FramePositions>& frames_;
  const Sagittal& plane_;
  double dt_;
};

// Ground lines of the ankles and the toe bases, both feet pooled.
std::array<Line, 2> fit_ground(const FootTracks& feet, const Sagittal& plane, double ground_speed) {
  std::array<Line, 2> ground;
  for (int part = 0; part < 2; ++part) {
    std::vector<std::array<double, 3>> samples;
    samples.reserve(2 * feet.size());
    for (std::size_t i = 0; i < feet.size(); ++i) {
      for (std::size_t s = 0; s < 2; ++s) {
        const Vec3& p = feet.at(i, s, part);
        samples.push_back({dot(p, plane.forward), dot(p, plane.up), feet.speed(i, s, part, true)});
      }
    }
    ground[static_cast<std::size_t>(part)] = ground_line(samples, ground_speed);
  }
  return ground;
}

// Whether a foot bears on the ground, frame by frame, debounced.
std::vector<bool> foot_contact(const FootTracks& feet, std::size_t side,
                               const std::array<Line, 2>& ground, const Sagittal& plane,
                               const ClipOptions& o, double dt) {
  std::vector<bool> on(feet.size());
  for (std::size_t i = 0; i < feet.size(); ++i) {
    bool down = false;
    for (int part = 0; part < 2; ++part) {
      const Vec3& q = feet.at(i, side, part);
      const double height =
          dot(q, plane.up) - ground[static_cast<std::size_t>(part)].at(dot(q, plane.forward));
      down = down ||
             (height < o.contact_height && feet.speed(i, side, part, true) < o.contact_speed) ||
             feet.speed(i, side, part, false) < o.still_speed;
    }
    on[i] = down;
  }
  return debounce(on, static_cast<std::size_t>(std::max(1.0, std::nearbyint(o.min_run / dt))));
}

// The four angles of a leg, radians; ankle and toe relative to `rest`'s.
rig::LegAngles leg_angles(const LegPositions& p, const LegPositions& rest, bool has_tip,
                          const Sagittal& plane) {
  const Vec3 thigh = p.knee - p.hip;
  const Vec3 shank = p.ankle - p.knee;
  const Vec3 foot = p.toe - p.ankle;
  rig::LegAngles a;
  a.hip = std::atan2(dot(thigh, plane.forward), -dot(thigh, plane.up));
  a.knee = angle_between(thigh, shank);
  a.ankle =
      angle_between(shank, foot) - angle_between(rest.ankle - rest.knee, rest.toe - rest.ankle);
  a.toe = has_tip ? angle_between(foot, p.tip - p.toe) -
                        angle_between(rest.toe - rest.ankle, rest.tip - rest.toe)
                  : 0.0;
  return a;
}

// Heel strikes and toe offs, left cycles, cadence, step length and speed.
void measure_gait(CapturedClip& clip, const std::array<std::vector<bool>, 2>& contact,
                  const std::vector<FramePositions>& frames, const Sagittal& plane, double dt,
                  const ClipOptions& o) {
  std::vector<std::pair<std::size_t, std::size_t>> strikes;  // (frame, side), in order
  for (std::size_t s = 0; s < 2; ++s) {
    for (std::size_t i = 1; i < frames.size(); ++i) {
      if (contact[s][i] && !contact[s][i - 1]) {
        clip.events.heel_strikes[s].push_back(i);
        strikes.emplace_back(i, s);
      }
      if (!contact[s][i] && contact[s][i - 1]) clip.events.toe_offs[s].push_back(i);
    }
  }
  std::sort(strikes.begin(), strikes.end());
  const std::vector<std::size_t>& left = clip.events.heel_strikes[0];
  for (std::size_t k = 0; k + 1 < left.size(); ++k) {
    const double duration = static_cast<double>(left[k + 1] - left[k]) * dt;
    if (duration >= o.min_cycle && duration <= o.max_cycle) {
      clip.cycles.push_back({left[k], left[k + 1]});
    }
  }
  std::vector<double> step_times;
  std::vector<double> step_lengths;
  for (std::size_t k = 0; k < strikes.size(); ++k) {
    const auto [i, s] = strikes[k];
    step_lengths.push_back(
        dot(frames[i].legs[s].ankle - frames[i].legs[1 - s].ankle, plane.forward));
    if (k + 1 < strikes.size() && strikes[k + 1].second != s) {
      const double gap = static_cast<double>(strikes[k + 1].first - i) * dt;
      if (gap > 0.0 && gap < 1.0) step_times.push_back(gap);  // (both feet at once: no step)
    }
  }
  clip.cadence = step_times.empty() ? 0.0 : 60.0 / mean_of(step_times);
  clip.step_length = mean_of(step_lengths);
  if (strikes.size() >= 2 && strikes.back().first > strikes.front().first) {
    const std::size_t i0 = strikes.front().first;
    const std::size_t i1 = strikes.back().first;
    clip.speed =
        dot(frames[i1].root - frames[i0].root, plane.forward) / (static_cast<double>(i1 - i0) * dt);
  }
}

// The legs' joints and lengths (into clip.legs) and the rig's segments (notes for estimates).
rig::Segments measure_segments(CapturedClip& clip, const BvhClip& bvh,
                               const detail::SkeletonLegs& found,
                               const std::array<LegPositions, 2>& rest, const Sagittal& plane,
                               const std::string& where) {
  const double unit = clip.metres_per_unit;
  auto name = [&](int j) {
    return j >= 0 ? bvh.joints[static_cast<std::size_t>(j)].name : std::string();
  };
  for (std::size_t s = 0; s < 2; ++s) {
    const LegPositions& r = rest[s];
    const detail::LegChain& c = found.legs[s];
    MeasuredLeg& leg = clip.legs[s];
    leg = {name(c.hip), name(c.knee), name(c.ankle), name(c.toe), name(c.tip)};
    leg.thigh = unit * norm(r.knee - r.hip);
    leg.shank = unit * norm(r.ankle - r.knee);
    leg.foot = unit * norm(r.toe - r.ankle);
    leg.has_toes = c.tip >= 0;
    leg.toes = leg.has_toes ? unit * norm(r.tip - r.toe) : 0.0;
  }
  rig::Segments seg;
  seg.thigh = 0.5 * (clip.legs[0].thigh + clip.legs[1].thigh);
  seg.shank = 0.5 * (clip.legs[0].shank + clip.legs[1].shank);
  const double stature = (seg.thigh + seg.shank) / kHipToAnkleShare;
  double drop = 0.0;
  for (std::size_t s = 0; s < 2; ++s) {
    const Vec3 foot = unit * (rest[s].toe - rest[s].ankle);
    drop -= 0.5 * dot(foot, plane.up);
    seg.ball += 0.5 * norm(plane.horizontal(foot));
  }
  if (drop >= kLowestAnkle) {
    seg.ankle_height = drop;
  } else {
    seg.ankle_height = kAnkleHeightShare * stature;
    clip.notes.push_back(
        "the toe bases lie less than 5 mm below the ankles in the rest pose: ankle height from "
        "proportions, " +
        number_text(seg.ankle_height) + " m");
  }
  seg.heel = kHeelShare * kFootShare * stature;
  if (clip.legs[0].has_toes && clip.legs[1].has_toes) {
    seg.toe = 0.5 * (clip.legs[0].toes + clip.legs[1].toes);
  } else {
    seg.toe = kToeShare * kFootShare * stature;
    clip.notes.push_back("a foot without a toe tip: toe length from proportions, " +
                         number_text(seg.toe) + " m");
  }
  try {
    rig::validate(seg);
  } catch (const std::invalid_argument& e) {
    throw MocapError(where, 0,
                     "expected the skeleton to make a plausible leg (at " + number_text(unit) +
                         " m per unit): " + e.what());
  }
  return seg;
}

}  // namespace

const char* unit_name(double metres_per_unit) {
  for (std::size_t k = 0; k < kUnits.size(); ++k) {
    if (metres_per_unit == kUnits[k]) return kUnitNames[k];
  }
  return "custom";
}

CapturedClip analyse_clip(const BvhClip& bvh, std::string_view source, const ClipOptions& options) {
  const std::string where(source);
  check_options(options, where);
  detail::SkeletonLegs found =
      detail::find_legs(bvh, where, options.mapping ? &*options.mapping : nullptr);
  CapturedClip clip;
  clip.notes = std::move(found.notes);
  clip.root = bvh.joints[static_cast<std::size_t>(found.root)].name;
  const std::size_t total = bvh.frame_count();
  const double dt = bvh.frame_time;

  // The joints forward kinematics must place: the legs', the root, and their ancestors.
  std::vector<char> needed(bvh.joints.size(), 0);
  auto mark = [&](int j) {
    for (; j >= 0 && !needed[static_cast<std::size_t>(j)];
         j = bvh.joints[static_cast<std::size_t>(j)].parent)
      needed[static_cast<std::size_t>(j)] = 1;
  };
  mark(found.root);
  for (const detail::LegChain& c : found.legs) {
    for (int j : {c.hip, c.knee, c.ankle, c.toe, c.tip})
      mark(j);
  }
  std::vector<Vec3> position(bvh.joints.size());
  std::vector<Mat3> orientation(bvh.joints.size());
  auto legs_now = [&](double unit) {
    std::array<LegPositions, 2> legs;
    for (std::size_t s = 0; s < 2; ++s) {
      const detail::LegChain& c = found.legs[s];
      auto at = [&](int j) {
        return j >= 0 ? unit * position[static_cast<std::size_t>(j)] : Vec3{};
      };
      legs[s] = {at(c.hip), at(c.knee), at(c.ankle), at(c.toe), at(c.tip)};
    }
    return legs;
  };

  // The rest pose (every channel zero), file units: the unit, rest angles, segments.
  forward_kinematics(bvh, std::vector<double>(bvh.channel_count, 0.0), needed, position,
                     orientation);
  std::array<LegPositions, 2> rest = legs_now(1.0);
  for (std::size_t s = 0; s < 2; ++s) {
    if (!(norm(rest[s].knee - rest[s].hip) + norm(rest[s].ankle - rest[s].knee) > 1e-9)) {
      throw MocapError(where, 0,
                       std::string("expected a ") + (s == 0 ? "left" : "right") +
                           " leg of some length in the rest pose found hip, knee and ankle at "
                           "one point");
    }
  }
  clip.unit_guessed = !options.metres_per_unit;
  clip.metres_per_unit = options.metres_per_unit.value_or(
      guess_unit(norm(rest[0].knee - rest[0].hip) + norm(rest[0].ankle - rest[0].knee)));
  const double unit = clip.metres_per_unit;

  // The frames kept, forward kinematics in metres.
  clip.skipped_frames =
      options.skip.value_or(is_calibration_pose(bvh, bvh.frame(0)) ? std::size_t{1} : 0);
  if (clip.skipped_frames >= total || total - clip.skipped_frames < 2) {
    throw MocapError(
        where, 0,
        "expected at least 2 frames after skipping " + std::to_string(clip.skipped_frames) +
            " found " +
            std::to_string(total > clip.skipped_frames ? total - clip.skipped_frames : 0));
  }
  const std::size_t n = total - clip.skipped_frames;
  std::vector<FramePositions> frames(n);
  for (std::size_t i = 0; i < n; ++i) {
    forward_kinematics(bvh, bvh.frame(clip.skipped_frames + i), needed, position, orientation);
    FramePositions& f = frames[i];
    f.root = unit * position[static_cast<std::size_t>(found.root)];
    f.legs = legs_now(unit);
    for (const LegPositions& l : f.legs) {
      for (const Vec3* p : {&std::as_const(f.root), &l.hip, &l.knee, &l.ankle, &l.toe, &l.tip}) {
        for (double v : *p) {
          if (!(std::abs(v) <= kFarthest)) {
            throw MocapError(where, 0,
                             "expected positions within 100 km of the origin found " +
                                 number_text(v) + " m in frame " +
                                 std::to_string(clip.skipped_frames + i + 1) + " (at " +
                                 number_text(unit) + " m per unit)");
          }
        }
      }
    }
  }

  // The sagittal plane: up given or detected, forward the root's horizontal travel.
  clip.up_detected = !options.up;
  clip.up = options.up ? *options.up : detect_up(frames, where);
  Sagittal plane;
  plane.up = clip.up == UpAxis::Y ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
  const Vec3 travel = plane.horizontal(frames.back().root - frames.front().root);
  const double travelled = norm(travel);
  if (!(travelled > 1e-6)) {
    throw MocapError(where, 0,
                     "expected the root '" + clip.root +
                         "' to travel found it in place: no walking direction (a treadmill "
                         "clip is not supported)");
  }
  if (travelled < kShortTravel) {
    clip.notes.push_back("the root travels only " + number_text(travelled) +
                         " m: the walking direction is unreliable");
  }
  plane.forward = (1.0 / (travelled + 1e-12)) * travel;
  clip.forward = plane.forward;

  // Contacts, events, segments.
  const FootTracks feet(frames, plane, dt);
  const std::array<Line, 2> ground = fit_ground(feet, plane, options.ground_speed);
  const std::array<std::vector<bool>, 2> contact = {
      foot_contact(feet, 0, ground, plane, options, dt),
      foot_contact(feet, 1, ground, plane, options, dt)};
  measure_gait(clip, contact, frames, plane, dt, options);
  const rig::Segments segments = measure_segments(clip, bvh, found, rest, plane, where);

  // The motion in the rig's terms: x along f from the root's first position, y above the toe
  // bases' ground at x = 0.
  const Line& floor = ground[1];
  if (!(std::abs(floor.slope) <= kSteepestGround)) {
    throw MocapError(where, 0,
                     "expected the toe bases' ground to be a floor found it rising " +
                         number_text(floor.slope) + " m per metre walked");
  }
  const double x0 = dot(frames.front().root, plane.forward);
  const double y0 = floor.at(x0);
  eval::Motion& motion = clip.motion;
  motion.fps = 1.0 / dt;
  motion.segments = segments;
  motion.captured = true;
  motion.frames.resize(n);
  double x_min = 0.0;
  double x_max = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    eval::Frame& frame = motion.frames[i];
    frame.time = static_cast<double>(i) * dt;
    const Vec3 mid = 0.5 * (frames[i].legs[0].hip + frames[i].legs[1].hip);
    frame.pose.pelvis = {dot(mid, plane.forward) - x0, dot(mid, plane.up) - y0};
    for (std::size_t s = 0; s < 2; ++s) {
      frame.pose.legs[s] = leg_angles(frames[i].legs[s], rest[s], found.legs[s].tip >= 0, plane);
      frame.points[s] =
          rig::forward_kinematics(segments, frame.pose.pelvis, 0.0, frame.pose.legs[s]);
      frame.contact[s] = contact[s][i];
    }
    x_min = std::min(x_min, frame.pose.pelvis.x);
    x_max = std::max(x_max, frame.pose.pelvis.x);
  }
  const double margin = 10.0;  // m, beyond the pelvis's path
  clip.ground = terrain::Terrain::polyline({{x_min - margin, floor.slope * (x_min - margin)},
                                            {x_max + margin, floor.slope * (x_max + margin)}});
  return clip;
}

CapturedClip read_clip(const std::filesystem::path& path, const ClipOptions& options) {
  return analyse_clip(read_bvh_file(path), path.string(), options);
}

}  // namespace fuzzygait::io
