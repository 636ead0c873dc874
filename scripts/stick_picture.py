# What scripts/blender-picture.py and scripts/body-picture.py share: an armature drawn as sticks
# on its bones, copied at chosen frames into one picture, lit and rendered by Cycles on the CPU.
import math
import os

import bpy
from mathutils import Matrix, Vector


def material(name, colour):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*colour, 1)
    return m


def stick(rig, bone, a, b, radius, colour):
    """A cylinder from a to b (armature space at rest) that moves with the bone."""
    bpy.ops.mesh.primitive_cylinder_add(radius=radius, depth=max((b - a).length, 1e-3),
                                        vertices=12)
    obj = bpy.context.active_object
    to_bone = bone.matrix_local.inverted()
    a, b = to_bone @ a, to_bone @ b
    turn = (b - a).to_track_quat("Z", "Y").to_matrix().to_4x4()
    obj.data.transform(Matrix.Translation((a + b) / 2) @ turn)
    obj.data.materials.append(colour)
    obj.parent, obj.parent_type, obj.parent_bone = rig, "BONE", bone.name
    obj.matrix_parent_inverse = Matrix.Translation((0, -bone.length, 0))
    obj.matrix_basis = Matrix()


def stage(scene, camera_at, look_at, lens, sun_turn_deg):
    """A camera at camera_at looking at look_at, a sun turned about Z, a pale sky."""
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    camera.location = camera_at
    camera.rotation_euler = (Vector(look_at) - camera.location).to_track_quat("-Z", "Y").to_euler()
    camera.data.lens = lens
    scene.camera = camera
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 3
    sun.rotation_euler = (math.radians(40), 0, math.radians(sun_turn_deg))
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("world")
    world.color = (0.8, 0.85, 0.9)
    scene.world = world


def render_sticks_at(scene, rig, frames, out, samples, width, height):
    """The sticks on rig's bones copied where they stand at each frame, rendered into out."""
    scene.render.engine = "CYCLES"
    scene.cycles.samples, scene.cycles.device, scene.cycles.use_denoising = samples, "CPU", False
    scene.cycles.max_bounces = 2  # little noise without a denoiser (Debian's has none)
    scene.render.resolution_x, scene.render.resolution_y = width, height
    sticks = [o for o in scene.objects if o.parent is rig]
    for frame in frames:
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
