# Imports a BVH file with Blender's own importer and writes, per frame, every joint's world
# position in the BVH's units and axes, in the columns of tests/js/bvh_positions.mjs (frame, then
# NAME_x, NAME_y, NAME_z per joint), so one C++ test compares both with the skeleton's forward
# kinematics.
#
#   blender -b --factory-startup --python-exit-code 1 --python bvh_positions.py -- IN.bvh OUT.csv
#
# The importer's default orientation (forward -Z, up Y) turns the BVH's Y up into Blender's Z up:
# a position (x, y, z) in Blender is (x, z, -y) in the BVH.
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bvh_import import import_bvh  # noqa: E402 (after the path it lives on)

armature, csv_path = import_bvh("usage: blender -b --python bvh_positions.py -- IN.bvh OUT.csv")
scene = bpy.context.scene
world = armature.matrix_world
pose = armature.pose.bones
names = [b.name for b in armature.data.bones]  # the file's order


def position(point):
    v = world @ point
    return ["%.6f" % c for c in (v.x, v.z, -v.y)]


header = ["frame"]
for name in names:
    header += ["%s_%s" % (name, a) for a in "xyz"]
lines = [",".join(header)]
first, last = armature.animation_data.action.frame_range
frame_count = int(round(last - first)) + 1
for frame in range(frame_count):
    scene.frame_set(int(first) + frame)
    row = [str(frame)]
    for name in names:
        row += position(pose[name].head)
    lines.append(",".join(row))

with open(csv_path, "w") as out:
    out.write("\n".join(lines) + "\n")
print("bvh_positions.py: wrote %d frames to %s" % (frame_count, csv_path))
