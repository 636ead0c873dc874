# Imports a binary glTF file of a posed skeleton (io::write_skeleton_gltf) with Blender's own glTF
# importer, checks what it made (one armature with a bone per skin joint, an action, the mesh
# Body skinned to the armature), and writes per frame every bone's head in world space, metres,
# in glTF's axes and the columns of tests/js/gltf_positions.mjs (frame, time, then NAME_x,
# NAME_y, NAME_z per joint in skin order), so one C++ test compares both with the skeleton's
# forward kinematics.
#
#   blender -b --factory-startup --python-exit-code 1 --python gltf_positions.py -- IN.glb OUT.csv
#
# Exits 3 when Blender's Python has no numpy (its glTF importer needs it; Debian: python3-numpy).
# The scene takes the file's frame rate (from its first two key times) before importing, as the
# importer keys time x the scene's fps: frame i is key i. Blender's Z up is glTF's Y and its -Y
# glTF's Z: a position (X, Y, Z) in Blender is (X, Z, -Y) in glTF. Debian 12's Blender 3.4
# imports with import_shading="SMOOTH" (its default breaks on Debian's numpy 1.24).
import json
import struct
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(argv) != 2:
    print("usage: blender -b --python gltf_positions.py -- IN.glb OUT.csv", file=sys.stderr)
    sys.exit(2)
glb_path, csv_path = argv

try:
    import numpy  # noqa: F401  (the importer's dependency)
except ImportError:
    print("Blender's Python has no numpy, which its glTF importer needs", file=sys.stderr)
    sys.exit(3)

# The file's joint names (skin order) and key times, from its JSON and binary chunks.
with open(glb_path, "rb") as f:
    glb = f.read()
json_length = struct.unpack_from("<I", glb, 12)[0]
document = json.loads(glb[20:20 + json_length])
binary = glb[20 + json_length + 8:]
names = [document["nodes"][n]["name"] for n in document["skins"][0]["joints"]]
walk = [a for a in document["animations"] if a["name"] == "Walk"]
if len(walk) != 1:
    sys.exit("%s has no animation Walk" % glb_path)
times_accessor = document["accessors"][walk[0]["samplers"][0]["input"]]
view = document["bufferViews"][times_accessor["bufferView"]]
times = struct.unpack_from("<%df" % times_accessor["count"], binary,
                           view.get("byteOffset", 0) + times_accessor.get("byteOffset", 0))
fps = round(1.0 / (times[1] - times[0])) if len(times) > 1 else 24

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = fps
scene.render.fps_base = 1.0
result = bpy.ops.import_scene.gltf(filepath=glb_path, import_shading="SMOOTH")
if result != {"FINISHED"}:
    sys.exit("Blender could not import %s: %s" % (glb_path, result))

armatures = [o for o in scene.objects if o.type == "ARMATURE"]
if len(armatures) != 1:
    sys.exit("expected one armature, found %s" % [o.name for o in armatures])
armature = armatures[0]
bones = sorted(b.name for b in armature.data.bones)
if bones != sorted(names):
    sys.exit("the armature's bones are %s, the skin's joints %s" % (bones, sorted(names)))
meshes = [o for o in scene.objects if o.type == "MESH"]
if [o.name for o in meshes] != ["Body"]:
    sys.exit("expected the mesh Body, found %s" % [o.name for o in meshes])
if not any(m.type == "ARMATURE" and m.object == armature for m in meshes[0].modifiers):
    sys.exit("Body is not skinned to the armature")
action = armature.animation_data.action if armature.animation_data else None
if action is None:
    sys.exit("the armature has no action")
first, last = action.frame_range
print("imported: armature %s with %d bones, action %s with %d curves over frames %g..%g at %d fps"
      % (armature.name, len(bones), action.name, len(action.fcurves), first, last, fps))

header = ["frame", "time"]
for name in names:
    header += ["%s_%s" % (name, a) for a in "xyz"]
lines = [",".join(header)]
world = armature.matrix_world
pose = armature.pose.bones
for frame in range(len(times)):
    scene.frame_set(frame)
    row = [str(frame), "%.6f" % times[frame]]
    for name in names:
        v = world @ pose[name].head
        row += ["%.7f" % c for c in (v.x, v.z, -v.y)]
    lines.append(",".join(row))

with open(csv_path, "w") as out:
    out.write("\n".join(lines) + "\n")
print("gltf_positions.py: wrote %d frames to %s" % (len(times), csv_path))
