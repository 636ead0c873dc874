#!/usr/bin/env python3
"""upper-body.py - how people's arms, pelvis and trunk move in the CMU walks (data/mocap/cmu).

usage: scripts/upper-body.py [CLIP.bvh ...]

For each clip, over its left gait cycles (left heel strike to the next; a heel strike is the
left ankle's lowest point between two of its forward swings), the mean of: the left shoulder's
flexion (upper arm LeftArm -> LeftForeArm against the downward vertical, in the walk's sagittal
plane, forward +), the left elbow's flexion (3-D angle between upper arm and forearm), the left
and right thighs' inclination (hip -> knee, same plane), the pelvis's rotation (the line from the
right to the left hip joint against the walk's left, about the vertical; left hip forward +) and
the thorax's (the same for the shoulder joints). Prints each figure's range, the share of the
cycle where it peaks, and the straight-line fit of the shoulder and of the pelvis's rotation to a
thigh, which is what the body controllers in controllers/*/upper_body_*.fll read; then the frontal
plane (see frontal()). numpy only.
"""
import glob, math, os, sys
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def parse_bvh(path):
    with open(path) as fh:
        lines = fh.read().split("\n")
    joints, stack, i = [], [], 0
    while not lines[i].strip().upper().startswith("MOTION"):
        tok = lines[i].split() or [""]
        if tok[0] in ("ROOT", "JOINT", "End"):
            name = joints[stack[-1]]["name"] + "_End" if tok[0] == "End" else tok[1]
            joints.append({"name": name, "parent": stack[-1] if stack else -1,
                           "offset": np.zeros(3), "channels": []})
        elif tok[0] == "{":
            stack.append(len(joints) - 1)
        elif tok[0] == "}":
            stack.pop()
        elif tok[0] == "OFFSET":
            joints[stack[-1]]["offset"] = np.array([float(v) for v in tok[1:4]])
        elif tok[0] == "CHANNELS":
            joints[stack[-1]]["channels"] = tok[2:2 + int(tok[1])]
        i += 1
    dt = float(lines[i + 2].split(":")[1])
    frames = np.array([[float(v) for v in ln.split()] for ln in lines[i + 3:] if ln.strip()])
    return joints, frames, dt


def rotation(axis, degrees):
    c, s = np.cos(np.radians(degrees)), np.sin(np.radians(degrees))
    n = len(degrees)
    m = np.zeros((n, 3, 3))
    a = "XYZ".index(axis)
    b, d = [k for k in range(3) if k != a]
    m[:, a, a] = 1
    m[:, b, b] = c
    m[:, d, d] = c
    sign = 1 if axis != "Y" else -1
    m[:, b, d] = -sign * s
    m[:, d, b] = sign * s
    return m


def positions(joints, frames):
    """World positions of every joint, frames x joints x 3 (BVH units)."""
    n = len(frames)
    world_p = np.zeros((n, len(joints), 3))
    world_r = np.zeros((n, len(joints), 3, 3))
    col = 0
    for j, jt in enumerate(joints):
        t = np.tile(jt["offset"], (n, 1))
        r = np.tile(np.eye(3), (n, 1, 1))
        for c in jt["channels"]:
            v = frames[:, col]
            col += 1
            if c.endswith("position"):
                t[:, "XYZ".index(c[0].upper())] += v
            else:
                r = r @ rotation(c[0].upper(), v)
        if jt["parent"] < 0:
            world_p[:, j], world_r[:, j] = t, r
        else:
            p = jt["parent"]
            world_p[:, j] = world_p[:, p] + np.einsum("nij,nj->ni", world_r[:, p], t)
            world_r[:, j] = world_r[:, p] @ r
    return world_p


def measure(path):
    joints, frames, dt = parse_bvh(path)
    names = [j["name"] for j in joints]
    if frames[0][3:].round().tolist() == frames[0][3:].tolist():  # a calibration T-pose first
        frames = frames[1:]
    p = positions(joints, frames)
    at = lambda name: p[:, names.index(name)]
    up = np.array([0.0, 1.0, 0.0])
    travel = at("Hips")[-1] - at("Hips")[0]
    travel[1] = 0
    forward = travel / np.linalg.norm(travel)
    left = np.cross(up, forward)  # Y up, X left, Z forward

    def inclination(a, b):  # forward of the downward vertical, in the sagittal plane
        v = at(b) - at(a)
        return np.degrees(np.arctan2(v @ forward, -(v @ up)))

    def about_vertical(a, b):  # the line a -> b turned from the body's left, left end forward +
        v = at(a) - at(b)
        return np.degrees(np.arctan2(v @ forward, v @ left))

    def knee(hip, knee_joint, ankle):  # flexion: 180 deg less the angle at the knee
        a, b = at(hip) - at(knee_joint), at(ankle) - at(knee_joint)
        c = np.sum(a * b, 1) / np.linalg.norm(a, axis=1) / np.linalg.norm(b, axis=1)
        return 180.0 - np.degrees(np.arccos(np.clip(c, -1, 1)))

    def obliquity():  # the left hip joint above the right, in the frontal plane, left up +
        v = at("LeftUpLeg") - at("RightUpLeg")
        return np.degrees(np.arctan2(v @ up, v @ left))

    def adduction(hip, knee_joint, side):  # the thigh towards the midline, in the pelvis's frame
        pelvis_left = at("LeftUpLeg") - at("RightUpLeg")
        pelvis_left /= np.linalg.norm(pelvis_left, axis=1)[:, None]
        thigh = at(knee_joint) - at(hip)
        thigh /= np.linalg.norm(thigh, axis=1)[:, None]
        return np.degrees(np.arcsin(np.clip(-side * np.sum(thigh * pelvis_left, 1), -1, 1)))

    def sway():  # the hips' centre to the left of the walk's straight line, over leg length
        centre = 0.5 * (at("LeftUpLeg") + at("RightUpLeg"))
        lateral = centre @ left
        t = np.arange(len(lateral))
        lateral = lateral - np.polyval(np.polyfit(t, lateral, 1), t)
        return 100.0 * lateral / leg_length

    hip_height = 0.5 * (at("LeftUpLeg") + at("RightUpLeg")) @ up
    foot_low = np.minimum(at("LeftToeBase") @ up, at("RightToeBase") @ up)
    leg_length = np.median(hip_height - foot_low)
    upper = at("LeftForeArm") - at("LeftArm")
    fore = at("LeftHand") - at("LeftForeArm")
    cosine = np.sum(upper * fore, 1) / np.linalg.norm(upper, axis=1) / np.linalg.norm(fore, axis=1)
    series = {
        "shoulder": inclination("LeftArm", "LeftForeArm"),
        "elbow": np.degrees(np.arccos(np.clip(cosine, -1, 1))),
        "left_thigh": inclination("LeftUpLeg", "LeftLeg"),
        "right_thigh": inclination("RightUpLeg", "RightLeg"),
        "pelvis_rotation": about_vertical("LeftUpLeg", "RightUpLeg"),
        "thorax_rotation": about_vertical("LeftArm", "RightArm"),
        "left_knee": knee("LeftUpLeg", "LeftLeg", "LeftFoot"),
        "right_knee": knee("RightUpLeg", "RightLeg", "RightFoot"),
        "pelvis_obliquity": obliquity(),
        "left_hip_adduction": adduction("LeftUpLeg", "LeftLeg", 1.0),
        "pelvis_sway": sway(),
    }
    # Left heel strikes: the left thigh's most forward inclinations, a cycle apart.
    thigh = series["left_thigh"]
    peaks = [i for i in range(2, len(thigh) - 2)
             if thigh[i] == thigh[i - 2:i + 3].max() and thigh[i] > thigh.mean() + 5]
    strikes = [i for k, i in enumerate(peaks) if k == 0 or i - peaks[k - 1] > 0.5 / dt]
    grid = np.linspace(0, 1, 51)
    cycles = {k: [] for k in series}
    for a, b in zip(strikes, strikes[1:]):
        if not 0.6 < (b - a) * dt < 2.0:
            continue
        for k, v in series.items():
            cycles[k].append(np.interp(a + grid * (b - a), np.arange(len(v)), v))
    speed = np.linalg.norm(travel) * 0.056444 / (dt * (len(frames) - 1))  # CMU units to m
    return {k: np.mean(v, 0) for k, v in cycles.items()}, len(cycles["shoulder"]), speed, series


def main():
    clips = sys.argv[1:] or sorted(glob.glob(os.path.join(ROOT, "data/mocap/cmu/*.bvh")))
    print("clip   cycles speed  shoulder range / peak  elbow range  pelvis rotation  thorax"
          "    shoulder ~ left thigh  pelvis ~ right thigh")
    fits = []
    for clip in clips:
        mean, count, speed, series = measure(clip)
        s, e = mean["shoulder"], mean["elbow"]
        pr, tr = mean["pelvis_rotation"], mean["thorax_rotation"]
        a_s = np.polyfit(series["left_thigh"], series["shoulder"], 1)
        r_s = np.corrcoef(series["left_thigh"], series["shoulder"])[0, 1]
        a_p = np.polyfit(series["right_thigh"], series["pelvis_rotation"], 1)
        r_p = np.corrcoef(series["right_thigh"], series["pelvis_rotation"])[0, 1]
        a_e = np.polyfit(series["left_thigh"], series["elbow"], 1)
        a_t = np.polyfit(series["right_thigh"], series["thorax_rotation"], 1)
        fits.append((a_s, a_p, s.max() - s.min(), e.min(), e.max(),
                     pr.max() - pr.min(), tr.max() - tr.min(), a_e, a_t))
        print("%s %3d %5.2f  %5.1f..%5.1f at %3.0f %%  %4.1f..%4.1f  %5.1f..%5.1f  %5.1f..%5.1f"
              "   %+.2f x %+5.1f (r %.2f)  %+.2f x %+5.1f (r %.2f)" % (
                  os.path.basename(clip)[:-4], count, speed, s.min(), s.max(),
                  100 * np.argmax(s) / 50, e.min(), e.max(), pr.min(), pr.max(), tr.min(),
                  tr.max(), a_s[0], a_s[1], r_s, a_p[0], a_p[1], r_p))
    f = np.array([np.concatenate([a, b, [c, d, e, g, h], i, j]) for a, b, c, d, e, g, h, i, j in fits])
    print("mean: shoulder = %.2f x left thigh %+.1f deg (range %.1f deg); elbow %.1f..%.1f deg; "
          "pelvis rotation = %.2f x right thigh %+.1f (range %.1f); thorax range %.1f" %
          (f[:, 0].mean(), f[:, 1].mean(), f[:, 4].mean(), f[:, 5].mean(), f[:, 6].mean(),
           f[:, 2].mean(), f[:, 3].mean(), f[:, 7].mean(), f[:, 8].mean()))
    print("mean: elbow = %.2f x left thigh %+.1f; thorax rotation = %.2f x right thigh %+.1f" %
          (f[:, 9].mean(), f[:, 10].mean(), f[:, 11].mean(), f[:, 12].mean()))
    frontal(clips)


def ramp(x, a, b):  # 0 at a, 1 at b, clamped
    return np.clip((x - a) / (b - a), 0.0, 1.0)


def frontal(clips):
    """The frontal plane: pelvis obliquity, hip adduction and the pelvis's sway, and the number
    of upper_body_pelvis_sway.fll (the pelvis moves over a side whose knee is straight, below 30
    deg, and whose thigh is near vertical: each side's answer is that membership times the fitted
    percent of the leg's length). The obliquity printed here is the CMU root's roll: the swing
    side drops, as Schwartz et al. 2008's, but it is lowest at the swing's end where theirs is
    lowest at its start (16 % after the other foot's contact); upper_body_pelvis_obliquity.fll
    follows Schwartz's, the bound of issue 30 (tests/body/follower_test.cpp)."""
    print("\nclip   obliquity range / left up most  left hip adduction  sway, % of leg length"
          " / most left")
    s_x, s_y = [], []
    curves = {"pelvis_obliquity": [], "left_hip_adduction": [], "pelvis_sway": []}
    for clip in clips:
        mean, count, speed, series = measure(clip)
        o, a, w = mean["pelvis_obliquity"], mean["left_hip_adduction"], mean["pelvis_sway"]
        for k in curves:
            curves[k].append(mean[k])
        print("%s %5.1f..%4.1f at %3.0f %%          %5.1f..%4.1f        %5.2f..%4.2f at %3.0f %%" % (
            os.path.basename(clip)[:-4], o.min(), o.max(), 100 * np.argmax(o) / 50, a.min(),
            a.max(), w.min(), w.max(), 100 * np.argmax(w) / 50))
        kl, kr = series["left_knee"], series["right_knee"]
        over = lambda k, thigh: ramp(-k, -30, 0) * ramp(31 - np.abs(thigh), 0, 31)
        s_x.append(over(kl, series["left_thigh"]) - over(kr, series["right_thigh"]))
        s_y.append(series["pelvis_sway"])
    c_s = np.linalg.lstsq(np.concatenate(s_x)[:, None], np.concatenate(s_y), rcond=None)[0][0]
    r_s = np.corrcoef(np.concatenate(s_x), np.concatenate(s_y))[0, 1]
    print("fit: pelvis sway = %.2f %% of leg length x (left over - right over) (r %.2f)" %
          (c_s, r_s))
    for k, v in curves.items():
        print("mean %s every 10 %%: %s" % (k, " ".join("%5.1f" % x for x in np.mean(v, 0)[::5])))


if __name__ == "__main__":
    main()
