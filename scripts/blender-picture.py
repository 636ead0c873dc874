# Draws docs/blender.png: the project's BVH skeleton walked by the add-on along a quarter circle,
# sticks on the bones copied at four frames into one picture, rendered by Cycles on the CPU (30 s).
#
#   build/fuzzygait walk -o out/walk
#   blender -b --factory-startup --python scripts/blender-picture.py -- \
#       build/python apps/blender out/walk.bvh docs/blender.png
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector

module_dir, addon_dir, bvh, out = sys.argv[sys.argv.index("--") + 1:]
sys.dont_write_bytecode = True
sys.path[:0] = [module_dir, addon_dir,
                os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "blender")]
import fuzzygait_blender  # noqa: E402
import scenes  # noqa: E402 (tests/blender/scenes.py)

bpy.ops.wm.read_factory_settings(use_empty=True)
fuzzygait_blender.register()
scene = bpy.context.scene
scene.render.fps, scene.frame_start, scene.frame_end = 30, 1, 120

rig = scenes.import_bvh(bvh, 0.01)
rig.animation_data_clear()
rig.location.z = -min((rig.matrix_world @ b.tail_local).z for b in rig.data.bones)

path = scenes.quarter_circle(4.0, "path")
path.data.bevel_depth = 0.01
bpy.context.view_layer.objects.active = rig
bpy.ops.fuzzygait.walk_armature(speed=1.3, path="CURVE", curve=path.name)


def material(name, colour):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*colour, 1)
    return m


bone_material = material("bone", (0.8, 0.35, 0.1))


def stick(bone, a, b, radius=0.02):
    """A cylinder from a to b (armature space at rest) that moves with the bone."""
    bpy.ops.mesh.primitive_cylinder_add(radius=radius, depth=(b - a).length, vertices=12)
    obj = bpy.context.active_object
    to_bone = bone.matrix_local.inverted()
    a, b = to_bone @ a, to_bone @ b
    turn = (b - a).to_track_quat("Z", "Y").to_matrix().to_4x4()
    obj.data.transform(Matrix.Translation((a + b) / 2) @ turn)
    obj.data.materials.append(bone_material)
    obj.parent, obj.parent_type, obj.parent_bone = rig, "BONE", bone.name
    obj.matrix_parent_inverse = Matrix.Translation((0, -bone.length, 0))
    obj.matrix_basis = Matrix()


bones = rig.data.bones
for bone in bones:
    if bone.name not in ("Hips", "Head"):
        stick(bone, bone.head_local, bone.tail_local)
stick(bones["Head"], bones["Head"].head_local, bones["Head"].tail_local, radius=0.07)
stick(bones["Hips"], bones["LeftUpLeg"].head_local, bones["RightUpLeg"].head_local)
stick(bones["Hips"], bones["Hips"].head_local, bones["Spine"].head_local)
path.data.materials.append(material("path", (0.1, 0.3, 0.8)))
bpy.ops.mesh.primitive_plane_add(size=20, location=(2, -2, 0))
bpy.context.active_object.data.materials.append(material("ground", (0.7, 0.7, 0.7)))

camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
scene.collection.objects.link(camera)
camera.location = (-1.6, -7.4, 2.2)
target = Vector((1.9, -2.4, 0.7))
camera.rotation_euler = (target - camera.location).to_track_quat("-Z", "Y").to_euler()
camera.data.lens = 32
scene.camera = camera
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
sun.data.energy = 3
sun.rotation_euler = (math.radians(40), 0, math.radians(-30))
scene.collection.objects.link(sun)
world = bpy.data.worlds.new("world")
world.color = (0.8, 0.85, 0.9)
scene.world = world

scene.render.engine = "CYCLES"
scene.cycles.samples, scene.cycles.device, scene.cycles.use_denoising = 96, "CPU", False
scene.cycles.max_bounces = 2  # little noise without a denoiser (Debian's has none)
scene.render.resolution_x, scene.render.resolution_y = 720, 360
# The sticks at four frames, copied where they stand, all in one picture.
sticks = [o for o in scene.objects if o.parent is rig]
for frame in (1, 40, 80, 120):
    scene.frame_set(frame)
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
