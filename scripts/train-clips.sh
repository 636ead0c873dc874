#!/usr/bin/env bash
# Trains a controller set on each of the CMU walking clips (data/mocap/cmu) and, leaving each clip
# out in turn, on the other eight, then prints the tables of docs/learning.md:
#   per clip: thigh, knee and ankle RMSE (deg) of the trained set walked in closed loop at the
#   clip's legs and step against the clip's mean cycle, stance share and cadence against the
#   clip's, the base set's RMSE before training, the level grid's walks within the contact bounds,
#   the random starts that settle, and the seconds the training took;
#   leave one out: the set trained on eight clips walked against the ninth.
# Usage: scripts/train-clips.sh [BUILD_DIR] [OUT_DIR] [-- extra fuzzygait train options]
# (defaults build and out/train-clips). Figures over a bound (4 deg, 3 points of stance, 5 % of
# cadence; 6 deg left out) are starred. Environment: TRAIN_CLIPS_STARTS (random starts checked,
# default 500), TRAIN_CLIPS_LOO_OPTIONS (options of the eight-clip trainings only, such as a
# smaller budget: each walks eight clips a generation), TRAIN_CLIPS_REUSE=1 (keep a training
# whose report.json exists).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
out=${2:-$root/out/train-clips}
shift $(($# < 2 ? $# : 2))
[[ ${1:-} == -- ]] && shift
extra=("$@")
program=$build/fuzzygait
clips=(05_01 07_01 07_02 07_03 07_06 08_01 08_02 08_03 08_06)
starts=${TRAIN_CLIPS_STARTS:-500}
read -r -a loo_options <<< "${TRAIN_CLIPS_LOO_OPTIONS:-}"
mkdir -p "$out"

done_already() { [[ ${TRAIN_CLIPS_REUSE:-0} == 1 && -f $1/report.json ]]; }

for clip in "${clips[@]}"; do
  done_already "$out/$clip" && continue
  "$program" train "$root/data/mocap/cmu/$clip.bvh" -o "$out/$clip" --check-starts "$starts" \
    "${extra[@]}" > "$out/$clip.log" 2>&1
done
for clip in "${clips[@]}"; do
  others=()
  for other in "${clips[@]}"; do
    [[ $other == "$clip" ]] || others+=("$root/data/mocap/cmu/$other.bvh")
  done
  done_already "$out/without_$clip" ||
    "$program" train "${others[@]}" -o "$out/without_$clip" --check-starts 0 "${extra[@]}" \
      "${loo_options[@]}" > "$out/without_$clip.log" 2>&1
  "$program" train "$root/data/mocap/cmu/$clip.bvh" --controllers "$out/without_$clip" \
    --evaluate "$out/without_$clip/held_out.json" --check-starts 0 > /dev/null 2>&1
done

python3 - "$out" "${clips[@]}" <<'EOF'
import json, sys
out, clips = sys.argv[1], sys.argv[2:]

def star(value, bad):
    return f"{value:.1f}" + (" *" if bad else "")

def curves(s, bound):
    if not s["walked"]:
        return ["does not walk"] * 3
    return [star(s[k], s[k] > bound) for k in ("thigh_rmse_deg", "knee_rmse_deg", "ankle_rmse_deg")]

def timing(s, clip):
    if not s["walked"]:
        return ["-", "-"]
    stance = s["stance_percent"]
    cadence = s["cadence_steps_per_min"]
    return [f"{star(stance, abs(stance - clip['clip_stance_percent']) > 3)} ({clip['clip_stance_percent']:.1f})",
            f"{star(cadence, abs(cadence / clip['clip_cadence_steps_per_min'] - 1) > 0.05)} "
            f"({clip['clip_cadence_steps_per_min']:.1f})"]

print("| clip | thigh | knee | ankle | stance (clip) | cadence (clip) | before: thigh / knee / ankle "
      "| grid | terrain | starts | s |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for clip in clips:
    r = json.load(open(f"{out}/{clip}/report.json"))
    c = r["clips"][0]
    before = c["before"]
    b = " / ".join(f"{before[k]:.1f}" for k in ("thigh_rmse_deg", "knee_rmse_deg", "ankle_rmse_deg")) \
        if before["walked"] else "does not walk"
    print(f"| {clip} | " + " | ".join(curves(c["after"], 4.0) + timing(c["after"], c)) +
          f" | {b} | {r['grid_within_bounds']} of {r['grid_walks']} | "
          f"{r['terrain_within_bounds']} of {r['terrain_walks']} | "
          f"{r['random_starts_settled']} of {r['random_starts']} | {r['seconds']:.0f} |")
print()
print("Leave one out (trained on the other eight, walked against this one):")
print()
print("| held out | thigh | knee | ankle | stance (clip) | cadence (clip) | s |")
print("|---|---|---|---|---|---|---|")
for clip in clips:
    r = json.load(open(f"{out}/without_{clip}/report.json"))
    e = json.load(open(f"{out}/without_{clip}/held_out.json"))["clips"][0]
    print(f"| {clip} | " + " | ".join(curves(e, 6.0) + timing(e, e)) + f" | {r['seconds']:.0f} |")
EOF
