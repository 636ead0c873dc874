#!/usr/bin/python3
"""The whole body along a path from Python: a game's skeleton (a BVH file's, or CMU's 07_01 by
default) walked round an S of two rounded right angles, its joints in the world and the skeleton's
local rotations every frame, written as NumPy arrays.

    PYTHONPATH=build/python python3 examples/walk_a_path.py [SKELETON.bvh|.glb|.vrm] [OUT.npz]

Writes OUT.npz (default out/python_path.npz): `positions` (frames, 26, 3) and `rotations` (frames,
26, 4) of the body's joints (fuzzygait.JOINTS), `local` (frames, joints, 4) and `root` (frames, 3)
of the skeleton, and prints where a few joints are.
"""
import pathlib
import sys

import numpy as np

import fuzzygait as fg

here = pathlib.Path(__file__).resolve().parent
skeleton_file = sys.argv[1] if len(sys.argv) > 1 else here.parent / "data/mocap/cmu/07_01.bvh"
out = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else "out/python_path.npz")
out.parent.mkdir(parents=True, exist_ok=True)

skeleton = fg.Skeleton.read(skeleton_file)        # or fg.Skeleton(names, parents, offsets, ...)
poser = fg.SkeletonPoser(skeleton)                 # its joints found by their names
walker = fg.Walker(speed=1.2, segments=poser.humanoid.segments)   # on the skeleton's legs
route = fg.Path.polyline([[0, 0], [0, 3], [3, 3], [3, 6]], corner_radius=1.0)   # x, z metres
follower = fg.PathFollower(poser.humanoid, route, walker)

joint = fg.JOINTS.index
frames = {"positions": [], "rotations": [], "local": [], "root": []}
while walker.pelvis[0] < route.length and walker.time < 20:
    walker.advance(1 / 60)
    positions, rotations = follower.update()       # the body in the world
    local, root = poser.pose(positions, rotations)  # the skeleton's local rotations, its units
    for name, value in zip(frames, (positions, rotations, local, root)):
        frames[name].append(value)
    if len(frames["root"]) % 60 == 0:
        hips, hand = positions[joint("hips")], positions[joint("leftHand")]
        print(f"t={walker.time:5.2f} s  hips ({hips[0]:5.2f}, {hips[1]:4.2f}, {hips[2]:5.2f})  "
              f"left hand ({hand[0]:5.2f}, {hand[1]:4.2f}, {hand[2]:5.2f})  "
              f"{'left foot planted' if walker.in_contact[0] else ''}")
np.savez(out, **{name: np.array(values) for name, values in frames.items()})
end = route.at(route.length)
print(f"path end ({end['x']:.2f}, {end['z']:.2f}) reached after {walker.pelvis[0]:.2f} m: "
      f"{len(frames['root'])} frames of {len(skeleton)} joints in {out}")
