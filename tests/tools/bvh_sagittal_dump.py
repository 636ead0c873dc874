#!/usr/bin/env python3
"""Runs the reference extractor (bvh_sagittal.py, beside this file) on a clip and prints at full
precision what tests/io/mocap_test.cpp compares, one record a line:
  skip S scale M            frames dropped, metres per unit
  frame l_hip l_knee l_ankle l_toe r_hip r_knee r_ankle r_toe l_contact r_contact   (degrees)
  cycles N cadence C step L speed V
  mean thigh|knee|ankle v0 .. v50   (left mean cycle, 0..100 % in 2 % steps)
usage: bvh_sagittal_dump.py CLIP.bvh [--scale M] [--up y|z] [--skip N]
"""
import argparse
import contextlib
import io
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bvh_sagittal as reference  # noqa: E402

COLUMNS = ["l_hip", "l_knee", "l_ankle", "l_toe", "r_hip", "r_knee", "r_ankle", "r_toe",
           "l_contact", "r_contact"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bvh")
    ap.add_argument("--scale", type=float)
    ap.add_argument("--up", choices=["y", "z"], default="y")
    ap.add_argument("--skip", type=int, default=-1)
    args = ap.parse_args()
    args.h_thr, args.v_thr = 0.04, 1.0
    res = reference.analyse(args.bvh, args)
    print("skip %d scale %r" % (res["skip"], res["scale"]))
    for i in range(len(res["t"])):
        print("frame " + " ".join(repr(float(res[c][i])) for c in COLUMNS))
    with contextlib.redirect_stdout(io.StringIO()):
        out = reference.cycles(res)
    if out:
        print("cycles %d cadence %r step %r speed %r" % (out["cycles"], out["cadence"],
                                                       out["step"], out["speed"]))
        for key, label in (("hip", "thigh"), ("knee", "knee"), ("ankle", "ankle")):
            print("mean " + label + " " + " ".join(repr(v) for v in out["mean"][key]))
    else:
        print("cycles 0")


if __name__ == "__main__":
    main()
