#!/usr/bin/env bash
# Predicted depth sigma against the observed spread (docs/accuracy.md, "Uncertainty of each point").
# Frames: for each scene and noise seed 1..FRAME_SEEDS, `rfrecon simulate`, transport and reconstruct with the true rig
# (calibration part 0) by each method (--sigma-samples 8 where there is no closed form); scripts/depth_sigma_spread.py
# over the seeds with depth_sigma_observation.
# Calibrations: for pose seed 1..POSE_SEEDS, checkerboard-poses with every board pose moved at random (up to 15 mm
# across, 30 mm in depth, 4 degrees about each axis; the noise seed is the pose seed) is rendered and calibrated; each
# rig reconstructs seed 1's T.h5 of each scene with each method (--sigma-samples 8: the integration and the fusion
# rerun on the rig moved along its covariance's principal directions), and the spread over the rigs is compared with
# depth_sigma_calibration. Prints one JSON line per scene, method and part. About 70 minutes on a 2-core machine
# with 30 pose seeds, most of it the calibrations and the reruns.
# Usage: bash scripts/depth_sigma_monte_carlo.sh OUT_DIR [FRAME_SEEDS] [POSE_SEEDS]   (default 20 and 10)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
rfrecon=${RFRECON:-$root/build/rfrecon}
out=$1
frame_seeds=${2:-20}
pose_seeds=${3:-10}
mkdir -p "$out/calib"
if [[ ! -f $out/calib/poses.json ]]; then  # the built-in scene as a file, its poses to move
  "$rfrecon" -q simulate --scene checkerboard-poses -o "$out/calib/base" --force >/dev/null
  cp "$out/calib/base/scene.json" "$out/calib/poses.json"
  rm -rf "$out/calib/base"
fi
for seed in $(seq 1 "$pose_seeds"); do
  d=$out/calib/seed_$seed
  [[ -f $d/rig.yaml ]] && continue
  mkdir -p "$d"
  python3 - "$out/calib/poses.json" "$d/scene.json" "$seed" <<'PY'
import json, sys
import numpy as np
scene = json.load(open(sys.argv[1]))
rng = np.random.default_rng(int(sys.argv[3]))
for view in scene["views"]:
    board = view["board"]
    board["position"] = list(np.array(board["position"]) + rng.uniform(-1, 1, 3) * [15, 15, 30])
    a = np.radians(rng.uniform(-4, 4, 3))
    rx = np.array([[1, 0, 0], [0, np.cos(a[0]), -np.sin(a[0])], [0, np.sin(a[0]), np.cos(a[0])]])
    ry = np.array([[np.cos(a[1]), 0, np.sin(a[1])], [0, 1, 0], [-np.sin(a[1]), 0, np.cos(a[1])]])
    rz = np.array([[np.cos(a[2]), -np.sin(a[2]), 0], [np.sin(a[2]), np.cos(a[2]), 0], [0, 0, 1]])
    board["rotation_matrix"] = list((rz @ ry @ rx @ np.array(board["rotation_matrix"]).reshape(3, 3)).ravel())
json.dump(scene, open(sys.argv[2], "w"), indent=1)
PY
  "$rfrecon" -q simulate --scene "$d/scene.json" --seed "$seed" -o "$d/poses" --force >/dev/null
  "$rfrecon" -q calibrate "$d"/poses/capture/pose_* --board 14x9 --square 20 -o "$d/rig.yaml" --force > "$d/calibrate.txt"
  rm -rf "$d/poses/capture"
done
for scene in cube-anisotropic board-plane; do
  for seed in $(seq 1 "$frame_seeds"); do
    d=$out/$scene/s$seed
    if [[ ! -f $d/fused/points.ply ]]; then
      "$rfrecon" -q simulate --scene "$scene" --seed "$seed" -o "$d" --force >/dev/null
      "$rfrecon" -q transport "$d/capture" -o "$d/T.h5" --force >/dev/null
      for method in triangulate integrate fused; do  # the triangulation's sigma has a closed form: no samples
        "$rfrecon" -q reconstruct "$d/T.h5" --calib "$d/truth/rig.yaml" --method "$method" --sigma-samples 8 \
          -o "$d/$method" --force >/dev/null
      done
      ((seed == 1)) || rm -rf "$d/capture" "$d/T.h5"  # seed 1's T.h5 serves the calibrations
    fi
  done
  for method in triangulate integrate fused; do
    dirs=()
    for seed in $(seq 1 "$frame_seeds"); do dirs+=("$out/$scene/s$seed/$method"); done
    printf '{"scene": "%s", "method": "%s", "part": "observation", "spread": %s}\n' "$scene" "$method" \
      "$(python3 "$root/scripts/depth_sigma_spread.py" --json --sigma depth_sigma_observation "${dirs[@]}")"
  done
  for method in triangulate integrate fused; do
    dirs=()
    for seed in $(seq 1 "$pose_seeds"); do
      r=$out/$scene/calib_${seed}_$method
      [[ -f $r/points.ply ]] || "$rfrecon" -q reconstruct "$out/$scene/s1/T.h5" --calib "$out/calib/seed_$seed/rig.yaml" \
        --method "$method" --sigma-samples 8 -o "$r" --force >/dev/null
      dirs+=("$r")
    done
    printf '{"scene": "%s", "method": "%s", "part": "calibration", "spread": %s}\n' "$scene" "$method" \
      "$(python3 "$root/scripts/depth_sigma_spread.py" --json --sigma depth_sigma_calibration "${dirs[@]}")"
  done
done
