# Draws docs/body_path.png: `fuzzygait walk --path`'s whole body (PREFIX.body.bvh) walking its
# path, sticks on the bones copied at evenly spaced frames into one picture, the hips' track on the
# ground, rendered by Cycles on the CPU (about a minute).
#
#   printf 'x,z\n0,0\n0,3\n3,3\n3,6\n' > out/s.csv
#   build/fuzzygait walk --path out/s.csv --speed 1.3 --fps 30 -o out/s
#   blender -b --factory-startup --python scripts/body-picture.py -- out/s.body.bvh docs/body_path.png
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector

bvh, out = sys.argv[sys.argv.index("--") + 1:]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "blender"))
import scenes  # noqa: E402 (tests/blender/scenes.py)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
rig = scenes.import_bvh(bvh, 1.0)  # the file is in metres
frame_range = rig.animation_data.action.frame_range
scene.frame_start, scene.frame_end = int(frame_range[0]), int(frame_range[1])
first, last = int(scene.frame_start), int(scene.frame_end)


def material(name, colour):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*colour, 1)
    return m


colours = {"arm": material("arms", (0.15, 0.45, 0.85)), "leg": material("legs", (0.8, 0.35, 0.1)),
           "trunk": material("trunk", (0.3, 0.3, 0.3))}


def stick(bone, a, b, radius, kind):
    """A cylinder from a to b (armature space at rest) that moves with the bone."""
    bpy.ops.mesh.primitive_cylinder_add(radius=radius, depth=max((b - a).length, 1e-3),
                                        vertices=12)
    obj = bpy.context.active_object
    to_bone = bone.matrix_local.inverted()
    a, b = to_bone @ a, to_bone @ b
    turn = (b - a).to_track_quat("Z", "Y").to_matrix().to_4x4()
    obj.data.transform(Matrix.Translation((a + b) / 2) @ turn)
    obj.data.materials.append(colours[kind])
    obj.parent, obj.parent_type, obj.parent_bone = rig, "BONE", bone.name
    obj.matrix_parent_inverse = Matrix.Translation((0, -bone.length, 0))
    obj.matrix_basis = Matrix()


bones = rig.data.bones
for bone in bones:
    name = bone.name.lower()
    kind = "arm" if ("arm" in name or "hand" in name or "shoulder" in name) else \
        "leg" if ("leg" in name or "foot" in name or "toe" in name) else "trunk"
    radius = 0.06 if name == "head" else 0.018
    if name != "hips":
        stick(bone, bone.head_local, bone.tail_local, radius, kind)
stick(bones["hips"], bones["leftUpperLeg"].head_local, bones["rightUpperLeg"].head_local, 0.018,
      "trunk")
stick(bones["hips"], bones["hips"].head_local, bones["spine"].head_local, 0.018, "trunk")

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
curve.materials.append(material("track", (0.1, 0.6, 0.3)))
low = Vector((min(p.x for p in track), min(p.y for p in track), 0))
high = Vector((max(p.x for p in track), max(p.y for p in track), 0))
middle = (low + high) / 2
bpy.ops.mesh.primitive_plane_add(size=2 * max((high - low).length, 4), location=middle)
bpy.context.active_object.data.materials.append(material("ground", (0.75, 0.75, 0.75)))

camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
scene.collection.objects.link(camera)
span = max((high - low).length, 3.0)
camera.location = middle + Vector((0.55 * span, -1.05 * span, 0.75 * span))
target = middle + Vector((0, 0, 0.6))
camera.rotation_euler = (target - camera.location).to_track_quat("-Z", "Y").to_euler()
camera.data.lens = 35
scene.camera = camera
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
sun.data.energy = 3
sun.rotation_euler = (math.radians(35), 0, math.radians(-25))
scene.collection.objects.link(sun)
world = bpy.data.worlds.new("world")
world.color = (0.8, 0.85, 0.9)
scene.world = world

scene.render.engine = "CYCLES"
scene.cycles.samples, scene.cycles.device, scene.cycles.use_denoising = 64, "CPU", False
scene.cycles.max_bounces = 2
scene.render.resolution_x, scene.render.resolution_y = 960, 540
sticks = [o for o in scene.objects if o.parent is rig]
count = 9
for k in range(count):
    scene.frame_set(first + round(k * (last - first) / (count - 1)))
    for piece in sticks:
        copy = piece.copy()
        scene.collection.objects.link(copy)
        copy.parent = None
        copy.matrix_world = piece.matrix_world.copy()
for piece in sticks:
    piece.hide_render = True
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.compression = 100
scene.render.filepath = os.path.abspath(out)
bpy.ops.render.render(write_still=True)
print("wrote", out)
