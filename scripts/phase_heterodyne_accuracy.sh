#!/usr/bin/env bash
# Heterodyne beats against the order code on the cube (docs/accuracy.md, "Heterodyne beats"): for each noise seed,
# `rfrecon simulate` of cube-anisotropic with the phase family unwrapped by the half-period Gray code at periods 16 and
# 8, and by the beats of 64, 58 and 53 fringes; then transport, reconstruct (triangulate, true rig) and evaluate: each
# capture's coverage of the object, and its depth RMS on the pixels all three reconstruct. Prints
# "seed capture coverage% rms_mm same_pixels_coverage%" per line.
# Usage: bash scripts/phase_heterodyne_accuracy.sh [OUT_DIR] [SEEDS...]   (default out/heterodyne, seeds 1 to 3)
set -euo pipefail
rfrecon=$(cd "$(dirname "$0")/.." && pwd)/build/rfrecon
out=${1:-out/heterodyne}
shift || true
seeds=("$@")
if ((${#seeds[@]} == 0)); then seeds=(1 2 3); fi
mkdir -p "$out"
cd "$out"
declare -A options=([order16]="--phase-period 16" [order8]="--phase-period 8"
  [beats64]="--phase-fringes 64 --phase-heterodyne 6")
names=(order16 order8 beats64)
field() { python3 -c "import json, sys; o = json.load(open(sys.argv[1]))['object_pixels']; print(o[sys.argv[2]])" "$@"; }
for seed in "${seeds[@]}"; do
  for n in "${names[@]}"; do
    d=s${seed}_$n
    # shellcheck disable=SC2086  # the options are words
    "$rfrecon" simulate --scene cube-anisotropic --family phase ${options[$n]} --dot-spacing 0 --seed "$seed" \
      -o "$d" --force >/dev/null 2>&1
    "$rfrecon" transport "$d/capture" -o "$d/T.h5" --force >/dev/null 2>&1
    "$rfrecon" reconstruct "$d/T.h5" --calib "$d/truth/rig.yaml" --method triangulate -o "$d/tri" --force \
      >/dev/null 2>&1
  done
  for n in "${names[@]}"; do
    d=s${seed}_$n
    others=()
    for o in "${names[@]}"; do [[ $o != "$n" ]] && others+=("s${seed}_$o/tri"); done
    "$rfrecon" evaluate "$d/tri" --truth "$d" -o "$d/all.json" --error-map "$d/all.png" --force >/dev/null 2>&1
    "$rfrecon" evaluate "$d/tri" --truth "$d" --same-pixels-as "${others[@]}" -o "$d/same.json" \
      --error-map "$d/same.png" --force >/dev/null 2>&1
    coverage=$(field "$d/all.json" coverage_percent)
    same_coverage=$(field "$d/same.json" coverage_percent)
    rms=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['object_pixels']['depth_error_mm']['rms'])" \
      "$d/same.json")
    printf '%s %s %.2f %.4f %.2f\n' "$seed" "$n" "$coverage" "$rms" "$same_coverage"
  done
done
