#include "fuzzygait/learn/upper_body.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton.hpp"
#include "fuzzygait/io/skeleton_file.hpp"
#include "fuzzygait/learn/training.hpp"
#include "offline/learn/set_edit.hpp"
#include "runtime/common/format.hpp"

namespace fuzzygait::learn {

namespace {

using body::Vec3;

constexpr double kDegrees = 180.0 / std::numbers::pi;

bool finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Which leg a part reads and how the two sides' answers make the body's value, as
// body::PathFollower poses them: value = sign * (answer(left leg) - answer(right leg)), or each
// arm its own answer.
enum class Sides { OwnArm, LeftMinusRight, RightMinusLeft };

Sides sides_of(gait::UpperBody part) {
  switch (part) {
    case gait::UpperBody::Shoulder:
    case gait::UpperBody::Elbow:
      return Sides::OwnArm;
    // The follower turns the body by yaw(left's answer - right's), which brings the right side
    // forward: the left hip forward is the right's answer less the left's.
    case gait::UpperBody::PelvisRotation:
    case gait::UpperBody::ThoraxRotation:
      return Sides::RightMinusLeft;
    case gait::UpperBody::PelvisObliquity:
    case gait::UpperBody::PelvisSway:
      return Sides::LeftMinusRight;
    case gait::UpperBody::TrunkLean:  // not fitted (below)
      return Sides::OwnArm;
  }
  return Sides::OwnArm;
}

// The clip's value of `part` at frame k (side: the arm's, for the arms).
double value_of(const UpperBodySeries& s, gait::UpperBody part, std::size_t side, std::size_t k) {
  switch (part) {
    case gait::UpperBody::Shoulder:
      return s.shoulder[side][k];
    case gait::UpperBody::Elbow:
      return s.elbow[side][k];
    case gait::UpperBody::PelvisRotation:
      return s.pelvis_rotation[k];
    case gait::UpperBody::ThoraxRotation:
      return s.thorax_rotation[k];
    case gait::UpperBody::PelvisObliquity:
      return s.pelvis_obliquity[k];
    case gait::UpperBody::PelvisSway:
      return s.pelvis_sway[k];
    case gait::UpperBody::TrunkLean:  // not fitted (below)
      return 0.0;
  }
  return 0.0;
}

// A frame of the clip at time t: the upper body's frame k and the share of the way to k + 1.
struct At {
  std::size_t k = 0;
  double share = 0.0;
};
std::optional<At> at_time(const UpperBodySeries& s, double t) {
  if (s.size() < 2 || t < s.time.front() || t > s.time.back()) return std::nullopt;
  const auto next = std::upper_bound(s.time.begin(), s.time.end(), t);
  const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(next - s.time.begin() - 1, 0));
  if (k + 1 >= s.size()) return At{s.size() - 2, 1.0};
  const double span = s.time[k + 1] - s.time[k];
  return At{k, span > 0.0 ? (t - s.time[k]) / span : 0.0};
}

double interpolate(const UpperBodySeries& s, gait::UpperBody part, std::size_t side, At at) {
  const double a = value_of(s, part, side, at.k);
  return a + at.share * (value_of(s, part, side, at.k + 1) - a);
}

// A row of the least squares: the two legs' metrics (one for an arm) and the clip's value.
struct Sample {
  gait::MetricValues left{};
  gait::MetricValues right{};
  bool arm = false;  // only `left` is read: the arm's own leg
  double value = 0.0;
  std::size_t clip = 0;
};

}  // namespace

UpperBodySeries measure_upper_body(std::span<const UpperBodyPoints> frames, Vec3 forward, Vec3 up,
                                   double leg_length) {
  if (frames.size() < 2) {
    throw std::invalid_argument("upper body: two frames or more are needed, got " +
                                std::to_string(frames.size()));
  }
  if (std::abs(length(forward) - 1.0) > 1e-6 || std::abs(length(up) - 1.0) > 1e-6 ||
      std::abs(dot(forward, up)) > 1e-6) {
    throw std::invalid_argument(
        "upper body: forward and up must be unit vectors square to each other");
  }
  if (!(leg_length > 0.0) || !std::isfinite(leg_length)) {
    throw std::invalid_argument("upper body: the leg length must be above 0, got " +
                                common::number_text(leg_length));
  }
  const Vec3 left = cross(up, forward);
  UpperBodySeries s;
  std::vector<double> lateral;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const UpperBodyPoints& f = frames[k];
    for (std::size_t side = 0; side < 2; ++side) {
      for (const Vec3 p : {f.hip[side], f.shoulder[side], f.elbow[side], f.wrist[side]}) {
        if (!finite(p)) {
          throw std::invalid_argument("upper body: frame " + std::to_string(k) +
                                      " has a joint that is not finite");
        }
      }
    }
    if (!std::isfinite(f.time)) {
      throw std::invalid_argument("upper body: frame " + std::to_string(k) +
                                  "'s time is not finite");
    }
    s.time.push_back(f.time);
    for (std::size_t side = 0; side < 2; ++side) {
      const Vec3 upper = f.elbow[side] - f.shoulder[side];
      const Vec3 fore = f.wrist[side] - f.elbow[side];
      s.shoulder[side].push_back(std::atan2(dot(upper, forward), -dot(upper, up)) * kDegrees);
      const double cosine = dot(normalized(upper), normalized(fore));
      s.elbow[side].push_back(std::acos(std::clamp(cosine, -1.0, 1.0)) * kDegrees);
    }
    const Vec3 hips = f.hip[0] - f.hip[1];
    const Vec3 shoulders = f.shoulder[0] - f.shoulder[1];
    s.pelvis_rotation.push_back(std::atan2(dot(hips, forward), dot(hips, left)) * kDegrees);
    s.thorax_rotation.push_back(std::atan2(dot(shoulders, forward), dot(shoulders, left)) *
                                kDegrees);
    s.pelvis_obliquity.push_back(
        std::atan2(dot(hips, up), std::hypot(dot(hips, left), dot(hips, forward))) * kDegrees);
    lateral.push_back(dot(0.5 * (f.hip[0] + f.hip[1]), left));
  }
  // The sway: off the hips' centre's straight-line fit against time.
  const auto n = static_cast<double>(frames.size());
  double mt = 0.0, ml = 0.0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    mt += s.time[k] / n;
    ml += lateral[k] / n;
  }
  double stt = 0.0, stl = 0.0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    stt += (s.time[k] - mt) * (s.time[k] - mt);
    stl += (s.time[k] - mt) * (lateral[k] - ml);
  }
  const double slope = stt > 0.0 ? stl / stt : 0.0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    s.pelvis_sway.push_back(100.0 * (lateral[k] - ml - slope * (s.time[k] - mt)) / leg_length);
  }
  // The turns and the roll about their means: one held all along is the subject's stance or the
  // markers' (a difference of the two sides' answers cannot make it).
  for (std::vector<double>* v : {&s.pelvis_rotation, &s.thorax_rotation, &s.pelvis_obliquity}) {
    double mean = 0.0;
    for (const double x : *v)
      mean += x / n;
    for (double& x : *v)
      x -= mean;
  }
  return s;
}

std::optional<UpperBodySeries> capture_upper_body(const io::BvhClip& bvh,
                                                  const io::CapturedClip& captured,
                                                  std::string* why) {
  const body::Skeleton skeleton = io::skeleton_from_bvh(bvh, captured.metres_per_unit);
  body::HumanoidMap map;
  try {
    map = body::map_humanoid(skeleton);
  } catch (const std::invalid_argument& e) {
    if (why) *why = e.what();
    return std::nullopt;
  }
  using body::Joint;
  const std::array<std::array<Joint, 4>, 2> wanted = {
      {{Joint::left_upper_leg, Joint::left_upper_arm, Joint::left_lower_arm, Joint::left_hand},
       {Joint::right_upper_leg, Joint::right_upper_arm, Joint::right_lower_arm,
        Joint::right_hand}}};
  for (const auto& side : wanted) {
    for (const Joint j : side) {
      if (map[j] == body::kUnmapped) {
        if (why) *why = "the skeleton has no joint for " + std::string(body::name(j));
        return std::nullopt;
      }
    }
  }
  const Vec3 up = captured.up == io::UpAxis::Y ? Vec3{0.0, 1.0, 0.0} : Vec3{0.0, 0.0, 1.0};
  Vec3 forward{captured.forward[0], captured.forward[1], captured.forward[2]};
  forward = normalized(forward - dot(forward, up) * up);
  std::vector<body::Quat> local(skeleton.size());
  std::vector<Vec3> positions(skeleton.size());
  std::vector<body::Quat> rotations(skeleton.size());
  std::vector<UpperBodyPoints> frames;
  for (std::size_t f = captured.skipped_frames; f < bvh.frame_count(); ++f) {
    Vec3 root;
    io::bvh_frame(bvh, f, local, root);
    body::forward_kinematics(skeleton, local, root, positions, rotations);
    UpperBodyPoints p;
    p.time = static_cast<double>(f - captured.skipped_frames) * bvh.frame_time;
    for (std::size_t side = 0; side < 2; ++side) {
      auto at = [&](Joint j) { return positions[static_cast<std::size_t>(map[j])]; };
      p.hip[side] = at(wanted[side][0]);
      p.shoulder[side] = at(wanted[side][1]);
      p.elbow[side] = at(wanted[side][2]);
      p.wrist[side] = at(wanted[side][3]);
    }
    frames.push_back(p);
  }
  return measure_upper_body(frames, forward, up,
                            captured.motion.segments.leg_length() / captured.metres_per_unit);
}

UpperBodyFit fit_upper_body(const gait::ControllerSet& base, std::span<const UpperBodyClip> clips) {
  if (clips.empty()) throw std::invalid_argument("upper body: no clip to learn from");
  // The legs' metrics at each frame of each clip, as the walker measures them.
  std::vector<std::vector<std::array<gait::MetricValues, 2>>> metrics(clips.size());
  std::vector<std::vector<At>> times(clips.size());
  for (std::size_t c = 0; c < clips.size(); ++c) {
    const UpperBodyClip& clip = clips[c];
    if (clip.legs == nullptr) {
      throw std::invalid_argument("upper body: clip '" + clip.name + "' has no legs' motion");
    }
    const eval::Motion& motion = clip.legs->motion;
    TrainingOptions options;
    options.time_step = 1.0 / motion.fps;
    const TrainingClip data =
        training_data(motion, clip.legs->ground, clip.legs->step_length, base, options);
    for (std::size_t n = 0; n < data.steps.size(); ++n) {
      const auto& step = data.steps[n];
      if (!step[0].known || !step[1].known) continue;
      // (training_data's step n is the motion's frame n, as the series' frame n.)
      if (clip.series.size() < 2) break;
      const std::optional<At> at = at_time(
          clip.series, clip.series.time.front() + static_cast<double>(n) * options.time_step);
      if (!at) continue;
      metrics[c].push_back({step[0].metrics, step[1].metrics});
      times[c].push_back(*at);
    }
  }

  UpperBodyFit fit;
  fit.set = base;
  for (int p = 0; p < gait::kUpperBodyCount; ++p) {
    const auto part = static_cast<gait::UpperBody>(p);
    const auto index = static_cast<std::size_t>(p);
    const std::string name(gait::upper_body_name(part));
    const std::optional<gait::Controller>& controller = base.upper_body[index];
    if (!controller) continue;
    if (part == gait::UpperBody::TrunkLean) {
      // It answers the ground's incline, and the clips are level walks.
      fit.notes.push_back(name + ": kept (the clips walk level ground: nothing to fit it to)");
      continue;
    }
    const fuzzy::Engine& engine = controller->engine();
    if (engine.outputs.size() != 1 ||
        !std::all_of(engine.outputs[0].terms.begin(), engine.outputs[0].terms.end(),
                     [](const fuzzy::Term& t) {
                       return t.kind == fuzzy::TermKind::Constant && t.parameters.size() == 1;
                     })) {
      fit.notes.push_back(name + ": kept (its output words are not all constants)");
      continue;
    }
    const std::vector<fuzzy::Term>& terms = engine.outputs[0].terms;
    const std::size_t count = terms.size();
    // The answer is sum_t c_t * w_t(metrics): each w_t is the controller with c_t = 1, the others
    // 0.
    std::vector<gait::Controller> basis;
    std::vector<fuzzy::Workspace> workspaces;
    for (std::size_t t = 0; t < count; ++t) {
      fuzzy::Engine unit = engine;
      for (std::size_t u = 0; u < count; ++u)
        unit.outputs[0].terms[u].parameters[0] = u == t ? 1.0 : 0.0;
      basis.emplace_back(std::move(unit), controller->source());
      workspaces.push_back(basis.back().make_workspace());
    }
    auto weights = [&](const gait::MetricValues& m, Eigen::VectorXd& out) {
      for (std::size_t t = 0; t < count; ++t)
        out[static_cast<Eigen::Index>(t)] = basis[t].evaluate(m, workspaces[t]);
    };
    const Sides sides = sides_of(part);
    std::vector<Eigen::VectorXd> rows;
    std::vector<double> values;
    std::vector<std::size_t> row_clip;
    Eigen::VectorXd a(static_cast<Eigen::Index>(count)), b(static_cast<Eigen::Index>(count));
    for (std::size_t c = 0; c < clips.size(); ++c) {
      for (std::size_t k = 0; k < metrics[c].size(); ++k) {
        const auto& m = metrics[c][k];
        if (sides == Sides::OwnArm) {
          for (std::size_t side = 0; side < 2; ++side) {
            weights(m[side], a);
            rows.push_back(a);
            values.push_back(interpolate(clips[c].series, part, side, times[c][k]));
            row_clip.push_back(c);
          }
        } else {
          weights(m[0], a);
          weights(m[1], b);
          rows.push_back(sides == Sides::LeftMinusRight ? Eigen::VectorXd(a - b)
                                                        : Eigen::VectorXd(b - a));
          values.push_back(interpolate(clips[c].series, part, 0, times[c][k]));
          row_clip.push_back(c);
        }
      }
    }
    if (rows.empty()) {
      fit.notes.push_back(name + ": kept (no frame of the clips where both legs are known)");
      continue;
    }
    if (std::any_of(values.begin(), values.end(), [](double v) { return !std::isfinite(v); })) {
      fit.notes.push_back(name + ": kept (the clips' values are not finite)");
      continue;
    }
    Eigen::VectorXd base_values(static_cast<Eigen::Index>(count));
    for (std::size_t t = 0; t < count; ++t)
      base_values[static_cast<Eigen::Index>(t)] = terms[t].parameters[0];
    // Normal equations with a light pull (1e-3 of the data's weight a word) to the base's values.
    Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(a.size(), a.size());
    Eigen::VectorXd right = Eigen::VectorXd::Zero(a.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      normal += rows[r] * rows[r].transpose();
      right += rows[r] * values[r];
    }
    const double pull = 1e-3 * static_cast<double>(rows.size()) / static_cast<double>(count);
    normal += pull * Eigen::MatrixXd::Identity(a.size(), a.size());
    right += pull * base_values;
    const Eigen::VectorXd solved = normal.ldlt().solve(right);
    Eigen::VectorXd rounded = solved;
    for (Eigen::Index t = 0; t < rounded.size(); ++t)
      rounded[t] = detail::round_significant(solved[t], 3);
    if (!rounded.allFinite()) {
      fit.notes.push_back(name + ": kept (the fit did not converge)");
      continue;
    }
    // The RMSE per clip, before and after.
    std::vector<double> before(clips.size(), 0.0), after(clips.size(), 0.0);
    std::vector<double> rows_of(clips.size(), 0.0);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const double e0 = rows[r].dot(base_values) - values[r];
      const double e1 = rows[r].dot(rounded) - values[r];
      before[row_clip[r]] += e0 * e0;
      after[row_clip[r]] += e1 * e1;
      rows_of[row_clip[r]] += 1.0;
    }
    for (std::size_t c = 0; c < clips.size(); ++c) {
      fit.rmse_before[index].push_back(rows_of[c] > 0.0 ? std::sqrt(before[c] / rows_of[c]) : 0.0);
      fit.rmse_after[index].push_back(rows_of[c] > 0.0 ? std::sqrt(after[c] / rows_of[c]) : 0.0);
    }
    fuzzy::Engine fitted = engine;
    for (std::size_t t = 0; t < count; ++t)
      fitted.outputs[0].terms[t].parameters[0] = rounded[static_cast<Eigen::Index>(t)];
    fit.set.upper_body[index].emplace(std::move(fitted), controller->source());
    fit.fitted[index] = true;
  }
  return fit;
}

}  // namespace fuzzygait::learn
