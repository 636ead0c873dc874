# Imports a binary glTF file with Blender's own glTF importer, checks what it made (one armature
# "Armature" with the walk's 15 bones, one action with the root's location and the 12 joints'
# rotations, the meshes Body, skinned to the armature, and Ground), and writes per frame what
# Blender shows, in the columns of tests/js/gltf_angles.mjs: the sagittal angles (degrees,
# fuzzygait's clinical signs), the joints' world positions and the skinned body's lowest and
# highest points (metres, glTF's axes), so one C++ test compares it with the walk's CSV.
#
#   blender -b --factory-startup --python-exit-code 1 --python gltf_import.py -- IN.glb OUT.csv FPS
#
# Exits 3 when Blender's Python has no numpy (its glTF importer needs it; Debian: python3-numpy).
# Debian 12's Blender 3.4 imports with import_shading="SMOOTH": its default ("NORMALS") breaks
# on Debian's numpy 1.24.
# The importer keys the action at time x the scene's fps, so the scene takes the walk's fps first
# and frame i is the walk's frame i. Blender's Z up is glTF's Y and its -Y glTF's Z: a glTF
# position (X, Y, Z) is Blender's (X, -Z, Y).
# Angles come from the joints' positions, each bone's vector to its child against the same
# vector at rest, so they do not depend on how the importer orients its bones: a bone's rotation
# about X is the angle from its rest vector to its posed one in the (Y up, Z forward) plane.
import math
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(argv) != 3:
    print("usage: blender -b --python gltf_import.py -- IN.glb OUT.csv FPS", file=sys.stderr)
    sys.exit(2)
glb_path, csv_path, fps = argv[0], argv[1], int(argv[2])

try:
    import numpy  # noqa: F401  (the importer's dependency)
except ImportError:
    print("Blender's Python has no numpy, which its glTF importer needs", file=sys.stderr)
    sys.exit(3)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = fps
scene.render.fps_base = 1.0
result = bpy.ops.import_scene.gltf(filepath=glb_path, import_shading="SMOOTH")
if result != {"FINISHED"}:
    sys.exit("Blender could not import %s: %s" % (glb_path, result))

SIDES = (("l", "Left"), ("r", "Right"))
BONES = ["Hips"]
for _, side in SIDES:
    BONES += [side + n for n in ("UpLeg", "Leg", "Foot", "ToeBase", "Toe_End")]
BONES += ["Spine", "Neck", "Head", "HeadTop_End"]

armatures = [o for o in scene.objects if o.type == "ARMATURE"]
if [o.name for o in armatures] != ["Armature"]:
    sys.exit("expected one armature named Armature, found %s" % [o.name for o in armatures])
armature = armatures[0]
if sorted(b.name for b in armature.data.bones) != sorted(BONES):
    sys.exit("the armature's bones are %s" % [b.name for b in armature.data.bones])
meshes = sorted(o.name for o in scene.objects if o.type == "MESH")
if meshes != ["Body", "Ground"]:
    sys.exit("expected the meshes Body and Ground, found %s" % meshes)
body = scene.objects["Body"]
skinning = [m for m in body.modifiers if m.type == "ARMATURE" and m.object == armature]
if len(skinning) != 1:
    sys.exit("Body is not skinned to the armature (modifiers %s)" % list(body.modifiers))
unknown = {g.name for g in body.vertex_groups} - set(BONES)
if unknown:
    sys.exit("Body has vertex groups of no bone: %s" % sorted(unknown))
if scene.objects["Ground"].parent == armature:
    sys.exit("Ground was put under the armature")

action = armature.animation_data.action if armature.animation_data else None
if action is None:
    sys.exit("the armature has no action")
paths = {}
for curve in action.fcurves:
    paths.setdefault(curve.data_path, 0)
    paths[curve.data_path] += 1
expected_paths = {'pose.bones["Hips"].location': 3}
for name in BONES:
    if not name.endswith("_End"):
        expected_paths['pose.bones["%s"].rotation_quaternion' % name] = 4
if paths != expected_paths:
    sys.exit("the action animates %s" % sorted(paths.items()))
first, last = action.frame_range
if abs(first) > 1e-3:
    sys.exit("the action starts at frame %s, not 0" % first)
frames = round(last) + 1
print("imported: armature with %d bones, action %s with %d curves over frames %g..%g, meshes %s"
      % (len(armature.data.bones), action.name, len(action.fcurves), first, last, meshes))


def gltf_axes(v):
    return (v.x, v.z, -v.y)


rest = {name: armature.data.bones[name].head_local for name in BONES}


def rotation(parent, child, posed):
    """The (parent -> child) vector's turn about X from rest to posed, radians."""
    y0, z0 = gltf_axes(rest[child] - rest[parent])[1:]
    y1, z1 = gltf_axes(posed[child] - posed[parent])[1:]
    return math.atan2(y0 * z1 - z0 * y1, y0 * y1 + z0 * z1)


def wrap(radians):
    return math.atan2(math.sin(radians), math.cos(radians))


header = ["frame", "time", "pelvis_x", "pelvis_y", "pelvis_z", "pelvis_tilt"]
for s, _ in SIDES:
    header += ["%s_%s" % (s, a) for a in ("thigh", "hip", "knee", "ankle", "toe")]
for s, _ in SIDES:
    for j in ("hip", "knee", "ankle", "ball", "tip"):
        header += ["%s_%s_%s" % (s, j, c) for c in "xyz"]
for j in ("spine", "neck", "head", "head_top"):
    header += ["%s_%s" % (j, c) for c in "xyz"]
header += ["body_lowest_y", "body_highest_y"]
rows = [",".join(header)]

world = armature.matrix_world
depsgraph = bpy.context.evaluated_depsgraph_get()
for frame in range(frames):
    scene.frame_set(frame)
    posed = {name: armature.pose.bones[name].head.copy() for name in BONES}
    # A bone's sagittal angle (forward or toes-up positive) is minus its turn about X.
    tilt = rotation("Hips", "Spine", posed)
    row = [str(frame), "%.6f" % (frame / fps)]
    row += ["%.6f" % v for v in gltf_axes(world @ posed["Hips"])]
    row.append("%.6f" % math.degrees(tilt))
    points = []
    for _, side in SIDES:
        up_leg, leg, foot, toes, tip = (side + n for n in
                                        ("UpLeg", "Leg", "Foot", "ToeBase", "Toe_End"))
        thigh = -rotation(up_leg, leg, posed)
        shank = -rotation(leg, foot, posed)
        foot_pitch = -rotation(foot, toes, posed)
        toes_pitch = -rotation(toes, tip, posed)
        row += ["%.6f" % math.degrees(a) for a in
                (thigh, wrap(thigh + tilt), wrap(thigh - shank), wrap(foot_pitch - shank),
                 wrap(toes_pitch - foot_pitch))]
        for name in (up_leg, leg, foot, toes, tip):
            points += ["%.6f" % v for v in gltf_axes(world @ posed[name])]
    for name in ("Spine", "Neck", "Head", "HeadTop_End"):
        points += ["%.6f" % v for v in gltf_axes(world @ posed[name])]
    row += points
    evaluated = body.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    heights = [(evaluated.matrix_world @ v.co).z for v in mesh.vertices]
    evaluated.to_mesh_clear()
    row += ["%.6f" % min(heights), "%.6f" % max(heights)]
    rows.append(",".join(row))

with open(csv_path, "w") as out:
    out.write("\n".join(rows) + "\n")
