# What the Blender checks of BVH files share (bvh_angles.py, bvh_positions.py): the command line
# "blender -b --python SCRIPT -- IN.bvh OUT.csv" and the import of IN with Blender's own importer.
import builtins
import sys

import bpy


def import_bvh(usage):
    """Imports the BVH file named after '--' and returns (its armature object, the CSV path)."""
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 2:
        print(usage, file=sys.stderr)
        sys.exit(2)
    bvh_path, csv_path = argv
    # Debian 12's Blender 3.4 opens BVH files with mode 'rU', which Python 3.11 rejects.
    plain_open = builtins.open

    def open_without_u(file, mode="r", *args, **kwargs):
        return plain_open(file, mode.replace("U", ""), *args, **kwargs)

    builtins.open = open_without_u
    try:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        result = bpy.ops.import_anim.bvh(filepath=bvh_path, update_scene_fps=True,
                                         update_scene_duration=True)
    finally:
        builtins.open = plain_open
    if result != {"FINISHED"}:
        sys.exit("Blender could not import %s: %s" % (bvh_path, result))
    armature = next(o for o in bpy.context.scene.objects if o.type == "ARMATURE")
    return armature, csv_path
