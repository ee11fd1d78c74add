#!/usr/bin/env bash
# Leave-one-out on real Gray-code board captures (../shared/data/procam-graycode, docs/accuracy.md): for each pose,
# calibrates the rig from the other poses, reconstructs the pose with triangulation and measures its board with
# ../shared/tools/board_check.py (plane RMS, grid scale) with $PYTHON (default /usr/bin/python3, with Debian's
# python3-opencv and python3-numpy).
# Usage: scripts/procam_board_check.sh [DATA_DIR] [OUT_DIR] [reconstruct options...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data=${1:-$root/../shared/data/procam-graycode}
out=${2:-/tmp/procam-board-check}
shift $(($# < 2 ? $# : 2))
rfrecon=$root/build/rfrecon
check=$(dirname "$data")/../tools/board_check.py
capture=(--layout opencv-graycode --projector 1024x768)
poses=("$data"/capture_*)
mkdir -p "$out"
for pose in "${poses[@]}"; do
  name=$(basename "$pose")
  others=()
  for other in "${poses[@]}"; do [[ $other != "$pose" ]] && others+=("$other"); done
  "$rfrecon" transport "$pose" "${capture[@]}" -o "$out/$name.h5" --summary "$out/$name.transport.json" --force >/dev/null
  "$rfrecon" calibrate "${others[@]}" "${capture[@]}" --board 9x7 --square 75 -o "$out/$name.rig.yaml" --force \
    >"$out/$name.calibrate.log"
  "$rfrecon" reconstruct "$out/$name.h5" --calib "$out/$name.rig.yaml" --method triangulate -o "$out/$name" --force \
    "$@" >/dev/null
  echo "$name: $(grep -o 'stereo reprojection RMS [0-9.]* px' "$out/$name.calibrate.log" | head -1);" \
    "$("${PYTHON:-/usr/bin/python3}" "$check" "$out/$name" "$pose/graycode_40.png" "$out/$name.rig.yaml" 9 7 75)"
done
