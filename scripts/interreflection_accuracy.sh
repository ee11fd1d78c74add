#!/usr/bin/env bash
# Each depth method with and without one-bounce interreflection on the concave scenes (docs/accuracy.md,
# "Interreflection"): for each noise seed and scene, `rfrecon simulate` as built in (16 bounce rays per sample) and
# with --interreflection 0, then transport, reconstruct (triangulate, integrate, fused; true rig) and evaluate each face
# of the object: its coverage and its depth RMS on the pixels all three methods reconstruct. The same scene captured
# with Gray code alone (--dot-spacing 0) gives two more rows, each with its RMS on the pixels it and all three
# reconstruct: "gray-only", rfrecon's sub-pixel Gray decode triangulated, and "opencv-graycode", OpenCV's
# GrayCodePattern decode and cv::triangulatePoints (build/bench/opencv_graycode_reconstruct). Prints "seed scene object
# bounce method coverage% rms_mm same_pixels_coverage% own_rms_mm" per line (rms_mm on the compared pixels, own_rms_mm
# on all the method reconstructs; "nan" where none).
# Usage: bash scripts/interreflection_accuracy.sh [OUT_DIR] [SEEDS...]   (default out/interreflection, seeds 1 to 3)
set -euo pipefail
build=$(cd "$(dirname "$0")/.." && pwd)/build
rfrecon=$build/rfrecon
opencv=$build/bench/opencv_graycode_reconstruct
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
      if [[ ! -f $d/T.h5 ]]; then  # a rerun reuses the captures
        "$rfrecon" simulate --scene "$scene" "${extra[@]}" --seed "$seed" -o "$d" --force >/dev/null 2>&1
        "$rfrecon" transport "$d/capture" -o "$d/T.h5" --force >/dev/null 2>&1
      fi
      for m in "${methods[@]}"; do
        "$rfrecon" reconstruct "$d/T.h5" --calib "$d/truth/rig.yaml" --method "$m" -o "$d/$m" --force \
          >/dev/null 2>&1 || true  # a method that reconstructs nothing exits 6: its row says so
      done
      if [[ ! -f ${d}_gray/T.h5 ]]; then
        "$rfrecon" simulate --scene "$scene" "${extra[@]}" --dot-spacing 0 --seed "$seed" -o "${d}_gray" --force \
          >/dev/null 2>&1
        "$rfrecon" transport "${d}_gray/capture" -o "${d}_gray/T.h5" --force >/dev/null 2>&1
      fi
      "$rfrecon" reconstruct "${d}_gray/T.h5" --calib "$d/truth/rig.yaml" --method triangulate -o "$d/gray-only" \
        --force >/dev/null 2>&1 || true
      "$opencv" "${d}_gray/capture" "$d/truth/rig.yaml" "$d/opencv-graycode" --force >/dev/null 2>&1 || true
      rm -f "$d"/*.all.* "$d"/*.same.*  # a rerun's evaluations: evaluate refuses to overwrite files of its truth dir
      IFS=, read -r -a objects <<<"${faces[$scene]}"
      for object in "${objects[@]}"; do
        for m in "${methods[@]}" gray-only opencv-graycode; do
          [[ -d $d/$m ]] || { echo "$seed $scene '$object' $bounce $m 0.00 nan 0.00 nan"; continue; }
          others=()
          for o in "${methods[@]}"; do [[ $o != "$m" && -d $d/$o ]] && others+=("$d/$o"); done
          tag=${object// /_}
          "$rfrecon" evaluate "$d/$m" --truth "$d" --object "$object" -o "$d/$m.$tag.all.json" \
            --error-map "$d/$m.$tag.all.png" --force >/dev/null 2>&1
          "$rfrecon" evaluate "$d/$m" --truth "$d" --object "$object" --same-pixels-as "${others[@]}" \
            -o "$d/$m.$tag.same.json" --error-map "$d/$m.$tag.same.png" --force >/dev/null 2>&1
          read -r coverage own_rms < <(report "$d/$m.$tag.all.json")
          read -r same rms < <(report "$d/$m.$tag.same.json")
          echo "$seed $scene '$object' $bounce $m $coverage $rms $same $own_rms"
        done
      done
    done
  done
done
