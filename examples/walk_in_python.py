#!/usr/bin/python3
"""Walks the default character, measures it against people and writes it for Blender or three.js.

    PYTHONPATH=build/python python3 examples/walk_in_python.py [PREFIX]   (default out/python_walk)

Writes PREFIX.csv (the walk's frames) and PREFIX.bvh, and prints how the walk measures.
"""
import pathlib
import sys

import numpy as np

import fuzzygait as fg

prefix = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out/python_walk")
prefix.parent.mkdir(parents=True, exist_ok=True)

# One character, 1.80 m tall, at 1.3 m/s: 10 gait cycles at 120 frames a second.
walker = fg.Walker("default", speed=1.3, stature=1.80)
motion = walker.record_cycles(10, fps=120)
motion.write_csv(f"{prefix}.csv")
motion.write_bvh(f"{prefix}.bvh")

report = fg.evaluate(motion)
print(f"walked {len(motion)} frames: {report.cadence:.1f} steps/min, "
      f"{report.step_length:.3f} m steps, {report.speed:.2f} m/s, stance {report.stance_percent:.1f} %")
for joint in ("thigh", "knee", "ankle"):
    score = report.scores[joint]
    print(f"  {joint}: RMSE {score['rmse']:.1f} deg, r {score['pearson']:.2f} against people")
knee = report.curves["knee"]["mean"]
print(f"  peak swing knee {knee.max():.1f} deg at {2 * int(np.argmax(knee))} % of the cycle")

# A crowd of 100 of every height, stepped together; its arrays are views of its own memory.
crowd = fg.Crowd("default", [{"stature": h} for h in np.linspace(1.5, 2.0, 100)])
pelvis = crowd.pelvis
for _ in range(5 * 60):
    crowd.advance(1 / 60)
print(f"a crowd of {len(crowd)} walked 5 s: {pelvis[:, 0].min():.2f}-{pelvis[:, 0].max():.2f} m")
print(f"wrote {prefix}.csv and {prefix}.bvh")
