// Pictures of a walk: its joint curves over the gait cycle against normative data, the curves of
// several walks side by side (the paper's Fig. 5), and the walker itself as a side-view stick
// figure: a filmstrip across one stride, and an animation that plays in any browser.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fuzzygait/eval/evaluation.hpp"
#include "fuzzygait/eval/motion.hpp"
#include "fuzzygait/plot/svg.hpp"
#include "fuzzygait/terrain/terrain.hpp"

namespace fuzzygait::plot {

// The left-leg curves a GaitReport holds. The hip is drawn as the thigh's inclination (hip
// flexion minus pelvic tilt), which is what is compared with the reference.
enum class GaitJoint : std::uint8_t { Thigh, Knee, Ankle, Toe };

struct GaitCurvesOptions {
  std::string title = "Gait cycle";  // the key figures of the walk follow it
  bool cycle_sd = true;              // the walk's SD between cycles as a light band
};

// One panel per joint over the normalised gait cycle (0-100 %, left heel strike to the next):
// the walk's mean curve over the reference's mean +/- 2 SD band, with RMSE and Pearson r (the
// report's) in the legend, stance and swing parted at toe off (the measured stance share), and
// the peak swing knee flexion marked, the walk's and the reference's. The toe has no reference
// curve and is drawn alone. The title carries step length, cadence, speed and stance.
// `reference` is the one the report was scored against, or nullptr for the walk alone.
svg::Figure plot_gait_curves(const eval::GaitReport& report, const eval::Normative* reference,
                             const GaitCurvesOptions& options = {});

struct LabelledReport {
  std::string label;  // e.g. "step 0.60 m"
  eval::GaitReport report;
};

struct CurveComparisonOptions {
  std::string title = "Joint angles over the gait cycle";
  std::vector<GaitJoint> joints = {GaitJoint::Thigh, GaitJoint::Knee, GaitJoint::Ankle,
                                   GaitJoint::Toe};
  // Shades of one sequential scale instead of distinct hues, for walks ordered by a parameter
  // (a grid of step lengths).
  bool graded = false;
};

// The walks' mean curves, one panel per joint, beside the reference's mean +/- 2 SD (the paper
// compares steps of 0.60 and 0.70 m this way); each walk's legend entry has its RMSE and r, and
// a tick at the bottom marks its toe off. Throws std::invalid_argument without walks or joints.
svg::Figure plot_curve_comparison(std::span<const LabelledReport> walks,
                                  const eval::Normative* reference,
                                  const CurveComparisonOptions& options = {});

struct FilmstripOptions {
  int poses = 10;  // evenly in time across the stride
  int stride = 1;  // which left stride, from 0; the first often still carries the start pose
};

// The walker as a side-view stick figure across one stride (left heel strike to the next): the
// poses side by side, each centred on its pelvis over the ground under it and captioned with the
// cycle % and the left leg's gait phase; below, the same poses at their true places with the
// older ones fading (a chronophotograph), when each foot is on the ground, and how high the feet
// pass over it. Left and right legs in two colours (the right leg nearer the viewer), a trunk
// and head above the pelvis, dots under the foot points that bear on the ground. Throws
// std::invalid_argument when the walk has no such stride or an option is out of range.
svg::Figure plot_filmstrip(const eval::Motion& motion, const terrain::Terrain& terrain,
                           const FilmstripOptions& options = {});

struct WalkAnimationOptions {
  int first_stride = 1;      // the loop starts at this left heel strike, from 0
  int strides = 2;           // strides played in a loop; 0: the whole walk, from its first frame
  bool follow = true;        // the view travels with the walker; false: the whole path in view
  double frame_rate = 30.0;  // key frames per second (browsers interpolate between them)
  double view_width = 0.0;   // metres of ground in view when following; 0: four leg lengths
};

// The walker walking at real speed, as an SVG that plays in a loop in any browser (SMIL, no
// script): by default two steady strides, the view following at the walker's mean speed over
// ground marked so that the motion reads and the loop joins without a jump on level ground.
// Static viewers show the first frame. Throws std::invalid_argument when the walk has too few
// strides for the options or an option is out of range.
svg::Figure plot_walk_animation(const eval::Motion& motion, const terrain::Terrain& terrain,
                                const WalkAnimationOptions& options = {});

}  // namespace fuzzygait::plot
