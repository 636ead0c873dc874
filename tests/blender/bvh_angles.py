# Imports a BVH file with Blender's own importer and writes, per frame, what Blender shows: the
# sagittal angles (degrees, fuzzygait's clinical signs) and the joints' world positions, in the
# same CSV columns as tests/js/bvh_angles.mjs, so one C++ test compares both with the walk.
#
#   blender -b --factory-startup --python-exit-code 1 --python bvh_angles.py -- IN.bvh OUT.csv
#
# Positions are given back in the BVH's axes (X left, Y up, Z forward) from Blender's world
# axes as the importer's default orientation (forward -Z, up Y) maps them: a BVH character
# facing +Z faces -Y in Blender (its front view), so X = x, Y = z, Z = -y. If the importer put
# the character elsewhere, the positions would not match the walk.
# Angles come from each bone's head-to-tail direction, posed against rest, counter-clockwise in
# the (forward, up) plane: pelvis tilt = -angle(Hips), thigh = angle(UpLeg), and so on.
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bvh_import import import_bvh  # noqa: E402 (after the path it lives on)

armature, csv_path = import_bvh("usage: blender -b --python bvh_angles.py -- IN.bvh OUT.csv")
scene = bpy.context.scene
world = armature.matrix_world
pose = armature.pose.bones
rest = armature.data.bones


def bvh_axes(v):
    return (v.x, v.z, -v.y)


def direction_angle(head, tail):
    x, y, z = bvh_axes(world @ tail - world @ head)
    return math.atan2(y, z)


def sagittal(name):
    posed = direction_angle(pose[name].head, pose[name].tail)
    at_rest = direction_angle(rest[name].head_local, rest[name].tail_local)
    return posed - at_rest


def wrap(radians):
    return math.atan2(math.sin(radians), math.cos(radians))


def position(point):
    return ["%.6f" % v for v in bvh_axes(world @ point)]


sides = [("l", "Left"), ("r", "Right")]
header = ["frame", "time", "pelvis_x", "pelvis_y", "pelvis_z", "pelvis_tilt"]
for s, _ in sides:
    header += ["%s_%s" % (s, j) for j in ("thigh", "hip", "knee", "ankle", "toe")]
for s, _ in sides:
    for j in ("hip", "knee", "ankle", "ball", "tip"):
        header += ["%s_%s_%s" % (s, j, a) for a in "xyz"]

fps = scene.render.fps / scene.render.fps_base
lines = [",".join(header)]
# The action's keys, one per BVH frame (the scene's end frame is one past them).
first, last = armature.animation_data.action.frame_range
frame_count = int(round(last - first)) + 1
for frame in range(frame_count):
    scene.frame_set(int(first) + frame)
    pelvis = sagittal("Hips")
    row = [str(frame), "%.6f" % (frame / fps)] + position(pose["Hips"].head)
    row.append("%.6f" % math.degrees(-pelvis))
    points = []
    for _, name in sides:
        thigh = sagittal(name + "UpLeg")
        shank = sagittal(name + "Leg")
        foot = sagittal(name + "Foot")
        toes = sagittal(name + "ToeBase")
        row += ["%.6f" % math.degrees(a) for a in (
            thigh, wrap(thigh - pelvis), wrap(thigh - shank), wrap(foot - shank), wrap(toes - foot))]
        for joint in ("UpLeg", "Leg", "Foot", "ToeBase"):
            points += position(pose[name + joint].head)
        points += position(pose[name + "ToeBase"].tail)  # the End Site: the tip of the toes
    lines.append(",".join(row + points))

with open(csv_path, "w") as out:
    out.write("\n".join(lines) + "\n")
print("bvh_angles.py: wrote %d frames at %g fps to %s" % (frame_count, fps, csv_path))
