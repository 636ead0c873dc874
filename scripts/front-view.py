#!/usr/bin/env python3
"""front-view.py - the whole body seen from the front beside a person's, for the frontal plane.

usage: scripts/front-view.py BODY.bvh CLIP.bvh OUT.svg

Draws one left gait cycle of each (from a landing of the left foot to the next), eight moments,
as sticks seen from ahead of the walker (its left on the right of the picture, left limbs
orange, right ones blue), on the hips' centre's line at the cycle's start (grey): the pelvis's
roll and sway, the step width and the arms. BODY.bvh is `fuzzygait walk --path ... -o PREFIX`'s
PREFIX.body.bvh (VRM joint names), CLIP.bvh a CMU walk (data/mocap/cmu). numpy only.

  printf 'x,z\\n0,0\\n0,12\\n' > out/straight.csv
  build/fuzzygait walk --path out/straight.csv --speed 1.3 --fps 60 -o out/straight
  scripts/front-view.py out/straight.body.bvh data/mocap/cmu/07_01.bvh docs/body_front.svg
"""
import importlib.util
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("upper_body", os.path.join(HERE, "upper-body.py"))
upper_body = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(upper_body)

BODY = {"lhip": "leftUpperLeg", "rhip": "rightUpperLeg", "lknee": "leftLowerLeg",
        "rknee": "rightLowerLeg", "lfoot": "leftFoot", "rfoot": "rightFoot",
        "lsh": "leftUpperArm", "rsh": "rightUpperArm", "lelb": "leftLowerArm",
        "relb": "rightLowerArm", "lhand": "leftHand", "rhand": "rightHand", "neck": "neck"}
CMU = {"lhip": "LeftUpLeg", "rhip": "RightUpLeg", "lknee": "LeftLeg", "rknee": "RightLeg",
       "lfoot": "LeftFoot", "rfoot": "RightFoot", "lsh": "LeftArm", "rsh": "RightArm",
       "lelb": "LeftForeArm", "relb": "RightForeArm", "lhand": "LeftHand", "rhand": "RightHand",
       "neck": "Neck"}
BONES = [("lhip", "rhip"), ("lhip", "lknee"), ("lknee", "lfoot"), ("rhip", "rknee"),
         ("rknee", "rfoot"), ("lsh", "rsh"), ("lsh", "lelb"), ("lelb", "lhand"),
         ("rsh", "relb"), ("relb", "rhand"), ("mid", "neck")]
MOMENTS = 8
COLUMN = 110  # px a moment
LEG = 150  # px a leg length


def load(path, names):
    joints, frames, dt = upper_body.parse_bvh(path)
    if frames[0][3:].round().tolist() == frames[0][3:].tolist():  # a calibration T-pose first
        frames = frames[1:]
    p = upper_body.positions(joints, frames)
    listed = [j["name"] for j in joints]
    at = {k: p[:, listed.index(v)] for k, v in names.items()}
    at["mid"] = 0.5 * (at["lhip"] + at["rhip"])
    up = np.array([0.0, 1.0, 0.0])
    travel = at["mid"][-1] - at["mid"][0]
    travel[1] = 0.0
    forward = travel / np.linalg.norm(travel)
    left = np.cross(up, forward)
    # The left foot's landings: its forward speed falling below a third of its fastest.
    speed = np.gradient(at["lfoot"] @ forward) / dt
    moving = speed > speed.max() / 3
    landings = [i for i in range(1, len(speed)) if moving[i - 1] and not moving[i]]
    if len(landings) < 3:
        sys.exit("%s: fewer than three landings of the left foot" % path)
    a, b = landings[1], landings[2]
    feet = np.minimum(at["lfoot"] @ up, at["rfoot"] @ up)
    leg = np.median(at["mid"] @ up - feet)
    return at, up, left, a, b, leg, feet[a:b].min()


def draw(walk, x0, y0, label):
    at, up, left, a, b, leg, floor = walk
    out = ['<text x="%d" y="%d" font-size="16">%s</text>' % (x0, y0 - 10, label)]
    line = at["mid"][a] @ left
    for k in range(MOMENTS):
        i = int(a + (b - a) * k / MOMENTS)
        x = x0 + COLUMN * k + COLUMN // 2
        out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="#aaa" stroke-width="1"/>' %
                   (x, y0 + 10, x, y0 + 290))

        def point(name):
            q = at[name][i]
            return (x + LEG * (q @ left - line) / leg, y0 + 290 - LEG * (q @ up - floor) / leg)

        for s, e in BONES:
            (x1, y1), (x2, y2) = point(s), point(e)
            colour = ("#c05010" if s[0] == e[0] == "l" else
                      "#1060c0" if s[0] == e[0] == "r" else "#333")
            out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="%s" '
                       'stroke-width="3" stroke-linecap="round"/>' % (x1, y1, x2, y2, colour))
        out.append('<text x="%d" y="%d" font-size="12" text-anchor="middle">%d %%</text>' %
                   (x, y0 + 310, 100 * k / MOMENTS))
    return out


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    body, clip, out = sys.argv[1:]
    width = COLUMN * MOMENTS + 20
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="740" '
           'font-family="sans-serif"><rect width="100%%" height="100%%" fill="white"/>' % width]
    svg += draw(load(body, BODY), 10, 40, "fuzzygait: " + os.path.basename(body) +
                ", seen from ahead (left limbs orange), a left cycle from its landing")
    svg += draw(load(clip, CMU), 10, 400, "CMU " + os.path.basename(clip) + ", the same")
    svg.append("</svg>")
    with open(out, "w") as fh:
        fh.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
