#include "fuzzygait/io/skeleton_file.hpp"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "body/skeleton_fixtures.hpp"
#include "fuzzygait/body/humanoid_map.hpp"
#include "fuzzygait/body/skeleton_poser.hpp"

namespace fuzzygait::io {
namespace {

using body::Joint;
using body::Quat;
using body::Vec3;

using body::testing::expect_near;
using body::testing::expect_same_rotation;

constexpr double kPi = std::numbers::pi;
constexpr double kCmuUnit = 0.0254 / 0.45;

std::filesystem::path cmu_clip() {
  return std::filesystem::path(FUZZYGAIT_SOURCE_DIR) / "data/mocap/cmu/07_01.bvh";
}

std::string name_of(const body::Skeleton& s, const body::HumanoidMap& map, Joint j) {
  return map[j] < 0 ? std::string("-") : s.joints[static_cast<std::size_t>(map[j])].name;
}

TEST(BvhSkeleton, CmuSkeletonReadAndMapped) {
  const body::Skeleton cmu = read_bvh_skeleton(cmu_clip());
  EXPECT_DOUBLE_EQ(cmu.metres_per_unit, kCmuUnit);  // guessed from its legs
  EXPECT_EQ(cmu.joints[0].name, "Hips");
  EXPECT_EQ(cmu.size(), 31u);  // 31 joints; End Sites are their joints' ends
  ASSERT_TRUE(cmu.joints[static_cast<std::size_t>(cmu.find("Head"))].end.has_value());
  const body::HumanoidMap map = body::map_humanoid(cmu);
  EXPECT_EQ(name_of(cmu, map, Joint::spine), "Spine");  // LowerBack lies on Hips
  EXPECT_EQ(name_of(cmu, map, Joint::chest), "Spine1");
  EXPECT_EQ(name_of(cmu, map, Joint::neck), "Neck1");       // Neck lies on Spine1
  EXPECT_EQ(name_of(cmu, map, Joint::left_shoulder), "-");  // LeftShoulder lies on Spine1
  EXPECT_EQ(name_of(cmu, map, Joint::left_upper_arm), "LeftArm");
  EXPECT_EQ(name_of(cmu, map, Joint::right_toes), "RightToeBase");
  EXPECT_EQ(name_of(cmu, map, Joint::left_hand_end), "-");  // found from LeftHand's children

  const body::Humanoid h = body::humanoid_from_skeleton(cmu, map);
  const rig::Segments s = h.segments();
  std::cout << "CMU 07 as a humanoid: thigh " << s.thigh << " m, shank " << s.shank
            << " m, ankle height " << s.ankle_height << " m, ball " << s.ball << " m, toe " << s.toe
            << " m, heel " << s.heel << " m, hip width " << h.hip_width() << " m, hips "
            << h[Joint::hips].y << " m\n";
  EXPECT_NEAR(s.thigh, 0.5 * (6.92576 + 7.15484) * kCmuUnit, 1e-4);
  EXPECT_GT(s.ankle_height, 0.02);
  EXPECT_LT(s.ankle_height, 0.04);
  EXPECT_NEAR(h.hip_width(), (1.85590 + 1.68297) * kCmuUnit, 1e-9);
}

TEST(BvhSkeleton, CmuSkeletonPosedFollowsTheBodyPose) {
  const body::Skeleton cmu = read_bvh_skeleton(cmu_clip());
  const body::HumanoidMap map = body::map_humanoid(cmu);
  const body::SkeletonPoser poser(cmu, map);
  // The legs differ between the sides by a few millimetres; the humanoid has their mean.
  const std::vector<Vec3> rest = body::rest_positions(cmu);
  auto bone = [&](Joint a, Joint b) {
    return cmu.metres_per_unit * body::length(rest[static_cast<std::size_t>(map[b])] -
                                              rest[static_cast<std::size_t>(map[a])]);
  };
  const double thigh_gap = std::abs(bone(Joint::left_upper_leg, Joint::left_lower_leg) -
                                    bone(Joint::right_upper_leg, Joint::right_lower_leg));
  const double leg_gap = std::abs(bone(Joint::left_upper_leg, Joint::left_lower_leg) +
                                  bone(Joint::left_lower_leg, Joint::left_foot) -
                                  bone(Joint::right_upper_leg, Joint::right_lower_leg) -
                                  bone(Joint::right_lower_leg, Joint::right_foot));
  double worst_leg = 0.0;
  for (int k = 0; k < 8; ++k) {
    const body::BodyPose pose = body::testing::walking_pose(poser.humanoid(), 0.8 * k, 0.4 * k,
                                                            static_cast<std::uint32_t>(k));
    const std::vector<Vec3> at = body::testing::posed_positions(cmu, poser, pose);
    auto posed = [&](Joint j) { return at[static_cast<std::size_t>(map[j])]; };
    // Every bone between two mapped joints points as the BodyPose's segment does.
    for (std::size_t i = 1; i < body::kJointCount; ++i) {
      const auto joint = static_cast<Joint>(i);
      const Joint above = *body::parent(joint);
      // (Not the feet: CMU's toe bases lie at other heights and angles on the two sides, and the
      // rig's feet are the sides' mean.)
      if (map[joint] < 0 || map[above] < 0 || above == Joint::hips) continue;
      if (joint == Joint::left_toes || joint == Joint::right_toes) continue;
      expect_near(body::normalized(posed(joint) - posed(above)),
                  body::normalized(pose[joint] - pose[above]), 1e-9,
                  std::string(body::name(joint)));
    }
    // The trunk exactly; the legs within the sides' difference.
    for (const Joint j : {Joint::spine, Joint::chest, Joint::neck, Joint::head,
                          Joint::left_upper_leg, Joint::right_upper_leg}) {
      expect_near(posed(j), pose[j], 1e-9, std::string(body::name(j)));
    }
    for (const Joint j : {Joint::left_lower_leg, Joint::right_lower_leg, Joint::left_foot,
                          Joint::right_foot, Joint::left_toes, Joint::right_toes}) {
      const double miss = body::length(posed(j) - pose[j]);
      worst_leg = std::max(worst_leg, miss);
    }
  }
  std::cout << "CMU 07 legs: thighs differ by " << thigh_gap * 1000 << " mm, legs by "
            << leg_gap * 1000 << " mm; the posed knees, ankles and toes miss the BodyPose by "
            << worst_leg * 1000 << " mm at most\n";
  EXPECT_LT(worst_leg, 0.5 * thigh_gap + 0.5 * leg_gap + 0.005);
}

TEST(BvhSkeleton, CmuFeetStandOnTheFloorWithinTheSidesDifference) {
  const body::Skeleton cmu = read_bvh_skeleton(cmu_clip());
  const body::HumanoidMap map = body::map_humanoid(cmu);
  const body::SkeletonPoser poser(cmu, map);
  body::BodyPose pose;  // standing in the reference pose on y = 0
  body::forward_kinematics(poser.humanoid(), poser.humanoid()[Joint::hips], pose);
  std::vector<Quat> local(cmu.size()), world(cmu.size());
  std::vector<Vec3> at(cmu.size());
  Vec3 root;
  ASSERT_TRUE(poser.pose(pose, local, root));
  body::forward_kinematics(cmu, local, root, at, world);
  double lowest = 1.0;
  double highest = -1.0;
  for (const rig::Side side : rig::kSides) {
    const auto toe = static_cast<std::size_t>(map[body::toes(side)]);
    const Vec3 tip = at[toe] + body::rotate(world[toe], *cmu.joints[toe].end);
    for (const double y : {at[toe].y, tip.y}) {
      lowest = std::min(lowest, cmu.metres_per_unit * y);
      highest = std::max(highest, cmu.metres_per_unit * y);
    }
  }
  std::cout << "CMU 07 standing: toe bases and tips from " << lowest * 1000 << " to "
            << highest * 1000 << " mm above the floor\n";
  EXPECT_GT(lowest, -0.006);
  EXPECT_LT(highest, 0.006);
}

TEST(BvhSkeleton, CmuClipUnposedGivesTheMocapReadersKnee) {
  // The canonical body read off each frame of the clip bends its knees as analyse_clip measures
  // them: the 3-D angle between thigh and shank.
  const BvhClip clip = read_bvh_file(cmu_clip());
  const body::Skeleton cmu = skeleton_from_bvh(clip);
  const body::SkeletonPoser poser(cmu, body::map_humanoid(cmu));
  const CapturedClip captured = read_clip(cmu_clip());
  std::vector<Quat> local(cmu.size()), world(cmu.size());
  double worst = 0.0;
  double deepest = 0.0;
  for (std::size_t i = 0; i < captured.motion.frames.size(); ++i) {
    Vec3 root;
    bvh_frame(clip, i + captured.skipped_frames, local, root);
    body::BodyPose pose;
    ASSERT_TRUE(poser.unpose(local, root, world, pose));
    for (const rig::Side side : rig::kSides) {
      const Vec3 thigh = pose[body::lower_leg(side)] - pose[body::upper_leg(side)];
      const Vec3 shank = pose[body::foot(side)] - pose[body::lower_leg(side)];
      const double knee = std::acos(
          std::clamp(body::dot(body::normalized(thigh), body::normalized(shank)), -1.0, 1.0));
      const double measured =
          captured.motion.frames[i].pose.legs[static_cast<std::size_t>(rig::index(side))].knee;
      worst = std::max(worst, std::abs(knee - measured));
      deepest = std::max(deepest, knee);
    }
  }
  std::cout << "CMU 07_01 unposed: " << captured.motion.frames.size()
            << " frames, knee flexion up to " << deepest * 180 / kPi
            << " deg, largest difference from analyse_clip " << worst * 180 / kPi << " deg\n";
  EXPECT_LT(worst, 1e-5);              // radians: acos of a nearly straight knee loses digits
  EXPECT_GT(deepest, 50 * kPi / 180);  // a walk's swing knee
}

// A few frames of a posed rig.
struct Animation {
  std::vector<Quat> rotations;
  std::vector<Vec3> roots;
};
Animation animate(const body::Skeleton& skeleton, const body::SkeletonPoser& poser, int frames) {
  Animation a;
  a.rotations.resize(skeleton.size() * static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    const body::BodyPose pose = body::testing::walking_pose(poser.humanoid(), 0.5 * f, 0.2 * f,
                                                            static_cast<std::uint32_t>(f + 1));
    Vec3 root;
    poser.pose(pose,
               std::span<Quat>(a.rotations)
                   .subspan(static_cast<std::size_t>(f) * skeleton.size(), skeleton.size()),
               root);
    a.roots.push_back(root);
  }
  return a;
}

TEST(BvhSkeleton, WrittenAnimationReadsBackWithinItsDecimals) {
  const body::Skeleton mixamo = body::testing::build_skeleton(
      body::testing::mixamo_joints(), body::axis_angle({0, 1, 0}, kPi), 0.01, 31);
  const body::SkeletonPoser poser(mixamo, body::map_humanoid(mixamo));
  const Animation a = animate(mixamo, poser, 10);
  for (const char* order : {"ZXY", "ZYX", "XYZ"}) {
    SkeletonBvhOptions options;
    options.rotation_order = order;
    std::ostringstream text;
    write_skeleton_bvh(text, mixamo, a.rotations, a.roots, options);
    std::ostringstream again;
    write_skeleton_bvh(again, mixamo, a.rotations, a.roots, options);
    EXPECT_EQ(text.str(), again.str());  // deterministic bytes
    EXPECT_EQ(text.str().find("-0.000000 "), std::string::npos);

    const BvhClip clip = read_bvh(text.str(), "written.bvh");
    const body::Skeleton back = skeleton_from_bvh(clip, 0.01);
    // The file lists the joints depth first: the same joints, found by name.
    ASSERT_EQ(back.size(), mixamo.size());
    std::vector<std::size_t> same(back.size());
    for (std::size_t j = 0; j < back.size(); ++j) {
      const int found = mixamo.find(back.joints[j].name);
      ASSERT_GE(found, 0) << back.joints[j].name;
      same[j] = static_cast<std::size_t>(found);
      const body::SkeletonJoint& original = mixamo.joints[same[j]];
      if (j == 0) continue;
      EXPECT_EQ(back.joints[static_cast<std::size_t>(back.joints[j].parent)].name,
                mixamo.joints[static_cast<std::size_t>(original.parent)].name);
      expect_near(back.joints[j].offset, original.offset, 5e-7, "offset");
    }
    std::vector<Quat> local(back.size());
    std::vector<Vec3> written(back.size()), read(back.size());
    std::vector<Quat> world(back.size());
    for (std::size_t f = 0; f < a.roots.size(); ++f) {
      Vec3 root;
      bvh_frame(clip, f, local, root);
      body::forward_kinematics(back, local, root, read, world);
      const std::span<const Quat> frame =
          std::span<const Quat>(a.rotations).subspan(f * mixamo.size(), mixamo.size());
      body::forward_kinematics(mixamo, frame, a.roots[f], written, world);
      for (std::size_t j = 0; j < back.size(); ++j) {
        expect_near(read[j], written[same[j]], 1e-5,
                    std::string(order) + " " + back.joints[j].name);
        expect_same_rotation(local[j], frame[same[j]], 1e-12, "rotation");
      }
    }
  }
}

TEST(BvhSkeleton, WriterRefusesWhatItCannotWrite) {
  const body::Skeleton vrm =
      body::testing::build_skeleton(body::testing::vrm_joints(), Quat{}, 1.0, 0);
  std::vector<Quat> rotations(vrm.size());
  std::vector<Vec3> roots(1);
  std::ostringstream out;
  SkeletonBvhOptions bad_order;
  bad_order.rotation_order = "XXY";
  EXPECT_THROW(write_skeleton_bvh(out, vrm, rotations, roots, bad_order), std::invalid_argument);
  rotations[3].x = std::nan("");
  try {
    write_skeleton_bvh(out, vrm, rotations, roots);
    FAIL() << "a NaN rotation was written";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("'upperChest'"), std::string::npos);
  }
  rotations.pop_back();
  rotations[3].x = 0.0;
  EXPECT_THROW(write_skeleton_bvh(out, vrm, rotations, roots), std::invalid_argument);
}

TEST(BvhSkeleton, EulerAnglesRebuildTheRotationInEveryOrder) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Vec3 axes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const char* order : {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"}) {
    for (int k = 0; k < 200; ++k) {
      Quat q = body::normalized(Quat{unit(random), unit(random), unit(random), unit(random)});
      if (k == 0) {  // gimbal lock: the middle angle at 90 degrees
        const int middle = order[1] - 'X';
        q = body::axis_angle(axes[order[0] - 'X'], 0.4) * body::axis_angle(axes[middle], kPi / 2) *
            body::axis_angle(axes[order[2] - 'X'], -0.3);
      }
      const std::array<double, 3> e = euler_angles(q, order);
      const Quat back = body::axis_angle(axes[order[0] - 'X'], e[0]) *
                        body::axis_angle(axes[order[1] - 'X'], e[1]) *
                        body::axis_angle(axes[order[2] - 'X'], e[2]);
      expect_same_rotation(back, q, 1e-12, order);
    }
  }
}

TEST(BvhSkeleton, CmuClipFrameRoundTripsThroughTheWriter) {
  const BvhClip clip = read_bvh_file(cmu_clip());
  const body::Skeleton cmu = skeleton_from_bvh(clip);
  std::vector<Quat> local(cmu.size());
  std::vector<Vec3> roots(1);
  bvh_frame(clip, 40, local, roots[0]);
  SkeletonBvhOptions options;
  options.rotation_order = "ZYX";  // CMU's
  std::ostringstream text;
  write_skeleton_bvh(text, cmu, local, roots, options);
  const BvhClip back = read_bvh(text.str(), "cmu-again.bvh");
  const std::span<const double> original = clip.frame(40);
  const std::span<const double> written = back.frame(0);
  ASSERT_EQ(original.size(), written.size());
  for (std::size_t c = 0; c < original.size(); ++c) {
    EXPECT_NEAR(written[c], original[c], 2e-5) << "channel " << c;
  }
}

// A glTF model of `skeleton`'s rest pose: its joints as a skin's nodes below `armature`.
tinygltf::Model gltf_model(const body::Skeleton& skeleton, const tinygltf::Node& armature) {
  tinygltf::Model model;
  model.nodes.push_back(armature);
  tinygltf::Skin skin;
  for (const body::SkeletonJoint& joint : skeleton.joints) {
    tinygltf::Node node;
    node.name = joint.name;
    node.translation = {joint.offset.x, joint.offset.y, joint.offset.z};
    node.rotation = {joint.rotation.x, joint.rotation.y, joint.rotation.z, joint.rotation.w};
    const int parent = joint.parent < 0 ? 0 : joint.parent + 1;
    model.nodes[static_cast<std::size_t>(parent)].children.push_back(
        static_cast<int>(model.nodes.size()));
    skin.joints.push_back(static_cast<int>(model.nodes.size()));
    model.nodes.push_back(node);
  }
  model.skins.push_back(skin);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  model.asset.version = "2.0";
  return model;
}

std::filesystem::path write_gltf(tinygltf::Model& model, const std::string& name, bool binary) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "fuzzygait_skeleton";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / name;
  tinygltf::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&model, file.string(), false, true, true, binary));
  return file;
}

TEST(GltfSkeleton, SkinReadWithItsArmaturesTurnAndScale) {
  const body::Skeleton mixamo = body::testing::build_skeleton(
      body::testing::mixamo_joints(), body::axis_angle({0, 1, 0}, kPi), 0.01, 41);
  tinygltf::Node armature;
  armature.name = "Armature";
  const Quat turn = body::axis_angle({1, 0, 0}, kPi / 2);
  armature.rotation = {turn.x, turn.y, turn.z, turn.w};
  armature.scale = {0.01, 0.01, 0.01};
  armature.translation = {0.5, 0.0, -0.25};
  tinygltf::Model model = gltf_model(mixamo, armature);
  const std::filesystem::path file = write_gltf(model, "mixamo.gltf", false);

  const body::Skeleton read = read_gltf_skeleton(file);
  EXPECT_DOUBLE_EQ(read.metres_per_unit, 0.01);
  ASSERT_EQ(read.size(), mixamo.size());
  const std::vector<Vec3> original = body::rest_positions(mixamo);
  const std::vector<Vec3> rest = body::rest_positions(read);
  for (std::size_t j = 0; j < read.size(); ++j) {
    EXPECT_EQ(read.joints[j].name, mixamo.joints[j].name);
    const Vec3 expected = Vec3{0.5, 0.0, -0.25} + 0.01 * body::rotate(turn, original[j]);
    expect_near(0.01 * rest[j], expected, 1e-9, read.joints[j].name);
  }
  // It poses as the rig it was made from (turned Z-up by the armature).
  const body::SkeletonPoser poser(read, body::map_humanoid(read));
  EXPECT_NEAR(poser.humanoid().segments().thigh, 0.42, 1e-9);
  EXPECT_FALSE(read_vrm_humanoid_map(file, read).has_value());
  EXPECT_THROW(read_gltf_skeleton(file, 1), std::invalid_argument);
  EXPECT_THROW(read_gltf_skeleton(file.parent_path() / "missing.gltf"), std::invalid_argument);
}

TEST(GltfSkeleton, VrmExtensionsGiveTheMapWhateverTheNames) {
  // The VRM rig with names no convention knows: only the extension tells the bones.
  const body::Skeleton named =
      body::testing::build_skeleton(body::testing::vrm_joints(), Quat{}, 1.0, 3);
  body::Skeleton anonymous = named;
  for (std::size_t j = 0; j < anonymous.size(); ++j) {
    anonymous.joints[j].name = "bone_" + std::to_string(j);
  }
  const body::HumanoidMap expected = body::map_humanoid(named);
  for (const bool version_1 : {true, false}) {
    tinygltf::Node armature;
    armature.name = "Armature";
    tinygltf::Model model = gltf_model(anonymous, armature);
    tinygltf::Value::Object by_bone;
    tinygltf::Value::Array listed;
    for (std::size_t j = 0; j < named.size(); ++j) {
      const std::string& bone = named.joints[j].name;  // VRM's own bone names
      const int node = static_cast<int>(j) + 1;        // after the armature
      by_bone[bone] = tinygltf::Value(tinygltf::Value::Object{{"node", tinygltf::Value(node)}});
      listed.push_back(tinygltf::Value(tinygltf::Value::Object{{"bone", tinygltf::Value(bone)},
                                                               {"node", tinygltf::Value(node)}}));
    }
    const tinygltf::Value humanoid(tinygltf::Value::Object{
        {"humanBones", version_1 ? tinygltf::Value(by_bone) : tinygltf::Value(listed)}});
    const std::string extension = version_1 ? "VRMC_vrm" : "VRM";
    model.extensions[extension] = tinygltf::Value(tinygltf::Value::Object{{"humanoid", humanoid}});
    model.extensionsUsed.push_back(extension);
    const std::filesystem::path file =
        write_gltf(model, version_1 ? "rig_1.vrm" : "rig_0.vrm", true);

    const body::Skeleton read = read_gltf_skeleton(file);
    EXPECT_THROW(body::map_humanoid(read), std::invalid_argument);  // no name is known
    const std::optional<body::HumanoidMap> map = read_vrm_humanoid_map(file, read);
    ASSERT_TRUE(map.has_value()) << extension;
    EXPECT_EQ(map->joint, expected.joint) << extension;
  }
}

}  // namespace
}  // namespace fuzzygait::io
