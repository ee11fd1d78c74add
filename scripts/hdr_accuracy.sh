#!/usr/bin/env bash
# HDR against one exposure on the shiny Ward sphere (docs/accuracy.md, "HDR capture of a shiny sphere"): for each
# noise seed, `rfrecon capture` on the simulated rig at 10 ms, 40 ms and 10 + 40 ms merged, then transport,
# reconstruct (fused, true rig) and evaluate: each capture's coverage of the sphere, and its RMS depth error on the
# pixels all three reconstructed. Prints "seed exposures coverage% rms_um common_pixels" per line.
# Usage: bash scripts/hdr_accuracy.sh [OUT_DIR] [SEEDS...]   (default out/hdr, seeds 1 to 5)
set -euo pipefail
rfrecon=$(cd "$(dirname "$0")/.." && pwd)/build/rfrecon
out=${1:-out/hdr}
shift || true
seeds=("$@")
if ((${#seeds[@]} == 0)); then seeds=(1 2 3 4 5); fi
mkdir -p "$out"
cd "$out"
"$rfrecon" simulate --scene sphere-ward -o scene --force >/dev/null 2>&1
exposures=(10000 40000 10000,40000)
for seed in "${seeds[@]}"; do
  for e in "${exposures[@]}"; do
    n=s${seed}_${e/,/_}
    "$rfrecon" capture --camera sim:sphere-ward --seed "$seed" --exposures "$e" -o "$n.cap" --force >/dev/null 2>&1
    "$rfrecon" transport "$n.cap" -o "$n.h5" --force >/dev/null 2>&1
    "$rfrecon" reconstruct "$n.h5" --calib scene/truth/rig.yaml -o "$n.rec" --force >/dev/null 2>&1
  done
  for e in "${exposures[@]}"; do
    n=s${seed}_${e/,/_}
    others=()
    for o in "${exposures[@]}"; do [[ $o != "$e" ]] && others+=("s${seed}_${o/,/_}.rec"); done
    "$rfrecon" evaluate "$n.rec" --truth scene/truth -o "$n.all.json" --error-map "$n.all.png" --force >/dev/null 2>&1
    "$rfrecon" evaluate "$n.rec" --truth scene/truth --same-pixels-as "${others[@]}" -o "$n.same.json" \
      --error-map "$n.same.png" --force >/dev/null 2>&1
    python3 -c "
import json, sys
whole = json.load(open('$n.all.json'))['object_pixels']
same = json.load(open('$n.same.json'))['object_pixels']
print('$seed $e', round(whole['coverage_percent'], 2), round(same['depth_error_mm']['rms'] * 1000, 2),
      same['reconstructed_pixels'])"
  done
done
