#!/usr/bin/env bash
# ctest opencv_graycode_plane: OpenCV's pipeline (opencv_graycode_reconstruct) on a Gray-code-only capture of a plane
# decodes most of it, and its depth error is the integer pixel's quantisation, centred: a mean signed error under 5 %
# of the RMS (a half-pixel slip in either device's convention biases it by about the RMS).
# Usage: opencv_graycode_test.sh RFRECON OPENCV_GRAYCODE_RECONSTRUCT SCRATCH_DIR
set -euo pipefail
rfrecon=$1
opencv=$2
dir=$3
rm -rf "$dir"
"$rfrecon" -q simulate --scene plane-lambert --camera 320x256 --projector 256x160 --dot-spacing 0 --seed 1 -o "$dir"
"$opencv" "$dir/capture" "$dir/truth/rig.yaml" "$dir/opencv"
"$rfrecon" -q evaluate "$dir/opencv" --truth "$dir" -o "$dir/evaluation.json" --error-map "$dir/error_map.png"
python3 - "$dir/evaluation.json" <<'PY'
import json, sys
o = json.load(open(sys.argv[1]))["object_pixels"]
error = o["depth_error_mm"]
print("coverage %.1f %%, depth error RMS %.3f mm, bias %.4f mm" % (o["coverage_percent"], error["rms"], error["bias"]))
assert o["coverage_percent"] > 50, "OpenCV decoded too little of the plane"
assert abs(error["bias"]) < 0.05 * error["rms"], "the depth error is not centred"
PY
rm -rf "$dir"
