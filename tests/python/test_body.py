"""The whole body from Python: a follower poses it bit for bit as C++'s PathFollower, planted feet
stay put on a 1 m turn, the arms swing against each other, game skeletons from arrays and files
are mapped and posed, objects outlive the names Python drops, and refusals name what was wrong."""
import gc
import math
import weakref

import numpy as np
import pytest

import fuzzygait as fg
from conftest import BODY_BITS, CLI, CLIP, run

S_CORNERS = [[0, 0], [0, 3], [3, 3], [3, 6]]
ON_GROUND = 0.002  # m: a foot point this close to the ground bears on it (eval's slip)


def test_a_python_follower_poses_as_the_cpp_follower_bit_for_bit():
    frames = 600
    lines = run(BODY_BITS, frames).splitlines()
    expected = [[float.fromhex(v) for v in line.split()] for line in lines]
    walker = fg.Walker(speed=1.2, stature=1.80)
    follower = fg.PathFollower(fg.Humanoid(1.80), fg.Path.polyline(S_CORNERS, 1.0), walker)
    assert len(expected) == frames
    for i, line in enumerate(expected):
        walker.advance(1 / 60)
        positions, rotations = follower.update(walker)
        mine = [*positions.ravel(), *rotations.ravel(), follower.pelvis_drop]
        assert mine == line, f"frame {i}"
    assert follower.positions[0][0] > 2.5  # round both corners


def turn_path(radius):
    """The C++ test's path: 2 m, a quarter turn left, 2 m, a quarter turn right, 3 m."""
    quarter = radius * math.pi / 2
    return fg.Path([(2.0, 0.0), (quarter, 1 / radius), (2.0, 0.0), (quarter, -1 / radius),
                    (3.0, 0.0)])


def planted_slip(path, speed, seconds):
    """The largest horizontal move in one 1/60 s frame of a heel, ball or toe tip that is on the
    ground in both frames (as tests/body/follower_test.cpp measures it), m."""
    walker = fg.Walker(speed=speed, stature=1.75)
    follower = fg.PathFollower(None, path, walker)
    joints = fg.JOINTS
    before = None
    worst = 0.0
    for _ in range(int(seconds * 60)):
        walker.advance(1 / 60)
        positions, _ = follower.update()
        heels = follower.heels
        points = np.array([[heels[leg], positions[joints.index(side + "Toes")],
                            positions[joints.index(side + "ToesEnd")]]
                           for leg, side in enumerate(("left", "right"))])  # (2, 3, 3)
        on_ground = walker.points[:, 3:, 1] < ON_GROUND  # heel, ball, tip of each leg
        if before is not None:
            moved = np.hypot(*(points - before[0])[..., [0, 2]].transpose(2, 0, 1))
            both = on_ground & before[1]
            worst = max(worst, float(moved[both].max(initial=0.0)))
        before = (points, on_ground)
    return worst


def test_planted_feet_do_not_slide_on_a_1_m_turn():
    path = turn_path(1.0)
    seconds = (path.length + 1.0) / 1.0
    turning = planted_slip(path, 1.0, seconds)
    straight = planted_slip(fg.Path(), 1.0, seconds)
    # tests/body/follower_test.cpp's bounds (it measures 0.65 mm a frame).
    assert turning < 1.0e-3
    assert turning < straight + 0.2e-3


def test_the_arms_swing_against_each_other_and_their_own_legs():
    walker = fg.Walker(speed=1.3, stature=1.75)
    follower = fg.PathFollower(fg.Humanoid(1.75), fg.Path(), walker)
    j = fg.JOINTS.index
    left, right, thigh = [], [], []
    for _ in range(1200):
        walker.advance(1 / 120)
        p, _ = follower.update()
        for series, side in ((left, "left"), (right, "right")):
            arm = p[j(side + "LowerArm")] - p[j(side + "UpperArm")]
            series.append(math.degrees(math.atan2(arm[2], -arm[1])))
        knee_ahead = p[j("leftLowerLeg")] - p[j("leftUpperLeg")]
        thigh.append(math.degrees(math.atan2(knee_ahead[2], -knee_ahead[1])))
    left, right, thigh = (np.array(s[240:]) for s in (left, right, thigh))  # past the start
    assert np.corrcoef(left, right)[0, 1] < -0.9
    assert np.corrcoef(left, thigh)[0, 1] < -0.8  # forward as its own leg swings back
    # tests/body/follower_test.cpp: people's 49.5 deg, within 20 %.
    assert 0.8 * 49.5 < left.max() - left.min() < 1.2 * 49.5
    arms_down = fg.PathFollower(fg.Humanoid(1.75), fg.Path(), walker, upper_body=False)
    p, _ = arms_down.update()
    assert p[j("leftHand")][2] == pytest.approx(p[j("leftUpperArm")][2], abs=1e-9)


# A Mixamo rig in centimetres facing -Z, as a game holds it: its joints' rest positions (the body's
# left at -X, facing away), no rest rotations.
MIXAMO = [  # name, parent, position (cm, facing +Z; turned below)
    ("Hips", None, (0, 100, -2)), ("Spine", "Hips", (0, 110, -3)),
    ("Spine1", "Spine", (0, 122, -3)), ("Spine2", "Spine1", (0, 135, -2)),
    ("Neck", "Spine2", (0, 152, -2)), ("Head", "Neck", (0, 162, 0)),
    ("HeadTop_End", "Head", (0, 180, 0))]
for side, x in (("Left", 1), ("Right", -1)):
    MIXAMO += [(side + "UpLeg", "Hips", (9 * x, 92, 0)),
               (side + "Leg", side + "UpLeg", (9 * x, 50, 0)),
               (side + "Foot", side + "Leg", (9 * x, 8, 0)),
               (side + "ToeBase", side + "Foot", (9 * x, 0, 13)),
               (side + "Toe_End", side + "ToeBase", (9 * x, 0, 20)),
               (side + "Shoulder", "Spine2", (3 * x, 146, -2)),
               (side + "Arm", side + "Shoulder", (17 * x, 145, -2)),
               (side + "ForeArm", side + "Arm", (45 * x, 145, -2)),
               (side + "Hand", side + "ForeArm", (70 * x, 145, -2))]


def mixamo_skeleton():
    names = ["mixamorig:" + n for n, _, _ in MIXAMO]
    parents = [-1 if p is None else [n for n, _, _ in MIXAMO].index(p) for _, p, _ in MIXAMO]
    world = np.array([p for _, _, p in MIXAMO], float) * [-1, 1, -1]  # facing -Z
    offsets = np.array([world[i] - (world[p] if p >= 0 else 0) for i, p in enumerate(parents)])
    return fg.Skeleton(names, parents, offsets, metres_per_unit=0.01)


def quat_multiply(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw])


def rotate(q, v):
    u = q[1:]
    t = 2 * np.cross(u, v)
    return v + q[0] * t + np.cross(u, t)


def forward_kinematics(skeleton, local, root):
    """World positions of a posed skeleton, in its units."""
    world_rotation, world_position = [], []
    for i, parent in enumerate(skeleton.parents):
        if parent < 0:
            world_rotation.append(local[i])
            world_position.append(root)
        else:
            world_rotation.append(quat_multiply(world_rotation[parent], local[i]))
            world_position.append(world_position[parent] +
                                  rotate(world_rotation[parent], skeleton.offsets[i]))
    return np.array(world_position)


def test_a_mixamo_skeleton_from_arrays_is_found_walked_and_posed():
    skeleton = mixamo_skeleton()
    poser = fg.SkeletonPoser(skeleton)
    assert poser.map["leftUpperLeg"] == "mixamorig:LeftUpLeg"
    assert poser.map["chest"] == "mixamorig:Spine2"
    assert poser.joint_count == len(skeleton) == len(MIXAMO)
    walker = fg.Walker(speed=1.2, segments=poser.humanoid.segments)
    follower = fg.PathFollower(poser.humanoid, fg.Path.polyline(S_CORNERS, 1.0), walker)
    names = skeleton.names
    hip_joints = [names.index("mixamorig:LeftUpLeg"), names.index("mixamorig:RightUpLeg")]
    worst = 0.0
    for frame in range(360):
        walker.advance(1 / 60)
        positions, rotations = follower.update()
        local, root = poser.pose(positions, rotations)
        assert local.shape == (len(skeleton), 4) and root.shape == (3,)
        if frame % 30 == 0:
            posed = forward_kinematics(skeleton, local, root) * 0.01
            for joint, name in poser.map.items():  # the body's hips: between the hip joints
                at = posed[hip_joints].mean(axis=0) if joint == "hips" else posed[names.index(name)]
                worst = max(worst, np.abs(at - positions[fg.JOINTS.index(joint)]).max())
    # tests/body/skeleton_test.cpp: within 1.4e-15 m for Mixamo rigs.
    assert worst < 1e-12
    # A pose that is not finite: the rest pose.
    positions[0, 0] = math.nan
    local, root = poser.pose(positions, rotations)
    assert (local == skeleton.rotations).all() and (root == skeleton.offsets[0]).all()


def test_a_map_by_hand_poses_a_skeleton_whose_names_are_not_known():
    mixamo = mixamo_skeleton()
    renamed = fg.Skeleton([n.replace("mixamorig:", "bone_") for n in mixamo.names], mixamo.parents,
                          mixamo.offsets, metres_per_unit=0.01)
    with pytest.raises(ValueError, match="hips"):
        fg.SkeletonPoser(renamed)
    legs = {"hips": "bone_Hips"}
    for side, mixamo_side in (("left", "Left"), ("right", "Right")):
        legs.update({side + "UpperLeg": f"bone_{mixamo_side}UpLeg",
                     side + "LowerLeg": f"bone_{mixamo_side}Leg",
                     side + "Foot": f"bone_{mixamo_side}Foot"})
    poser = fg.SkeletonPoser(renamed, legs)
    assert poser.map == legs
    with pytest.raises(ValueError, match="no body joint 'leftKnee'"):
        fg.SkeletonPoser(renamed, {**legs, "leftKnee": "bone_LeftLeg"})


def test_skeletons_are_read_from_bvh_and_gltf_files(tmp_path):
    cmu = fg.Skeleton.read(CLIP)
    poser = fg.SkeletonPoser(cmu)
    assert poser.map["leftUpperLeg"] == "LeftUpLeg" and cmu.declared_map is None
    assert cmu.metres_per_unit == pytest.approx(0.0254 / 0.45)
    assert len(fg.Skeleton.read(CLIP, metres_per_unit=0.01)) == len(cmu)
    # `fuzzygait walk --path --gltf` writes the body as glTF: the humanoid's own skeleton.
    (tmp_path / "path.csv").write_text("x,z\n0,0\n0,2\n")
    run(CLI, "walk", "--path", tmp_path / "path.csv", "--gltf", "-o", tmp_path / "walk")
    body = fg.Skeleton.read(tmp_path / "walk.body.glb")
    assert body.metres_per_unit == 1.0 and "leftUpperLeg" in body.names
    assert fg.SkeletonPoser(body).map["leftFoot"] == "leftFoot"


def test_a_follower_keeps_its_path_and_walker_alive():
    def make():
        walker = fg.Walker(speed=1.2)
        path = fg.Path.polyline(S_CORNERS, 1.0)
        return fg.PathFollower(None, path, walker), weakref.ref(walker), weakref.ref(path)

    follower, walker, path = make()
    gc.collect()
    assert walker() is not None and path() is not None
    assert follower.walker is walker() and follower.path is path()
    for _ in range(60):
        walker().advance(1 / 60)
        positions, _ = follower.update()
    assert np.isfinite(positions).all()
    del follower
    gc.collect()
    assert walker() is None and path() is None


def test_step_width_in_metres_is_the_share_of_the_leg():
    walker = fg.Walker(speed=1.2)
    humanoid = fg.Humanoid.from_walker(walker)
    leg = walker.segments["thigh"] + walker.segments["shank"] + walker.segments["ankle_height"]
    a = fg.PathFollower(humanoid, fg.Path(), walker, step_width=0.2)
    b = fg.PathFollower(humanoid, fg.Path(), walker, step_width_per_leg_length=0.2 / leg)
    walker.advance(1 / 60)
    pa, pb = a.update()[0], b.update()[0]
    assert (pa == pb).all()
    left, right = pa[fg.JOINTS.index("leftFoot")], pa[fg.JOINTS.index("rightFoot")]
    assert left[0] - right[0] == pytest.approx(0.2, abs=0.02)


def test_joint_names_and_parents_are_the_bodys():
    assert len(fg.JOINTS) == len(fg.JOINT_PARENTS) == 26
    assert fg.JOINTS[:3] == ("hips", "spine", "chest") and fg.JOINT_PARENTS[0] == -1
    assert fg.PathFollower.names == fg.Humanoid.names == fg.JOINTS
    h = fg.Humanoid(1.80)
    assert h.offsets.shape == (26, 3) and h.segments == fg.segments_from_stature(1.80)
    assert h.hip_width > 0 and h.heel > 0


def test_refusals_name_what_was_wrong(tmp_path):
    with pytest.raises(ValueError, match="path point 3 is the same"):
        fg.Path.polyline([[0, 0], [0, 3], [0, 3], [2, 5]])
    with pytest.raises(ValueError, match="at least two points"):
        fg.Path.polyline([[0, 0]])
    with pytest.raises(ValueError, match=r"points must be an array of shape \(n, 2\), got \(3,\)"):
        fg.Path.polyline([0, 1, 2])
    with pytest.raises(ValueError, match="path piece 2: curvature"):
        fg.Path([(2.0, 0.0), (1.0, 4.0)])
    walker = fg.Walker(speed=1.2, stature=1.75)
    with pytest.raises(ValueError, match="leg segments are not the humanoid's"):
        fg.PathFollower(fg.Humanoid(1.60), fg.Path(), walker)
    with pytest.raises(ValueError, match="'look_ahead'"):
        fg.PathFollower(None, fg.Path(), walker, look_ahead=-1.0)
    with pytest.raises(ValueError, match="not both"):
        fg.PathFollower(None, fg.Path(), walker, step_width=0.1, step_width_per_leg_length=0.1)
    with pytest.raises(TypeError, match="walker must be a fuzzygait.Walker, not str"):
        fg.PathFollower(None, fg.Path(), "default")
    with pytest.raises(ValueError, match="stature"):
        fg.Humanoid(7.0)
    with pytest.raises(ValueError, match="skeleton joint 1 'Hips'"):
        fg.Skeleton(["Hips", "Hips"], [-1, 0], [[0, 1, 0], [0.1, 0, 0]])
    with pytest.raises(ValueError, match=r"offsets must be an array of shape \(2, 3\)"):
        fg.Skeleton(["Hips", "Spine"], [-1, 0], [[0, 1, 0]])
    with pytest.raises(ValueError, match="parents must hold one index per name"):
        fg.Skeleton(["Hips", "Spine"], [-1], [[0, 1, 0], [0, 1, 0]])
    broken = tmp_path / "broken.bvh"
    broken.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n")
    with pytest.raises(fg.ParseError, match="broken.bvh") as error:
        fg.Skeleton.read(broken)
    assert error.value.source.endswith("broken.bvh") and error.value.line > 0
    with pytest.raises(ValueError, match=r"hero\.fbx: expected a \.bvh, \.glb, \.gltf or \.vrm"):
        fg.Skeleton.read(tmp_path / "hero.fbx")
    with pytest.raises(ValueError, match="missing.glb"):
        fg.Skeleton.read(tmp_path / "missing.glb")
    poser = fg.SkeletonPoser(mixamo_skeleton())
    with pytest.raises(ValueError, match=r"positions must be an array of shape \(26, 3\)"):
        poser.pose(np.zeros((25, 3)), np.zeros((26, 4)))
