# Scene pieces shared by the add-on's test (test_addon.py) and scripts/blender-picture.py.
import builtins

import bpy


def import_bvh(filepath, scale):
    """Blender's BVH importer on filepath (units times scale); the new armature object."""
    # Debian 12's Blender 3.4 opens BVH files with mode 'rU', which Python 3.11 rejects.
    original = builtins.open
    builtins.open = lambda f, mode="r", *a, **k: original(f, mode.replace("U", ""), *a, **k)
    try:
        bpy.ops.import_anim.bvh(filepath=filepath, global_scale=scale)
    finally:
        builtins.open = original
    return bpy.context.active_object


def quarter_circle(radius, name="quarter"):
    """A Bezier quarter circle from the origin heading -Y, turning left (towards +X) about
    (radius, 0, 0): a curve object in the scene."""
    data = bpy.data.curves.new(name, "CURVE")
    data.dimensions = "3D"
    spline = data.splines.new("BEZIER")
    spline.bezier_points.add(1)
    k = 0.5522847498 * radius  # the handles of a circle's quarter
    a, b = spline.bezier_points
    a.co, a.handle_left, a.handle_right = (0, 0, 0), (0, k, 0), (0, -k, 0)
    b.co, b.handle_left, b.handle_right = (radius, -radius, 0), (radius - k, -radius, 0), \
        (radius + k, -radius, 0)
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    return obj
