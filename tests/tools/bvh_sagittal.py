#!/usr/bin/env python3
# Copied unchanged from the project's shared tools (shared/tools/bvh_sagittal.py): the reference the
# C++ reader (src/offline/io/mocap_clip.cpp) is held to by tests/io/mocap_test.cpp.
"""bvh_sagittal.py - reference extractor of sagittal leg angles from a BVH walking clip
(plain Python 3, standard library only).

usage: bvh_sagittal.py CLIP.bvh [-o OUT.csv|-] [--scale M_PER_UNIT] [--up y|z] [--skip N]
                       [--h-thr M] [--v-thr M_S] [--cycles] [--compare NORM.csv]

Method
  * Parses the BVH hierarchy (any channel order; a joint's rotation is R = R(ch1) R(ch2) R(ch3)
    in the order the CHANNELS line lists them) and runs forward kinematics for every frame.
  * Units: positions times --scale give metres.  Without --scale the unit is guessed from the
    rest-pose hip-to-ankle length among m, cm, mm, inch and CMU units (1/0.45 inch =
    0.056444 m), taking the one that makes it closest to 0.80 m.
  * A first frame that is a calibration T-pose (every rotation an integer, >80 % of them zero,
    as in the cgspeed CMU conversions) is dropped unless --skip N says otherwise.
  * Sagittal plane: vertical axis u (--up, default y) and walking direction f = horizontal
    displacement of the root from the first to the last frame.
CSV columns (angles in degrees)
  pelvis_tilt  always 0: the CMU skeleton has no pelvis markers.
  l_hip, r_hip thigh (hip->knee) inclination from the downward vertical, projected on the
               sagittal plane, positive when the knee is in front of the hip.  Compare it with a
               lab's hip flexion minus pelvic tilt.
  *_knee       3-D angle between thigh (hip->knee) and shank (knee->ankle); >= 0, 0 = straight.
  *_ankle      3-D angle between shank (knee->ankle) and foot (ankle->toe base) minus the same
               angle in the BVH rest pose (all rotations zero); positive = dorsiflexion.
  *_toe        3-D angle between foot (ankle->toe base) and toe (toe base->its end site) minus
               its rest value; positive = MTP extension (toes up).  nan if there is no end site.
  *_contact    1 while the foot is on the ground: ankle less than --h-thr (0.04 m) above its
               ground level and moving horizontally slower than --v-thr (1.0 m/s), or the same
               for the toe base, or ankle or toe base almost still (3-D speed < 0.3 m/s, which
               catches contacts on raised ground).  Ground level of ankle / toe base: straight
               line (height against distance along f) fitted to the frames where that point of
               either foot is still (< 0.2 m/s), which absorbs a tilted floor or a ramp.  Speeds
               are central differences over 5 frames; runs of contact or of no contact shorter
               than 0.05 s are merged into their neighbours.
--cycles  heel strike = onset of contact.  Left cycles (left heel strike to the next, 0.6-2.0 s)
  are resampled to 0..100 % in 2 % steps and averaged; prints thigh (= l_hip), knee and ankle
  with the number of cycles, cadence (from successive left/right heel strikes), step length
  (ankle-to-ankle distance along f at each heel strike) and speed.
--compare NORM.csv (percent,hip_mean,..,knee_mean,..,ankle_mean,..,pelvis_tilt_mean): also RMSE
  and Pearson r of the mean curves against hip_mean - pelvis_tilt_mean, knee_mean, ankle_mean.
"""
import argparse, csv, itertools, math, sys

ALIASES = {"hip": ["UpLeg", "Hip", "Thigh", "femur"], "knee": ["Leg", "Knee", "Shin", "tibia"],
           "ankle": ["Foot", "Ankle", "foot"], "toe": ["ToeBase", "Toe", "toes"]}
UNITS = [1.0, 0.01, 0.001, 0.0254, 0.0254 / 0.45]
COLS = ["pelvis_tilt", "l_hip", "l_knee", "l_ankle", "l_toe", "r_hip", "r_knee", "r_ankle", "r_toe",
        "l_contact", "r_contact"]

def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def norm(a): return math.sqrt(dot(a, a))
def mean(v): return sum(v) / len(v)

def angle3(a, b):
    return math.degrees(math.acos(max(-1.0, min(1.0, dot(a, b) / (norm(a) * norm(b) + 1e-12)))))

def matmul(a, b):
    return tuple(sum(a[3 * r + k] * b[3 * k + c] for k in range(3)) for r in range(3) for c in range(3))

def rot(axis, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return {"X": (1, 0, 0, 0, c, -s, 0, s, c), "Y": (c, 0, s, 0, 1, 0, -s, 0, c),
            "Z": (c, -s, 0, s, c, 0, 0, 0, 1)}[axis]

def parse_bvh(path):
    """Returns (joints, frames, dt); a joint is a dict(name, parent, offset, channels)."""
    with open(path) as fh:
        lines = fh.read().split("\n")
    joints, stack, i = [], [], 0
    while not lines[i].strip().upper().startswith("MOTION"):
        tok = lines[i].split() or [""]
        if tok[0] in ("ROOT", "JOINT", "End"):
            name = joints[stack[-1]]["name"] + "_End" if tok[0] == "End" else tok[1]
            joints.append({"name": name, "parent": stack[-1] if stack else -1,
                           "offset": (0.0, 0.0, 0.0), "channels": []})
        elif tok[0] == "{":
            stack.append(len(joints) - 1)
        elif tok[0] == "}":
            stack.pop()
        elif tok[0] == "OFFSET":
            joints[stack[-1]]["offset"] = tuple(float(v) for v in tok[1:4])
        elif tok[0] == "CHANNELS":
            joints[stack[-1]]["channels"] = tok[2:2 + int(tok[1])]
        i += 1
    nframes, dt = int(lines[i + 1].split(":")[1]), float(lines[i + 2].split(":")[1])
    frames = [[float(v) for v in ln.split()] for ln in lines[i + 3:i + 3 + nframes] if ln.strip()]
    return joints, frames, dt

def forward_kinematics(joints, frame, needed):
    """World positions of the joints whose indices are in `needed` (ancestors included)."""
    col, world = 0, {}
    for j, jt in enumerate(joints):
        ch = jt["channels"]
        vals, col = frame[col:col + len(ch)], col + len(ch)
        if j not in needed:
            continue
        t, r = list(jt["offset"]), (1, 0, 0, 0, 1, 0, 0, 0, 1)
        for c, v in zip(ch, vals):
            if c.endswith("position"):
                t["XYZ".index(c[0].upper())] += v
            else:
                r = matmul(r, rot(c[0].upper(), v))
        if jt["parent"] < 0:
            world[j] = (tuple(t), r)
        else:
            pp, pr = world[jt["parent"]]
            pt = tuple(dot(pr[3 * k:3 * k + 3], t) for k in range(3))
            world[j] = (tuple(p + q for p, q in zip(pp, pt)), matmul(pr, r))
    return {j: w[0] for j, w in world.items()}

def find_leg(joints, side):
    """Indices of hip, knee, ankle, toe base and toe end site of side 'Left' or 'Right'."""
    names, out = [j["name"] for j in joints], {}
    for part, cands in ALIASES.items():
        hits = [names.index(p + c) for c in cands for p in (side, side[0], side[0].lower())
                if p + c in names]
        if not hits:
            sys.exit("no %s %s joint among %s" % (side, part, names))
        out[part] = hits[0]
    ends = [k for k, j in enumerate(joints) if j["parent"] == out["toe"]]
    out["tip"] = ends[0] if ends else None
    return out

def ground_line(samples):
    """Ground height a + b*x through (x, height, speed) samples taken while still (< 0.2 m/s)."""
    still = [(x, h) for x, h, v in samples if v < 0.2]
    if len(still) < 10:
        return sorted(h for _, h, _ in samples)[len(samples) // 20], 0.0
    mx, mh = mean([x for x, _ in still]), mean([h for _, h in still])
    sxx = sum((x - mx) ** 2 for x, _ in still)
    b = sum((x - mx) * (h - mh) for x, h in still) / sxx if sxx > 1e-9 else 0.0
    return mh - b * mx, b

def debounce(flags, n):
    """Merge inner runs shorter than n frames into the state before them."""
    out, runs = [], [(k, len(list(g))) for k, g in itertools.groupby(flags)]
    for idx, (k, m) in enumerate(runs):
        out += [out[-1] if m < n and 0 < idx < len(runs) - 1 else k] * m
    return out

def analyse(path, args):
    joints, frames, dt = parse_bvh(path)
    legs = {s: find_leg(joints, s) for s in ("Left", "Right")}
    up = (0, 1, 0) if args.up == "y" else (0, 0, 1)
    leg = legs["Left"]
    leg_len = norm(joints[leg["knee"]]["offset"]) + norm(joints[leg["ankle"]]["offset"])
    scale = args.scale or min(UNITS, key=lambda s: abs(math.log(leg_len * s / 0.80)))
    skip = args.skip
    if skip < 0:  # auto: drop a calibration T-pose first frame
        rots = [v for c, v in zip([c for jt in joints for c in jt["channels"]], frames[0])
                if not c.endswith("position")]
        skip = int(all(v == round(v) for v in rots) and sum(v == 0 for v in rots) > 0.8 * len(rots))
    needed, todo = set(), [k for lg in legs.values() for k in lg.values() if k is not None]
    while todo:
        k = todo.pop()
        if k >= 0 and k not in needed:
            needed.add(k)
            todo.append(joints[k]["parent"])
    pos = [{k: tuple(scale * c for c in p) for k, p in forward_kinematics(joints, fr, needed).items()}
           for fr in frames[skip:]]
    n = len(pos)
    horiz = lambda v: sub(v, tuple(dot(v, up) * c for c in up))
    disp = horiz(sub(pos[-1][0], pos[0][0]))
    if norm(disp) < 0.2:
        print("warning: the root moves only %.2f m; walking direction unreliable" % norm(disp),
              file=sys.stderr)
    f = tuple(c / (norm(disp) + 1e-12) for c in disp)

    def speed(k, i, flat=True):
        a, b = max(0, i - 2), min(n - 1, i + 2)
        d = sub(pos[b][k], pos[a][k])
        return norm(horiz(d) if flat else d) / ((b - a) * dt)

    ground = {key: ground_line([(dot(p[lg[key]], f), dot(p[lg[key]], up), speed(lg[key], i))
                                for i, p in enumerate(pos) for lg in legs.values()])
              for key in ("ankle", "toe")}
    res = {"t": [i * dt for i in range(n)], "dt": dt, "f": f, "pos": pos, "scale": scale,
           "skip": skip, "legs": legs, "pelvis_tilt": [0.0] * n}
    for side, lg in legs.items():
        s, off = side[0].lower(), lambda k: joints[lg[k]]["offset"]
        rest_ank = angle3(off("ankle"), off("toe"))
        rest_toe = angle3(off("toe"), off("tip")) if lg["tip"] else 0.0
        for key in ("hip", "knee", "ankle", "toe", "contact"):
            res[s + "_" + key] = []
        for i, p in enumerate(pos):
            th, sh = sub(p[lg["knee"]], p[lg["hip"]]), sub(p[lg["ankle"]], p[lg["knee"]])
            ft = sub(p[lg["toe"]], p[lg["ankle"]])
            res[s + "_hip"].append(math.degrees(math.atan2(dot(th, f), -dot(th, up))))
            res[s + "_knee"].append(angle3(th, sh))
            res[s + "_ankle"].append(angle3(sh, ft) - rest_ank)
            res[s + "_toe"].append(angle3(ft, sub(p[lg["tip"]], p[lg["toe"]])) - rest_toe
                                   if lg["tip"] else float("nan"))
            on = False
            for key in ("ankle", "toe"):
                a, b = ground[key]
                h = dot(p[lg[key]], up) - a - b * dot(p[lg[key]], f)
                on = on or (h < args.h_thr and speed(lg[key], i) < args.v_thr) \
                    or speed(lg[key], i, flat=False) < 0.3
            res[s + "_contact"].append(int(on))
        res[s + "_contact"] = debounce(res[s + "_contact"], max(1, round(0.05 / dt)))
    return res

def heel_strikes(c):
    return [i for i in range(1, len(c)) if c[i] and not c[i - 1]]

def resample(y, i0, i1, pct):
    x = i0 + (i1 - i0) * pct / 100.0
    k = min(int(x), i1 - 1)
    return y[k] + (y[k + 1] - y[k]) * (x - k)

def cycles(res, norm_path=None):
    dt, grid, legs, f, pos = res["dt"], list(range(0, 101, 2)), res["legs"], res["f"], res["pos"]
    hs = {s: heel_strikes(res[s + "_contact"]) for s in "lr"}
    cyc = [(a, b) for a, b in zip(hs["l"], hs["l"][1:]) if 0.6 <= (b - a) * dt <= 2.0]
    if not cyc:
        print("no complete left cycle (left heel strikes at frames %s)" % hs["l"])
        return None
    curves = {k: [mean([resample(res["l_" + k], a, b, g) for a, b in cyc]) for g in grid]
              for k in ("hip", "knee", "ankle")}
    ev = sorted([(i, "Left") for i in hs["l"]] + [(i, "Right") for i in hs["r"]])
    steps = [(b - a) * dt for (a, sa), (b, sb) in zip(ev, ev[1:]) if sa != sb and (b - a) * dt < 1.0]
    other = {"Left": "Right", "Right": "Left"}
    lens = [dot(sub(pos[i][legs[s]["ankle"]], pos[i][legs[other[s]]["ankle"]]), f) for i, s in ev]
    i0, i1 = ev[0][0], ev[-1][0]
    out = {"cycles": len(cyc), "mean": curves,
           "cadence": 60.0 / mean(steps) if steps else float("nan"), "step": mean(lens),
           "speed": dot(sub(pos[i1][0], pos[i0][0]), f) / ((i1 - i0) * dt) if i1 > i0 else float("nan")}
    print("cycles %d  cadence %.1f steps/min  step length %.3f m  speed %.2f m/s  "
          "(scale %.6f m/unit, skipped %d frame)" % (len(cyc), out["cadence"], out["step"],
                                                      out["speed"], res["scale"], res["skip"]))
    print("pct   thigh    knee   ankle")
    for k, g in enumerate(grid):
        print("%3d %7.1f %7.1f %7.1f" % (g, curves["hip"][k], curves["knee"][k], curves["ankle"][k]))
    if norm_path:
        with open(norm_path) as fh:
            rows = {round(float(r["percent"])): r for r in csv.DictReader(fh)}
        col = lambda name: [float(rows[g][name]) for g in grid]
        ref = {"hip": [h - p for h, p in zip(col("hip_mean"), col("pelvis_tilt_mean"))],
               "knee": col("knee_mean"), "ankle": col("ankle_mean")}
        for k, label in (("hip", "thigh"), ("knee", "knee"), ("ankle", "ankle")):
            a, b = curves[k], ref[k]
            ma, mb = mean(a), mean(b)
            rmse = math.sqrt(mean([(x - y) ** 2 for x, y in zip(a, b)]))
            r = sum((x - ma) * (y - mb) for x, y in zip(a, b)) / math.sqrt(
                sum((x - ma) ** 2 for x in a) * sum((y - mb) ** 2 for y in b))
            out[label] = (rmse, r)
            print("compare %-6s RMSE %5.1f deg  r %.3f" % (label, rmse, r))
    return out

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bvh")
    ap.add_argument("-o", "--out", help="CSV output path ('-' = stdout)")
    ap.add_argument("--scale", type=float, help="metres per BVH unit (default: guessed)")
    ap.add_argument("--up", choices=["y", "z"], default="y")
    ap.add_argument("--skip", type=int, default=-1, help="leading frames to drop (default: auto)")
    ap.add_argument("--h-thr", type=float, default=0.04, help="contact height threshold, m")
    ap.add_argument("--v-thr", type=float, default=1.0, help="contact speed threshold, m/s")
    ap.add_argument("--cycles", action="store_true", help="print left mean-cycle curves")
    ap.add_argument("--compare", help="normative CSV: also print RMSE and r (implies --cycles)")
    args = ap.parse_args()
    res = analyse(args.bvh, args)
    if args.out:
        fh = sys.stdout if args.out == "-" else open(args.out, "w", newline="")
        w = csv.writer(fh)
        w.writerow(["time"] + COLS)
        for i, t in enumerate(res["t"]):
            w.writerow(["%.4f" % t] + [("%d" if c.endswith("contact") else "%.2f") % res[c][i]
                                       for c in COLS])
        fh.flush()
    if args.cycles or args.compare:
        cycles(res, args.compare)

if __name__ == "__main__":
    main()
