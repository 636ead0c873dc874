# The Blender add-on (apps/blender/fuzzygait_blender) in Blender itself, in background mode:
#
#   blender -b --factory-startup --python-exit-code 1 --python test_addon.py -- \
#       [--module-dir build/python] --addon-dir apps/blender --cli build/fuzzygait \
#       --work DIR [CASE...]
#
# Without --module-dir the add-on must find the module itself (an installed add-on does).
# Cases: straight (the project's own BVH skeleton, imported by Blender's importer, walked by the
# operator: keys on every frame, knees, ankles, balls and toe tips where the walker has them, the
# distance), curve (a quarter circle: the hips on it, facing along it, planted feet staying put),
# rigs (Mixamo- and Rigify-named armatures built here, rotated, scaled and with rolled bones:
# found by name and posed where the walker is), errors (each refusal, with its message, writing
# nothing), panel (the sidebar panel draws existing properties and passes them all to the
# operator; Find bones), register (the add-on unregisters and registers again) and body (the whole
# body of a Mixamo rig with arms: each bone where a Python follower puts its joint, along a curve
# the arms swinging and the feet planted). Exits 1 when a check fails.
import argparse
import math
import os
import subprocess
import sys
import time
import traceback
import types

import bpy
from mathutils import Matrix, Vector

parser = argparse.ArgumentParser()
parser.add_argument("--module-dir", default="")
parser.add_argument("--addon-dir", required=True)
parser.add_argument("--cli", required=True)
parser.add_argument("--work", required=True)
parser.add_argument("cases", nargs="*")
args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
if args.module_dir:
    sys.path.insert(0, args.module_dir)
sys.path.insert(0, args.addon_dir)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import fuzzygait_blender  # noqa: E402
from fuzzygait_blender import rig, ui, walk  # noqa: E402
import scenes  # noqa: E402

fuzzygait_blender.register()
fg = walk.import_module(ui.module_dirs(bpy.context))
print("fuzzygait module:", fg.__file__)
print("add-on:", fuzzygait_blender.__file__)
os.makedirs(args.work, exist_ok=True)

FPS, FIRST, LAST = 30, 1, 120
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def new_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for action in list(bpy.data.actions):
        bpy.data.actions.remove(action)
    bpy.context.view_layer.update()
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = FPS, 1.0
    scene.frame_start, scene.frame_end = FIRST, LAST
    return scene


def activate(obj):
    for other in bpy.context.scene.objects:
        other.select_set(False)
    if obj is not None:
        obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def import_walk_bvh():
    """The skeleton `fuzzygait walk` writes (1.75 m), imported in metres, feet on z = 0."""
    prefix = os.path.join(args.work, "walk")
    if not os.path.exists(prefix + ".bvh"):
        subprocess.run([args.cli, "walk", "--cycles", "2", "-o", prefix], check=True,
                       stdout=subprocess.DEVNULL)
    obj = scenes.import_bvh(prefix + ".bvh", 0.01)
    obj.animation_data_clear()
    for bone in obj.pose.bones:
        bone.matrix_basis = Matrix()
    obj.location.z = 0.927365  # the BVH's hips at the origin: its feet onto the ground
    bpy.context.view_layer.update()
    return obj


def world_head(obj, name):
    return obj.matrix_world @ obj.pose.bones[name].head


def expected_walker(stature, segments, speed=1.3):
    return fg.Walker("default", speed=speed, stature=stature, segments=segments)


def compare_legs(obj, mapping, start, forward, scale, walker, label):
    """Max distance (walker metres) between the knees, ankles, balls (toe heads) and toe tips in
    Blender and the walker's points placed along the straight path from start (world) along
    forward (world, level)."""
    up = Vector((0, 0, 1))
    hip_rest = (world_head(obj, mapping["thigh_l"]) + world_head(obj, mapping["thigh_r"])) / 2
    lateral = {side: world_head(obj, mapping["thigh_" + side]) - hip_rest for side in "lr"}
    x0 = float(walker.pelvis[0])
    worst = 0.0
    for frame in range(FIRST, LAST + 1):
        if frame > FIRST:
            walker.advance(1 / FPS)
        bpy.context.scene.frame_set(frame)
        points = walker.points
        for leg, side in enumerate("lr"):
            toe = obj.pose.bones[mapping["toe_" + side]]
            joints = {1: world_head(obj, mapping["shin_" + side]),
                      2: world_head(obj, mapping["foot_" + side]),
                      4: obj.matrix_world @ toe.head, 5: obj.matrix_world @ toe.tail}
            for j, got in joints.items():
                x, y = points[leg][j]
                want = start + forward * ((x - x0) * scale) + up * (y * scale) + lateral[side]
                worst = max(worst, (got - want).length / scale)
    print("%s: knees, ankles, balls and toe tips within %.3f mm of the walker's"
          % (label, worst * 1000))
    check(worst < 0.001, "%s: knees, ankles, balls and toe tips %.3f mm off the walker's"
          % (label, worst * 1e3))


def case_straight():
    scene = new_scene()
    obj = import_walk_bvh()
    activate(obj)
    start = obj.matrix_world @ Vector((0, 0, -0.927365))
    bpy.ops.fuzzygait.walk_armature(speed=1.3)
    mapping = rig.auto_map(obj.data.bones)
    check(mapping["thigh_l"] == "LeftUpLeg" and mapping["toe_r"] == "RightToeBase"
          and mapping["pelvis"] == "Hips" and mapping["spine"] == "Spine",
          "the BVH skeleton's bones: %s" % mapping)
    action = obj.animation_data.action
    keyed = {}
    for curve in action.fcurves:
        frames = sorted(round(p.co.x) for p in curve.keyframe_points)
        keyed[curve.data_path] = frames
        check(frames == list(range(FIRST, LAST + 1)),
              "%s[%d] keyed on %d frames, not %d-%d" % (curve.data_path, curve.array_index,
                                                      len(frames), FIRST, LAST))
    for name in ("Hips", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "RightUpLeg",
                 "RightLeg", "RightFoot", "RightToeBase", "Spine"):
        check(any('"%s"' % name in p for p in keyed), "no keys on %s" % name)
    check('pose.bones["Hips"].location' in keyed, "the pelvis's location is not keyed")

    segments = fg.segments_from_stature(1.75)
    compare_legs(obj, mapping, start, Vector((0, -1, 0)), 1.0, expected_walker(1.75, segments),
                 "BVH skeleton")
    scene.frame_set(FIRST)
    hip_first = world_head(obj, "LeftUpLeg")
    scene.frame_set(LAST)
    travel = (hip_first - world_head(obj, "LeftUpLeg")).y
    want = 1.3 * (LAST - FIRST) / FPS
    print("straight: travelled %.3f m in %.3f s, %.2f %% off 1.3 m/s"
          % (travel, (LAST - FIRST) / FPS, 100 * (travel / want - 1)))
    check(abs(travel / want - 1) < 0.03, "travelled %.3f m, not %.3f within 3 %%" % (travel, want))

    # A second walk replaces the keys in range and keeps the others.
    curve = action.fcurves.find('pose.bones["LeftLeg"].rotation_euler', index=0)
    curve.keyframe_points.insert(LAST + 10, 0.5)
    bpy.ops.fuzzygait.walk_armature(speed=1.3)
    frames = sorted(round(p.co.x) for p in curve.keyframe_points)
    check(frames == list(range(FIRST, LAST + 1)) + [LAST + 10],
          "walking again: LeftLeg keyed on %s" % frames[-3:])


def case_curve():
    scene = new_scene()
    obj = import_walk_bvh()
    radius = 4.0
    curve = scenes.quarter_circle(radius)
    activate(obj)
    bpy.ops.fuzzygait.walk_armature(speed=1.3, path="CURVE", curve=curve.name)
    centre = Vector((radius, 0, 0))
    worst_off, worst_heading, last_angle, worst_slide = 0.0, 0.0, 0.0, 0.0
    walker = expected_walker(1.75, fg.segments_from_stature(1.75))
    planted = {}
    for frame in range(FIRST, LAST + 1):
        if frame > FIRST:
            walker.advance(1 / FPS)
        scene.frame_set(frame)
        # A foot flat or on its ball keeps its ball (the toe's head) where it is.
        for leg, side in enumerate(("Left", "Right")):
            ball = obj.matrix_world @ obj.pose.bones[side + "ToeBase"].head
            if walker.phases[leg] in ("flat", "ball"):
                if leg in planted:
                    worst_slide = max(worst_slide, (ball - planted[leg]).length)
                planted[leg] = ball
            else:
                planted.pop(leg, None)
        hip = (world_head(obj, "LeftUpLeg") + world_head(obj, "RightUpLeg")) / 2
        radial = (hip - centre).xy
        worst_off = max(worst_off, abs(radial.length - radius))
        tangent = Vector((radial.y, -radial.x)).normalized()  # turning left from -Y
        # The body's facing: the posed thighs' axis (left to right) turned a quarter turn.
        across = (world_head(obj, "RightUpLeg") - world_head(obj, "LeftUpLeg")).xy
        facing = Vector((across.y, -across.x)).normalized()
        worst_heading = max(worst_heading, abs(math.degrees(facing.angle_signed(tangent))))
        last_angle = math.degrees(math.atan2(-radial.y, -radial.x))
    print("curve: hips within %.2f mm of the circle, facing within %.3f deg of its tangent, "
          "%.1f deg round" % (worst_off * 1000, worst_heading, last_angle))
    check(worst_off < 0.01, "the hips left the curve by %.1f mm" % (worst_off * 1000))
    check(worst_heading < 1.0, "the body faced %.2f deg off the tangent" % worst_heading)
    check(last_angle > 45, "the walk went only %.1f deg round the quarter circle" % last_angle)
    print("curve: a planted ball slides at most %.2f mm a frame" % (worst_slide * 1000))
    check(worst_slide < 0.003, "a planted ball slid %.2f mm a frame" % (worst_slide * 1000))


def build_armature(name, bones, matrix_world):
    """bones: (name, parent, head, tail, roll, connected) in armature space."""
    data = bpy.data.armatures.new(name)
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    obj.matrix_world = matrix_world
    activate(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    for bone_name, parent, head, tail, roll, connected in bones:
        edit = data.edit_bones.new(bone_name)
        edit.head, edit.tail, edit.roll = head, tail, roll
        if parent:
            edit.parent = data.edit_bones[parent]
            edit.use_connect = connected
    bpy.ops.object.mode_set(mode="OBJECT")
    return obj


def leg_bones(names, side, x, hip_z, knee, ankle, ball, tip, forward_sign, up_axis):
    """A leg's bones from heights and forward offsets (metres, before the rig's own axes)."""
    def at(lat, fwd, height):
        if up_axis == "Y":  # Mixamo: Y up, +Z forward, centimetres
            return Vector((lat, height, forward_sign * fwd)) * 100
        return Vector((lat, forward_sign * fwd, height))
    thigh, shin, foot, toe = names
    lat = x if side == "l" else -x
    return [
        (thigh, None, at(lat, 0, hip_z), at(lat, knee[0], knee[1]), 0.7, False),
        (shin, thigh, at(lat, knee[0], knee[1]), at(lat, ankle[0], ankle[1]), -1.1, True),
        (foot, shin, at(lat, ankle[0], ankle[1]), at(lat, ball[0], ball[1]), 2.0, True),
        (toe, foot, at(lat, ball[0], ball[1]), at(lat, tip[0], tip[1]), -0.4, True),
    ]


def rig_case(label, names, pelvis, spine, matrix_world, up_axis, forward_sign):
    bones = []
    hip_z = 0.93
    for side in "lr":
        leg = leg_bones([n % {"L": "Left" if side == "l" else "Right", "l": side.upper()}
                         for n in names], side, 0.09, hip_z, (0.02, 0.50), (0.0, 0.07),
                        (0.13, 0.0), (0.20, 0.0), forward_sign, up_axis)
        leg[0] = leg[0][:1] + (pelvis,) + leg[0][2:]
        bones.extend(leg)
    up_vec = Vector((0, 100, 0)) if up_axis == "Y" else Vector((0, 0, 1))
    pelvis_head = up_vec * (hip_z - 0.02)
    bones.insert(0, (pelvis, None, pelvis_head, pelvis_head + up_vec * 0.1, 0.3, False))
    bones.insert(1, (spine, pelvis, pelvis_head + up_vec * 0.1, pelvis_head + up_vec * 0.4,
                     0.0, True))
    obj = build_armature(label, bones, matrix_world)
    mapping = rig.auto_map(obj.data.bones)
    check(all(mapping[key] for key, _, _ in rig.ROLES), "%s: bones not found: %s"
          % (label, [k for k, v in mapping.items() if not v]))
    check(mapping["pelvis"] == pelvis and mapping["spine"] == spine,
          "%s: pelvis and spine mapped as %s, %s" % (label, mapping["pelvis"], mapping["spine"]))
    scene = bpy.context.scene
    settings = walk.Settings(frame_start=FIRST, frame_end=LAST, fps=FPS, speed=1.3)
    result = walk.walk_armature(obj, settings, bpy.context.evaluated_depsgraph_get())
    scene.frame_set(FIRST)
    bpy.context.view_layer.update()
    # The walk starts under the rest hips and goes the way the toes point, in world space.
    obj_rest = obj.matrix_world
    arm = obj.data.bones
    hip = obj_rest @ ((arm[mapping["thigh_l"]].head_local + arm[mapping["thigh_r"]].head_local)
                      / 2)
    toe = obj_rest @ arm[mapping["toe_l"]].tail_local
    start = Vector((hip.x, hip.y, toe.z))
    forward = (toe - obj_rest @ arm[mapping["foot_l"]].head_local)
    forward.z = 0
    print("%s: stature %.3f m, %.4g units a metre" % (label, result.stature, result.scale))
    check(abs(result.stature - 0.93 / 0.530) < 0.01, "%s: stature %.3f" % (label, result.stature))
    # The lateral offsets come from the rest pose: reset to it for the comparison's start.
    compare_legs(obj, mapping, start, forward.normalized(), result.scale,
                 expected_walker(result.stature, result.segments), label)
    # The pelvis tilts as the walker's (11 deg, the default set's), the spine stays upright.
    scene.frame_set(LAST // 2)
    spine = obj.pose.bones[mapping["spine"]]
    pelvis = obj.pose.bones[mapping["pelvis"]]
    spine_axis = (obj.matrix_world @ spine.tail - obj.matrix_world @ spine.head).normalized()
    pelvis_axis = (obj.matrix_world @ pelvis.tail - obj.matrix_world @ pelvis.head).normalized()
    lean = math.degrees(spine_axis.angle(Vector((0, 0, 1))))
    tilt = math.degrees(pelvis_axis.angle(Vector((0, 0, 1))))
    print("%s: spine %.3f deg off upright, pelvis tilted %.2f deg" % (label, lean, tilt))
    check(lean < 0.01, "%s: the spine leans %.3f deg" % (label, lean))
    check(abs(tilt - 11.0) < 0.1, "%s: the pelvis is tilted %.2f deg, not 11" % (label, tilt))
    check(pelvis_axis.dot(forward) > 0, "%s: the pelvis tilts backwards" % label)


def case_rigs():
    new_scene()
    bpy.context.scene.unit_settings.scale_length = 1.0
    # Mixamo: centimetres, Y up, as its FBX files come in (the object turned and scaled).
    mixamo = Matrix.Translation((2, 0, 0)) @ Matrix.Rotation(math.pi / 2, 4, "X") @ \
        Matrix.Scale(0.01, 4)
    rig_case("mixamo", ["mixamorig:%(L)sUpLeg", "mixamorig:%(L)sLeg", "mixamorig:%(L)sFoot",
                        "mixamorig:%(L)sToeBase"], "mixamorig:Hips", "mixamorig:Spine",
             mixamo, "Y", 1)
    # Rigify's meta-rig names, facing -Y, turned 30 degrees about Z and moved.
    rigify = Matrix.Translation((-3, 1, 0)) @ Matrix.Rotation(math.radians(30), 4, "Z")
    rig_case("rigify", ["thigh.%(l)s", "shin.%(l)s", "foot.%(l)s", "toe.%(l)s"], "spine",
             "spine.001", rigify, "Z", -1)


def refused(words, **options):
    """Runs the operator expecting a refusal whose message holds `words`."""
    try:
        result = bpy.ops.fuzzygait.walk_armature(**options)
    except RuntimeError as error:
        message = str(error)
        check(words in message, "refusal '%s' does not say '%s'" % (message.strip(), words))
        print("refused as expected:", message.strip().splitlines()[0])
        return
    check(False, "not refused (%s, wanted '%s'): %s" % (result, words, options))


def case_errors():
    new_scene()
    activate(None)
    refused("no armature is active")
    mesh = bpy.data.objects.new("mesh", bpy.data.meshes.new("mesh"))
    bpy.context.scene.collection.objects.link(mesh)
    activate(mesh)
    refused("no armature is active")
    legless = build_armature("legless", [("Hips", None, (0, 0, 1), (0, 0, 1.1), 0, False),
                                         ("LeftUpLeg", "Hips", (0.1, 0, 1), (0.1, 0, 0.5), 0,
                                          False)], Matrix())
    refused("no left shin bone")
    refused("right thigh bone 'Nope' is not in the armature", thigh_r="Nope")
    obj = import_walk_bvh()
    activate(obj)
    refused("does not exist", controller_folder=os.path.join(args.work, "no such set"))
    empty = os.path.join(args.work, "empty set")
    os.makedirs(empty, exist_ok=True)
    refused("controller set folder", controller_folder=empty)
    refused("not a built-in controller set", controllers="sprint")
    refused("speed must be a finite number", speed=float("nan"))
    refused("speed must be above 0", speed=-1.0)
    refused("step length must be above 0", pace="STEP", step_length=0.0)
    refused("stature must be 0 (measured) or above", stature=-1.0)
    refused("the walker cannot walk this armature", speed=40.0)
    refused("is not a curve object", path="CURVE", curve="legless")
    refused("no curve to walk along", path="CURVE")
    check(obj.animation_data is None or obj.animation_data.action is None,
          "a refused walk wrote keyframes")
    check(legless.animation_data is None, "a refused walk wrote keyframes on the legless rig")


class FakeLayout:
    """Stands in for a panel's layout: checks that each property drawn exists."""

    def __init__(self):
        self.operators = []

    def _has(self, data, name):
        check(name in data.bl_rna.properties, "the panel draws a missing property %r" % name)

    def prop(self, data, name, **_):
        self._has(data, name)

    def prop_search(self, data, name, search_data, search_name, **_):
        self._has(data, name)
        check(hasattr(search_data, search_name), "the panel searches %r" % search_name)

    def operator(self, idname, **_):
        module, name = idname.split(".")
        # (bpy.ops answers any attribute with a wrapper: only dir() lists the registered ones.)
        check(name in dir(getattr(bpy.ops, module)), "the panel's operator %s" % idname)
        self.operators.append(type("Properties", (), {})())
        return self.operators[-1]

    def label(self, **_):
        pass

    def column(self, **_):
        return self

    row = box = column


def case_panel():
    scene = new_scene()
    obj = import_walk_bvh()
    activate(obj)
    bpy.ops.fuzzygait.map_bones()
    check(scene.fuzzygait.thigh_l == "LeftUpLeg" and scene.fuzzygait.toe_r == "RightToeBase",
          "Find bones filled in %s, %s" % (scene.fuzzygait.thigh_l, scene.fuzzygait.toe_r))
    for pace, path in (("SPEED", "STRAIGHT"), ("STEP", "CURVE")):
        scene.fuzzygait.pace, scene.fuzzygait.path = pace, path
        scene.fuzzygait.use_scene_range = path == "STRAIGHT"
        layout = FakeLayout()
        ui.FUZZYGAIT_PT_walk.draw(types.SimpleNamespace(layout=layout), bpy.context)
        walk_button = layout.operators[-1]
        for key in list(ui.walk_properties()) + ui.BONE_ROLES:
            check(getattr(walk_button, key, None) == getattr(scene.fuzzygait, key),
                  "the panel's button does not pass %s" % key)


def case_register():
    fuzzygait_blender.unregister()
    check(not hasattr(bpy.ops.fuzzygait, "walk_armature") or
          "walk_armature" not in dir(bpy.ops.fuzzygait), "the operator outlived unregister()")
    fuzzygait_blender.register()
    new_scene()
    obj = import_walk_bvh()
    activate(obj)
    bpy.context.scene.frame_end = 10
    bpy.ops.fuzzygait.walk_armature(pace="STEP", step_length=0.7, controllers="heavy")
    check(obj.animation_data.action is not None, "no keys after registering again")


# A Mixamo rig with arms, metres, Z up, facing -Y (the body's left at +X): (name, parent, the
# body's (left, up, forward) position), each bone's tail at its first child's head.
MIXAMO_BODY = [("Hips", None, (0, 1.00, 0.02)), ("Spine", "Hips", (0, 1.10, 0.0)),
               ("Spine1", "Spine", (0, 1.22, 0.0)), ("Spine2", "Spine1", (0, 1.35, 0.01)),
               ("Neck", "Spine2", (0, 1.52, 0.01)), ("Head", "Neck", (0, 1.62, 0.02)),
               ("HeadTop_End", "Head", (0, 1.80, 0.02))]
for _side, _x in (("Left", 1), ("Right", -1)):
    MIXAMO_BODY += [(_side + "UpLeg", "Hips", (0.09 * _x, 0.92, 0)),
                    (_side + "Leg", _side + "UpLeg", (0.09 * _x, 0.50, 0.01)),
                    (_side + "Foot", _side + "Leg", (0.09 * _x, 0.08, 0)),
                    (_side + "ToeBase", _side + "Foot", (0.09 * _x, 0, 0.13)),
                    (_side + "Toe_End", _side + "ToeBase", (0.09 * _x, 0, 0.20)),
                    (_side + "Shoulder", "Spine2", (0.03 * _x, 1.46, 0)),
                    (_side + "Arm", _side + "Shoulder", (0.17 * _x, 1.45, 0)),
                    (_side + "ForeArm", _side + "Arm", (0.45 * _x, 1.45, 0)),
                    (_side + "Hand", _side + "ForeArm", (0.70 * _x, 1.45, 0))]


RIGIFY_LEGS = {"Hips": "spine", "LeftUpLeg": "thigh.L", "LeftLeg": "shin.L",
               "LeftFoot": "foot.L", "LeftToeBase": "toe.L", "RightUpLeg": "thigh.R",
               "RightLeg": "shin.R", "RightFoot": "foot.R", "RightToeBase": "toe.R"}


def mixamo_body_armature(name, names=None):
    """The rig as an armature; names: {joint: bone name}, "mixamorig:" + joint for the rest."""
    def bone_name(joint):
        return (names or {}).get(joint, "mixamorig:" + joint)
    at = {n: Vector((p[0], -p[2], p[1])) for n, _, p in MIXAMO_BODY}
    bones = []
    for n, parent, _ in MIXAMO_BODY:
        child = next((c for c, p, _ in MIXAMO_BODY if p == n), None)
        tail = at[child] if child else at[n] + (at[n] - at[parent]).normalized() * 0.05
        bones.append((bone_name(n), parent and bone_name(parent), at[n], tail, 0.3, False))
    obj = build_armature(name, bones, Matrix())
    for bone in obj.pose.bones:
        bone.rotation_mode = "XYZ" if "Arm" in bone.name else "QUATERNION"
    return obj


def body_against_follower(obj, label):
    """Walks the armature's whole body straight on and checks each bone the add-on's poser maps
    against a follower in Python: the bone's head where the follower puts its joint."""
    from fuzzygait_blender import body
    scene = bpy.context.scene
    activate(obj)
    bpy.ops.fuzzygait.walk_armature(speed=1.2, whole_body=True)
    check(obj.animation_data.action is not None, "%s: no keys" % label)
    bones = obj.data.bones
    mapping = rig.resolve_map(bones, {})
    skeleton, _ = body.skeleton_of(fg, obj, mapping["pelvis"], 1.0)
    poser = body.poser_of(fg, skeleton, mapping)
    walker = fg.Walker(speed=1.2, segments=poser.humanoid.segments)
    route = body.route_of(fg, None, None, float(walker.pelvis[0]))  # on from under the hips
    follower = fg.PathFollower(poser.humanoid, route, walker)
    start = (bones[mapping["thigh_l"]].head_local + bones[mapping["thigh_r"]].head_local) / 2
    start.z = 0.0  # on the ground
    worst = 0.0
    for frame in range(FIRST, LAST + 1):
        if frame > FIRST:
            walker.advance(1 / FPS)
        positions, _ = follower.update()
        scene.frame_set(frame)
        for joint, name in poser.map.items():
            if joint == "hips":  # the body's hips: between the hip joints, not a bone's head
                continue
            x, y, z = positions[fg.JOINTS.index(joint)]
            worst = max(worst, (world_head(obj, name) - (start + Vector((x, -z, y)))).length)
    print("%s: %d mapped bones within %.4f mm of the follower's joints"
          % (label, len(poser.map), worst * 1e3))
    check(worst < 1e-4, "%s: a bone %.4f mm off the follower's joint" % (label, worst * 1e3))
    return poser.map


def case_body():
    """The whole body: on a straight path each mapped bone's head where a follower puts its joint
    (Mixamo's names; Rigify's legs through the add-on's bone map); along a quarter circle the hips
    on it, the arms swinging against each other, planted balls staying put."""
    new_scene()
    check("leftHand" in body_against_follower(mixamo_body_armature("body"), "body"),
          "body: the hands were not mapped")
    new_scene()
    legs = body_against_follower(mixamo_body_armature("rigify", RIGIFY_LEGS), "rigify legs")
    check(legs.get("leftUpperLeg") == "thigh.L", "rigify legs: mapped as %s" % legs)

    scene = new_scene()
    obj = mixamo_body_armature("body")
    radius = 4.0
    curve = scenes.quarter_circle(radius)
    activate(obj)
    bpy.ops.fuzzygait.walk_armature(speed=1.3, path="CURVE", curve=curve.name, whole_body=True)
    centre = Vector((radius, 0, 0))
    worst_off, worst_slide, last_angle, planted_frames = 0.0, 0.0, 0.0, 0
    hands = {"Left": [], "Right": []}
    before = {}
    for frame in range(FIRST, LAST + 1):
        scene.frame_set(frame)
        hip = (world_head(obj, "mixamorig:LeftUpLeg") + world_head(obj, "mixamorig:RightUpLeg")) / 2
        radial = (hip - centre).xy
        worst_off = max(worst_off, abs(radial.length - radius))
        tangent = Vector((radial.y, -radial.x, 0)).normalized()
        last_angle = math.degrees(math.atan2(-radial.y, -radial.x))
        for side in hands:
            hands[side].append((world_head(obj, "mixamorig:%sHand" % side) - hip).dot(tangent))
            ball = world_head(obj, "mixamorig:%sToeBase" % side)
            if ball.z < 0.002 and side in before:
                worst_slide = max(worst_slide, (ball - before[side]).xy.length)
                planted_frames += 1
            before[side] = ball if ball.z < 0.002 else None
            if before[side] is None:
                del before[side]
    left, right = hands["Left"][30:], hands["Right"][30:]
    mean_l, mean_r = sum(left) / len(left), sum(right) / len(right)
    covariance = sum((a - mean_l) * (b - mean_r) for a, b in zip(left, right))
    spread = math.sqrt(sum((a - mean_l) ** 2 for a in left) * sum((b - mean_r) ** 2 for b in right))
    print("body on the curve: hips within %.1f mm of it, %.1f deg round; the hands swing %.0f mm, "
          "r %.2f between them; a planted ball slides at most %.2f mm a frame (%d frames)"
          % (worst_off * 1e3, last_angle, (max(left) - min(left)) * 1e3, covariance / spread,
             worst_slide * 1e3, planted_frames))
    check(worst_off < 0.05, "body: the hips left the curve by %.1f mm" % (worst_off * 1e3))
    check(last_angle > 45, "body: the walk went only %.1f deg round" % last_angle)
    swing = max(left) - min(left)
    check(swing > 0.15, "body: the left hand swings %.3f m" % swing)
    check(covariance / spread < -0.8, "body: the hands swing together (r %.2f)"
          % (covariance / spread))
    check(planted_frames > 40 and worst_slide < 0.003,
          "body: a planted ball slid %.2f mm a frame (%d frames planted)"
          % (worst_slide * 1e3, planted_frames))


CASES = {"straight": case_straight, "curve": case_curve, "rigs": case_rigs,
         "errors": case_errors, "panel": case_panel, "register": case_register,
         "body": case_body}
for name in args.cases or list(CASES):
    begin = time.monotonic()
    try:
        CASES[name]()
    except Exception:
        traceback.print_exc()
        failures.append("%s raised" % name)
    print("case %s: %.2f s" % (name, time.monotonic() - begin))
if failures:
    print("%d check(s) failed:\n  %s" % (len(failures), "\n  ".join(failures)))
    sys.exit(1)
print("all checks passed")
