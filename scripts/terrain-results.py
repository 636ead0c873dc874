#!/usr/bin/env python3
"""Walks the default set over the terrains of issue 19 and prints docs/terrain.md's tables.

Usage: scripts/terrain-results.py [--fuzzygait build/fuzzygait] [--style default] [--out DIR]

Each walk is `fuzzygait walk --terrain SPEC` measured by `fuzzygait eval --json`; nothing here
measures on its own, it only gathers the program's figures into tables.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

STAIRS = [("stairs 0.17 x 0.28, up", "stairs:0.17:0.28:10", "stairs up"),
          ("stairs 0.17 x 0.28, down", "stairs:-0.17:0.28:10", "stairs down")]
REZNICK = [(rise, tread) for rise, tread in
           [(0.097, 0.315), (0.120, 0.305), (0.146, 0.295), (0.162, 0.285)]]
RAMPS = [-20, -15, -10, -5, 5, 10, 15, 20]


def walk(fuzzygait, style, spec, prefix, duration=24.0):
    # A walk that stalls (the 0.097 m descent) fails, its files written: measured all the same.
    walked = subprocess.run([fuzzygait, "walk", "--style", style, "--terrain", spec, "--duration",
                             str(duration), "-o", prefix], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    if walked.returncode != 0 and "the walk stalled" not in walked.stderr:
        raise RuntimeError(f"fuzzygait walk --terrain {spec}: {walked.stderr.strip()}")
    subprocess.run([fuzzygait, "eval", prefix + ".csv", "--json", prefix + ".json"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(prefix + ".json") as f:
        return json.load(f)


def group(report, ground, degrees=None):
    for g in report["terrain"]["groups"]:
        if g["ground"] == ground and (degrees is None or g["degrees"] == degrees):
            return g
    return None


def mean(g, key):
    if g is None or key not in g:
        return math.nan
    v = g[key]
    return v["mean"] if isinstance(v, dict) else v


def fmt(v, digits=1):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.{digits}f}"


def contact(report):
    t = report["terrain"]
    slip = max(p["max_slip_m_per_frame"] for p in t["points"].values()) * 1000
    depth = max(p["max_penetration_m"] for p in t["points"].values()) * 1000
    return slip, depth, t["min_swing_clearance_m"] * 1000, t["nan_frames"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fuzzygait", default="build/fuzzygait")
    parser.add_argument("--style", default="default")
    parser.add_argument("--out", default=None, help="keep the walks here")
    args = parser.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="terrain-results-")
    os.makedirs(out, exist_ok=True)

    level = walk(args.fuzzygait, args.style, "flat", os.path.join(out, "level"), 14.0)
    level_group = group(level, "level")

    print(f"Set '{args.style}', 1.75 m, 0.70 m steps; `fuzzygait eval` figures, means over the "
          "steps of each kind of ground.\n")
    print("| stairs | reached | stance % | hip at contact | knee at contact | knee at toe off "
          "| peak swing knee | peak swing hip | hip range | toe-down vs level | cadence |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for label, spec, ground in STAIRS:
        r = walk(args.fuzzygait, args.style, spec, os.path.join(out, spec.replace(":", "_")))
        g = group(r, ground)
        cadence = 120.0 / mean(g, "cycle_time_s") if g else math.nan
        print(f"| {label} | {'yes' if r['terrain']['reached_end'] else 'no'} "
              f"| {fmt(mean(g, 'stance_percent'))} | {fmt(mean(g, 'hip_at_contact_deg'))} "
              f"| {fmt(mean(g, 'knee_at_contact_deg'))} | {fmt(mean(g, 'knee_at_toe_off_deg'))} "
              f"| {fmt(mean(g, 'peak_swing_knee_deg'))} | {fmt(mean(g, 'peak_swing_hip_deg'))} "
              f"| {fmt(mean(g, 'hip_range_deg'))} | {fmt(mean(g, 'toe_down_vs_level_deg'))} "
              f"| {fmt(cadence)} |")
        rows.append((label, r))

    print("\n| ramp (deg) | sole to surface, mid-stance | hip at contact vs level "
          "| knee at contact vs level | stance ankle vs level | step error % |")
    print("|---|---|---|---|---|---|")
    for degrees in RAMPS:
        spec = f"slope:{degrees}"
        r = walk(args.fuzzygait, args.style, spec, os.path.join(out, f"slope_{degrees}"), 16.0)
        g = group(r, "ramp up" if degrees > 0 else "ramp down", abs(degrees))
        if g is None:
            g = group(r, "ramp up" if degrees > 0 else "ramp down")
        d = {k: mean(g, k) - mean(level_group, k)
             for k in ("hip_at_contact_deg", "knee_at_contact_deg", "mid_stance_ankle_deg")}
        step = mean(g, "step_length_m")
        print(f"| {degrees:+d} | {fmt(mean(g, 'mid_stance_sole_to_surface_deg'))} "
              f"| {fmt(d['hip_at_contact_deg'], 1)} | {fmt(d['knee_at_contact_deg'], 1)} "
              f"| {fmt(d['mid_stance_ankle_deg'], 1)} | {fmt(abs(step / 0.70 - 1) * 100, 1)} |")
        rows.append((spec, r))

    print("\n| Reznick et al. 2021 stair (rise x tread) | up: reached | down: reached |")
    print("|---|---|---|")
    for rise, tread in REZNICK:
        up = walk(args.fuzzygait, args.style, f"stairs:{rise}:{tread}:8",
                  os.path.join(out, f"reznick_up_{rise}"))
        down = walk(args.fuzzygait, args.style, f"stairs:{-rise}:{tread}:8",
                    os.path.join(out, f"reznick_down_{rise}"))
        print(f"| {rise:.3f} x {tread:.3f} m | {'yes' if up['terrain']['reached_end'] else 'no'} "
              f"| {'yes' if down['terrain']['reached_end'] else 'no'} |")
        rows.append((f"stairs {rise} up", up))
        rows.append((f"stairs {rise} down", down))

    print("\n| walk | largest slip (mm a frame) | deepest point (mm) | swing clearance (mm) "
          "| NaN frames |")
    print("|---|---|---|---|---|")
    for label, r in rows:
        slip, depth, clearance, nans = contact(r)
        print(f"| {label} | {fmt(slip, 2)} | {fmt(depth, 2)} | {fmt(clearance, 1)} | {nans} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
