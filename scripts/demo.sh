#!/usr/bin/env bash
# The main job until `rfrecon demo` exists (issue 6): renders the built-in cube-anisotropic scene, builds its
# compressed light transport T with the OpenCL kernels, and writes the primal and dual images, into out/demo/.
# Pass --calibrate to also render the checkerboard poses and calibrate the rig from them (a few more minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/demo
rfrecon=build/rfrecon
mkdir -p "$out"
$rfrecon devices
$rfrecon simulate --scene cube-anisotropic --out "$out/cube" --force
$rfrecon transport "$out/cube/capture" -o "$out/cube/T.h5"
$rfrecon dual "$out/cube/T.h5" -o "$out/cube/dual.png"
$rfrecon dual "$out/cube/T.h5" --primal -o "$out/cube/primal.png"
if [[ "${1:-}" == "--calibrate" ]]; then
  $rfrecon simulate --scene checkerboard-poses --out "$out/poses" --force
  $rfrecon calibrate "$out"/poses/capture/pose_* --board 9x6 --square 30 -o "$out/poses/rig.yaml"
fi
echo "demo: outputs in $out/ (cube/T.h5, cube/dual.png, cube/primal.png, cube/truth/)"
