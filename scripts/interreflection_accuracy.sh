#!/usr/bin/env bash
# Each depth method with and without one-bounce interreflection on the concave scenes (docs/accuracy.md,
# "Interreflection"): for each noise seed and scene, `rfrecon simulate` as built in (16 bounce rays per sample) and
# with --interreflection 0, then transport, reconstruct (triangulate, integrate, fused; true rig) and evaluate each face
# of the object: its coverage and its depth RMS on the pixels all three methods reconstruct. Prints
# "seed scene object bounce method coverage% rms_mm same_pixels_coverage%" per line (rms "nan" where none).
# Usage: bash scripts/interreflection_accuracy.sh [OUT_DIR] [SEEDS...]   (default out/interreflection, seeds 1 to 3)
set -euo pipefail
rfrecon=$(cd "$(dirname "$0")/.." && pwd)/build/rfrecon
out=${1:-out/interreflection}
shift || true
seeds=("$@")
if ((${#seeds[@]} == 0)); then seeds=(1 2 3); fi
mkdir -p "$out"
cd "$out"
declare -A faces=([v-groove-ward]="left face,right face" [corner-brushed]="face 1,face 2,face 3" [bowl-ward]="bowl")
methods=(triangulate integrate fused)
report() {
  python3 -c "import json, sys
o = json.load(open(sys.argv[1]))['object_pixels']
rms = o['depth_error_mm']['rms']
print('%.2f %s' % (o['coverage_percent'], 'nan' if rms is None else '%.4f' % rms))" "$1"
}
for seed in "${seeds[@]}"; do
  for scene in v-groove-ward corner-brushed bowl-ward; do
    for bounce in on off; do
      d=s${seed}_${scene}_$bounce
      extra=()
      [[ $bounce == off ]] && extra=(--interreflection 0)
      "$rfrecon" simulate --scene "$scene" "${extra[@]}" --seed "$seed" -o "$d" --force >/dev/null 2>&1
      "$rfrecon" transport "$d/capture" -o "$d/T.h5" --force >/dev/null 2>&1
      for m in "${methods[@]}"; do
        "$rfrecon" reconstruct "$d/T.h5" --calib "$d/truth/rig.yaml" --method "$m" -o "$d/$m" --force \
          >/dev/null 2>&1 || true  # a method that reconstructs nothing exits 6: its row says so
      done
      IFS=, read -r -a objects <<<"${faces[$scene]}"
      for object in "${objects[@]}"; do
        for m in "${methods[@]}"; do
          [[ -d $d/$m ]] || { echo "$seed $scene '$object' $bounce $m 0.00 nan 0.00"; continue; }
          others=()
          for o in "${methods[@]}"; do [[ $o != "$m" && -d $d/$o ]] && others+=("$d/$o"); done
          tag=${object// /_}
          "$rfrecon" evaluate "$d/$m" --truth "$d" --object "$object" -o "$d/$m.$tag.all.json" \
            --error-map "$d/$m.$tag.all.png" --force >/dev/null 2>&1
          "$rfrecon" evaluate "$d/$m" --truth "$d" --object "$object" --same-pixels-as "${others[@]}" \
            -o "$d/$m.$tag.same.json" --error-map "$d/$m.$tag.same.png" --force >/dev/null 2>&1
          read -r coverage _ < <(report "$d/$m.$tag.all.json")
          read -r same rms < <(report "$d/$m.$tag.same.json")
          echo "$seed $scene '$object' $bounce $m $coverage $rms $same"
        done
      done
    done
  done
done
