# Draws docs/body_path.png: `fuzzygait walk --path`'s whole body (PREFIX.body.bvh) walking its
# path, sticks on the bones copied at evenly spaced frames into one picture, the hips' track on the
# ground, rendered by Cycles on the CPU (about a minute).
#
#   printf 'x,z\n0,0\n0,3\n3,3\n3,6\n' > out/s.csv
#   build/fuzzygait walk --path out/s.csv --speed 1.3 --fps 30 -o out/s
#   blender -b --factory-startup --python scripts/body-picture.py -- out/s.body.bvh docs/body_path.png
import os
import sys

import bpy
from mathutils import Vector

bvh, out = sys.argv[sys.argv.index("--") + 1:]
sys.dont_write_bytecode = True
here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(here, "..", "tests", "blender")]
import scenes  # noqa: E402 (tests/blender/scenes.py)
import stick_picture as picture  # noqa: E402 (scripts/stick_picture.py)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
rig = scenes.import_bvh(bvh, 1.0)  # the file is in metres
frame_range = rig.animation_data.action.frame_range
scene.frame_start, scene.frame_end = int(frame_range[0]), int(frame_range[1])
first, last = int(scene.frame_start), int(scene.frame_end)

colours = {"arm": picture.material("arms", (0.15, 0.45, 0.85)),
           "leg": picture.material("legs", (0.8, 0.35, 0.1)),
           "trunk": picture.material("trunk", (0.3, 0.3, 0.3))}

bones = rig.data.bones
for bone in bones:
    name = bone.name.lower()
    kind = "arm" if ("arm" in name or "hand" in name or "shoulder" in name) else \
        "leg" if ("leg" in name or "foot" in name or "toe" in name) else "trunk"
    radius = 0.06 if name == "head" else 0.018
    if name != "hips":
        picture.stick(rig, bone, bone.head_local, bone.tail_local, radius, colours[kind])
picture.stick(rig, bones["hips"], bones["leftUpperLeg"].head_local,
              bones["rightUpperLeg"].head_local, 0.018, colours["trunk"])
picture.stick(rig, bones["hips"], bones["hips"].head_local, bones["spine"].head_local, 0.018,
              colours["trunk"])

# The hips' track on the ground.
track = []
for frame in range(first, last + 1):
    scene.frame_set(frame)
    hips = rig.matrix_world @ rig.pose.bones["hips"].head
    track.append(Vector((hips.x, hips.y, 0.003)))
curve = bpy.data.curves.new("track", "CURVE")
curve.dimensions = "3D"
spline = curve.splines.new("POLY")
spline.points.add(len(track) - 1)
for p, q in zip(spline.points, track):
    p.co = (*q, 1)
curve.bevel_depth = 0.008
track_object = bpy.data.objects.new("track", curve)
scene.collection.objects.link(track_object)
curve.materials.append(picture.material("track", (0.1, 0.6, 0.3)))
low = Vector((min(p.x for p in track), min(p.y for p in track), 0))
high = Vector((max(p.x for p in track), max(p.y for p in track), 0))
middle = (low + high) / 2
bpy.ops.mesh.primitive_plane_add(size=2 * max((high - low).length, 4), location=middle)
bpy.context.active_object.data.materials.append(picture.material("ground", (0.75, 0.75, 0.75)))

# Seen from the side of the track's long axis, so the frames stand apart.
span = max((high - low).length, 3.0)
along = (high - low).normalized()
side = Vector((along.y, -along.x, 0))
if side.y > 0:
    side = -side
picture.stage(scene, middle + 1.05 * span * side + Vector((0, 0, 0.55 * span)),
              middle + Vector((0, 0, 0.5)), 30, -25)
count = 9
picture.render_sticks_at(scene, rig,
                         [first + round(k * (last - first) / (count - 1)) for k in range(count)],
                         out, 64, 960, 540)
