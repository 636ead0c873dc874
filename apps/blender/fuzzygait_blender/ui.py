# The add-on's face in Blender: the walk's settings (on the scene, edited in the sidebar panel),
# the operator that walks the active armature, one that fills in the bone map, and the add-on's
# preferences (where the fuzzygait module is).
import os

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from . import rig
from . import walk

BUILTIN_SETS = ("default", "cautious", "energetic", "heavy")  # without the module: for the UI


def _set_names(self, context, edit_text):
    try:
        return list(walk.import_module(module_dirs(context)).ControllerSet.builtin_names())
    except walk.WalkError:
        return list(BUILTIN_SETS)


def walk_properties():
    return {
        "controllers": StringProperty(
            name="Controller set", default="default", search=_set_names,
            description="A built-in controller set (default, cautious, energetic, heavy)"),
        "controller_folder": StringProperty(
            name="Set folder", subtype="DIR_PATH", default="",
            description="A controller set's folder (manifest.json and FLL files); overrides "
                        "the built-in set when given"),
        "pace": EnumProperty(
            name="Pace", default="SPEED",
            items=(("SPEED", "Speed", "Walk at a speed: the set's stride relation picks the step"),
                   ("STEP", "Step length", "Walk with a step length at the set's cadence"))),
        "speed": FloatProperty(name="Speed (m/s)", default=1.3, soft_min=0.3, soft_max=2.5,
                               description="Walking speed, metres a second of the walker"),
        "step_length": FloatProperty(name="Step (m)", default=0.70, soft_min=0.3, soft_max=1.2,
                                     description="Step length, heel to heel, metres"),
        "stature": FloatProperty(
            name="Stature (m)", default=0.0, soft_min=0.0, soft_max=2.5,
            description="The character's height; 0 measures it from the leg bones (1.75 m when "
                        "that is implausible for the scene's units)"),
        "use_scene_range": BoolProperty(name="Scene frame range", default=True,
                                        description="Keyframe the scene's frame range"),
        "frame_start": IntProperty(name="Start", default=1),
        "frame_end": IntProperty(name="End", default=250),
        "path": EnumProperty(
            name="Path", default="STRAIGHT",
            items=(("STRAIGHT", "Straight", "Straight ahead, the way the feet point"),
                   ("CURVE", "Curve", "Along a curve object, from its start"))),
        "curve": StringProperty(
            name="Curve", default="",
            description="The curve object to follow; empty: a selected curve"),
        "pelvis_tilt": BoolProperty(
            name="Pelvic tilt", default=True,
            description="Tilt the pelvis as the walker does, the spine bone kept upright "
                        "(needs a spine bone)"),
        "whole_body": BoolProperty(
            name="Whole body", default=False,
            description="Pose every bone fuzzygait maps (CMU, Mixamo, VRM, ... names): arms, "
                        "pelvis and trunk from the set's upper body, feet locked while planted, "
                        "on the armature's own legs"),
    }


BONE_ROLES = [key for key, _, _ in rig.ROLES]


def bone_properties():
    return {key: StringProperty(name=words.capitalize(), default="",
                                description="The %s bone; empty: found by its name" % words)
            for key, words, _ in rig.ROLES}


class FUZZYGAIT_PG_settings(bpy.types.PropertyGroup):
    __annotations__ = {**walk_properties(), **bone_properties()}


class FUZZYGAIT_AP_preferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    __annotations__ = {
        "module_dir": StringProperty(
            name="fuzzygait module folder", subtype="DIR_PATH", default="",
            description="The folder holding fuzzygait*.so (build/python, or where cmake "
                        "--install put it) when Blender's Python does not find it"),
    }

    def draw(self, context):
        self.layout.prop(self, "module_dir")


def module_dirs(context):
    dirs = []
    addon = context.preferences.addons.get(__package__) if context else None
    if addon and addon.preferences and addon.preferences.module_dir:
        dirs.append(bpy.path.abspath(addon.preferences.module_dir))
    try:
        from . import _installed
        dirs.append(_installed.MODULE_DIR)
    except ImportError:
        pass
    if os.environ.get("FUZZYGAIT_PYTHONPATH"):
        dirs.extend(os.environ["FUZZYGAIT_PYTHONPATH"].split(os.pathsep))
    return dirs


class FUZZYGAIT_OT_walk_armature(bpy.types.Operator):
    """Walk the active armature with fuzzygait: keyframes for the chosen frames"""
    bl_idname = "fuzzygait.walk_armature"
    bl_label = "Walk armature"
    bl_options = {"REGISTER", "UNDO"}
    __annotations__ = {**walk_properties(), **bone_properties()}

    def execute(self, context):
        scene = context.scene
        start, end = self.frame_start, self.frame_end
        if self.use_scene_range:
            start, end = scene.frame_start, scene.frame_end
        obj = context.active_object
        curve = None
        if self.path == "CURVE":
            if self.curve:
                curve = bpy.data.objects.get(self.curve)
                if curve is None or curve.type != "CURVE":
                    self.report({"ERROR"}, "Walk armature: '%s' is not a curve object" % self.curve)
                    return {"CANCELLED"}
            else:
                curve = next((o for o in context.selected_objects if o.type == "CURVE"), None)
        folder = bpy.path.abspath(self.controller_folder) if self.controller_folder else ""
        settings = walk.Settings(
            controllers=self.controllers, controller_folder=folder, pace=self.pace,
            speed=self.speed, step_length=self.step_length, stature=self.stature,
            frame_start=start, frame_end=end, fps=scene.render.fps / scene.render.fps_base,
            path=self.path, curve=curve, pelvis_tilt=self.pelvis_tilt,
            whole_body=self.whole_body, bones={key: getattr(self, key) for key in BONE_ROLES})
        try:
            result = walk.walk_armature(obj, settings, context.evaluated_depsgraph_get(),
                                        scene.unit_settings.scale_length, module_dirs(context))
        except walk.WalkError as error:
            self.report({"ERROR"}, "Walk armature: %s" % error)
            return {"CANCELLED"}
        scene.frame_set(scene.frame_current)
        message = ("Walked '%s' %.2f m in %d frames as %.2f m tall (%.4g units a metre)"
                   % (obj.name, result.travel, result.frames, result.stature, result.scale))
        if result.past_curve_end:
            message += "; past the curve's end it went straight on"
        self.report({"INFO"}, message)
        return {"FINISHED"}


class FUZZYGAIT_OT_map_bones(bpy.types.Operator):
    """Fill the bone map with the active armature's bones found by their names"""
    bl_idname = "fuzzygait.map_bones"
    bl_label = "Find bones"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        obj = context.active_object
        if obj is None or obj.type != "ARMATURE":
            self.report({"ERROR"}, "Find bones: no armature is active")
            return {"CANCELLED"}
        settings = context.scene.fuzzygait
        found = rig.auto_map(obj.data.bones)
        for key in BONE_ROLES:
            setattr(settings, key, found[key])
        missing = [rig.ROLE_WORDS[k] for k, _, required in rig.ROLES if required and not found[k]]
        if missing:
            self.report({"WARNING"}, "Find bones: not found: %s" % ", ".join(missing))
        return {"FINISHED"}


class FUZZYGAIT_PT_walk(bpy.types.Panel):
    bl_label = "fuzzygait walk"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "fuzzygait"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.fuzzygait
        obj = context.active_object
        armature = obj if obj is not None and obj.type == "ARMATURE" else None
        if armature is None:
            layout.label(text="Select an armature", icon="ERROR")

        col = layout.column(align=True)
        col.prop(settings, "controllers")
        col.prop(settings, "controller_folder")
        layout.prop(settings, "pace", expand=True)
        layout.prop(settings, "speed" if settings.pace == "SPEED" else "step_length")
        layout.prop(settings, "stature")
        layout.prop(settings, "use_scene_range")
        if not settings.use_scene_range:
            row = layout.row(align=True)
            row.prop(settings, "frame_start")
            row.prop(settings, "frame_end")
        layout.prop(settings, "path", expand=True)
        if settings.path == "CURVE":
            layout.prop_search(settings, "curve", bpy.data, "objects")
        layout.prop(settings, "pelvis_tilt")
        layout.prop(settings, "whole_body")

        box = layout.box()
        row = box.row()
        row.label(text="Bones (empty: by name)")
        row.operator(FUZZYGAIT_OT_map_bones.bl_idname, text="", icon="VIEWZOOM")
        for key, _, _ in rig.ROLES:
            if armature is not None:
                box.prop_search(settings, key, armature.data, "bones")
            else:
                box.prop(settings, key)

        op = layout.operator(FUZZYGAIT_OT_walk_armature.bl_idname, icon="ARMATURE_DATA")
        for key in list(walk_properties()) + BONE_ROLES:
            setattr(op, key, getattr(settings, key))


CLASSES = (FUZZYGAIT_PG_settings, FUZZYGAIT_AP_preferences, FUZZYGAIT_OT_walk_armature,
           FUZZYGAIT_OT_map_bones, FUZZYGAIT_PT_walk)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.fuzzygait = bpy.props.PointerProperty(type=FUZZYGAIT_PG_settings)


def unregister():
    del bpy.types.Scene.fuzzygait
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
