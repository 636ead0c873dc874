# fuzzygait's Blender add-on: walks the active armature with fuzzygait's fuzzy controllers,
# straight ahead or along a curve, and keyframes its pelvis and legs. MIT licence, as fuzzygait.
# It needs the fuzzygait Python module (built for the Python Blender runs; docs/blender.md).
bl_info = {
    "name": "fuzzygait walk",
    "author": "fuzzygait contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View > Sidebar > fuzzygait",
    "description": "Walk an armature with fuzzy controllers, straight or along a curve",
    "category": "Animation",
}

if "bpy" in locals():  # a reload (F8, or the add-on disabled and enabled again)
    import importlib
    from . import rig, path, walk, ui
    for _module in (rig, path, walk, ui):
        importlib.reload(_module)
else:
    import bpy  # noqa: F401
    from . import ui


def register():
    ui.register()


def unregister():
    ui.unregister()
