# Draws docs/blender.png: the project's BVH skeleton walked by the add-on along a quarter circle,
# sticks on the bones copied at four frames into one picture, rendered by Cycles on the CPU (30 s).
#
#   build/fuzzygait walk -o out/walk
#   blender -b --factory-startup --python scripts/blender-picture.py -- \
#       build/python apps/blender out/walk.bvh docs/blender.png
import os
import sys

import bpy

module_dir, addon_dir, bvh, out = sys.argv[sys.argv.index("--") + 1:]
sys.dont_write_bytecode = True
here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [module_dir, addon_dir, here, os.path.join(here, "..", "tests", "blender")]
import fuzzygait_blender  # noqa: E402
import scenes  # noqa: E402 (tests/blender/scenes.py)
import stick_picture as picture  # noqa: E402 (scripts/stick_picture.py)

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


bone_material = picture.material("bone", (0.8, 0.35, 0.1))
bones = rig.data.bones
for bone in bones:
    if bone.name not in ("Hips", "Head"):
        picture.stick(rig, bone, bone.head_local, bone.tail_local, 0.02, bone_material)
picture.stick(rig, bones["Head"], bones["Head"].head_local, bones["Head"].tail_local, 0.07,
              bone_material)
picture.stick(rig, bones["Hips"], bones["LeftUpLeg"].head_local, bones["RightUpLeg"].head_local,
              0.02, bone_material)
picture.stick(rig, bones["Hips"], bones["Hips"].head_local, bones["Spine"].head_local, 0.02,
              bone_material)
path.data.materials.append(picture.material("path", (0.1, 0.3, 0.8)))
bpy.ops.mesh.primitive_plane_add(size=20, location=(2, -2, 0))
bpy.context.active_object.data.materials.append(picture.material("ground", (0.7, 0.7, 0.7)))
picture.stage(scene, (-1.6, -7.4, 2.2), (1.9, -2.4, 0.7), 32, -30)
# The sticks at four frames, copied where they stand, all in one picture.
picture.render_sticks_at(scene, rig, (1, 40, 80, 120), out, 96, 720, 360)
