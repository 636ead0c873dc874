#!/usr/bin/env python3
"""A walk from standing to a stop as a chronophotograph: the side view of the walker every
`--every` seconds, drawn where it was, left leg blue, right leg orange, from `fuzzygait walk`'s
CSV (e.g. --start-pose standing --stop-at 4 --duration 6). Writes an SVG.

    python3 scripts/start-stop-picture.py out/walk.csv docs/start_stop.svg
"""
import argparse
import csv


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("walk_csv")
    parser.add_argument("svg")
    parser.add_argument("--every", type=float, default=0.1, help="seconds between poses")
    parser.add_argument("--since", type=float, default=0.0, help="first time drawn (s)")
    parser.add_argument("--until", type=float, default=None, help="last time drawn (s)")
    args = parser.parse_args()
    with open(args.walk_csv, newline="") as f:
        rows = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    if not rows:
        raise SystemExit(f"{args.walk_csv}: no frames")
    until = args.until if args.until is not None else rows[-1]["time"]
    chosen, next_time = [], args.since
    for row in rows:
        if row["time"] > until + 1e-9:
            break
        if row["time"] >= next_time - 1e-9 and row["time"] >= args.since - 1e-9:
            chosen.append(row)
            next_time += args.every
    xs = [r[f"{s}_{p}_x"] for r in chosen for s in "lr" for p in ("knee", "tip", "heel")]
    x0, x1 = min(xs) - 0.3, max(xs) + 0.3
    top = max(r["pelvis_y"] for r in chosen) + 0.75
    scale = min(1600.0 / (x1 - x0), 420.0 / (top + 0.15))
    height = (top + 0.15) * scale
    width = (x1 - x0) * scale

    def point(x, y):
        return f"{(x - x0) * scale:.1f},{(top - y) * scale:.1f}"

    parts = []
    for i, r in enumerate(chosen):
        fade = 0.35 + 0.65 * (i % 5 == 0)
        for side, colour in (("l", "#1f77b4"), ("r", "#ff7f0e")):
            names = ("hip", "knee", "ankle", "heel", "ball", "tip")
            pts = " ".join(point(r[f"{side}_{n}_x"], r[f"{side}_{n}_y"]) for n in names[:3])
            foot = " ".join(point(r[f"{side}_{n}_x"], r[f"{side}_{n}_y"])
                            for n in ("ankle", "heel", "ball", "tip"))
            parts.append(f'<polyline points="{pts} {foot}" fill="none" stroke="{colour}" '
                         f'stroke-width="1.6" opacity="{fade:.2f}"/>')
        px, py = r["pelvis_x"], r["pelvis_y"]
        parts.append(f'<line x1="{(px - x0) * scale:.1f}" y1="{(top - py) * scale:.1f}" '
                     f'x2="{(px - x0) * scale:.1f}" y2="{(top - py - 0.5) * scale:.1f}" '
                     f'stroke="#444" stroke-width="2" opacity="{fade:.2f}"/>')
    ground = (f'<line x1="0" y1="{top * scale:.1f}" x2="{width:.0f}" y2="{top * scale:.1f}" '
              'stroke="#777"/>')
    title = (f'<text x="8" y="18" font-family="sans-serif" font-size="14">Side view '
             f'every {args.every:g} s (every fifth darker), {chosen[0]["time"]:.1f}-'
             f'{chosen[-1]["time"]:.1f} s</text>')
    with open(args.svg, "w") as out:
        out.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height:.0f}" '
                  f'viewBox="0 0 {width:.0f} {height:.0f}"><rect width="100%" height="100%" fill="white"/>'
                  f'{title}{ground}{"".join(parts)}</svg>\n')


if __name__ == "__main__":
    main()
