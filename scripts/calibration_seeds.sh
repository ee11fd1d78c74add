#!/usr/bin/env bash
# Calibration accuracy over noise seeds: for each seed, render the scene (checkerboard-poses; the frames' noise changes
# with the seed), calibrate it, and compare the estimated rig and the corners found with the truth
# (`rfrecon evaluate-rig`); then the mean, spread and RMS over the seeds of every figure, as JSON.
# Usage: scripts/calibration_seeds.sh [--rfrecon BIN] [--seeds N] [--out DIR] [--calibrate "OPTIONS"]
#                                     [--scene NAME|FILE --board COLSxROWS --square MM] [extra simulate options...]
# --calibrate adds options to each `rfrecon calibrate` (e.g. "--dense-points 0"). About 2 minutes per seed on a
# 2-core machine.
set -euo pipefail
rfrecon=build/rfrecon
seeds=10
out=calibration-seeds
calibrate_options=""
scene=checkerboard-poses
board=14x9
square=20
while [[ $# -gt 0 ]]; do
  case "$1" in
    --rfrecon) rfrecon=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --calibrate) calibrate_options=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    --board) board=$2; shift 2 ;;
    --square) square=$2; shift 2 ;;
    *) break ;;
  esac
done
mkdir -p "$out"
for seed in $(seq 1 "$seeds"); do
  dir="$out/seed_$seed"
  if [[ ! -f "$dir/evaluate-rig.json" ]]; then
    "$rfrecon" -q simulate --scene "$scene" --seed "$seed" -o "$dir/poses" --force "$@"
    # shellcheck disable=SC2086 # the options are words
    "$rfrecon" -q calibrate "$dir"/poses/capture/pose_* --board "$board" --square "$square" -o "$dir/rig.yaml" --force \
      $calibrate_options > "$dir/calibrate.txt"
    "$rfrecon" evaluate-rig "$dir/rig.yaml" --truth "$dir/poses/truth/rig.yaml" -o "$dir/evaluate-rig.json" --force \
      --corners "$dir/rig_report/corners.json" --board-poses "$dir/poses/truth/board_poses.json"
    rm -rf "$dir/poses/capture"  # the frames are large; the truth and the rig stay
  fi
done
python3 - "$out" "$seeds" <<'PY'
import json, math, sys
out, seeds = sys.argv[1], int(sys.argv[2])
def flat(run, prefix=""):
    out = {}
    for key, value in run.items():
        if isinstance(value, dict):
            out.update(flat(value, prefix + key + "."))
        else:
            out[prefix + key] = value
    return out
runs = [flat(json.load(open(f"{out}/seed_{s}/evaluate-rig.json"))) for s in range(1, seeds + 1)]
summary = {"seeds": seeds}
for key, value in runs[0].items():
    if not isinstance(value, (int, float)) or key == "points":
        continue
    values = [r[key] for r in runs]
    mean = sum(values) / len(values)
    std = math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1)) if len(values) > 1 else 0.0
    rms = math.sqrt(sum(v * v for v in values) / len(values))
    summary[key] = {"mean": mean, "std": std, "rms": rms, "min": min(values), "max": max(values)}
    print(f"{key:34s} mean {mean:+.3e}  std {std:.3e}  rms {rms:.3e}  [{min(values):+.3e}, {max(values):+.3e}]")
with open(f"{out}/summary.json.tmp", "w") as f:
    json.dump(summary, f, indent=2)
import os
os.replace(f"{out}/summary.json.tmp", f"{out}/summary.json")
print(f"wrote {out}/summary.json")
PY
