#!/usr/bin/env bash
# The scan on a machine with a GPU: pipeline_bench on the GPU's OpenCL platform alone, on PoCL's CPU device alone and
# on both (the scheduler's split), then sched_bench on both; JSON and console output into OUT. Builds build/ first
# when it lacks the benchmarks (docs/building.md). A few minutes in all. docs/performance.md.
# Usage: bash scripts/gpu_bench.sh OUT
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: gpu_bench.sh OUT}
mkdir -p "$out"
if [[ ! -x build/bench/pipeline_bench ]]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON >/dev/null
  cmake --build build -j"$(nproc)" --target pipeline_bench sched_bench rfrecon_cli
fi
build/rfrecon devices | tee "$out/devices.txt"
scan="$out/scan"  # rendered once (about 40 s on 2 cores), reused by every run
for selection in gpu cpu gpu,cpu; do
  echo "== pipeline_bench on $selection"
  RFRECON_DEVICES=$selection build/bench/pipeline_bench --scan="$scan" \
    --benchmark_out="$out/pipeline_${selection/,/_}.json" --benchmark_out_format=json 2>&1 |
    grep -v "^\[.*\] \[info\]" | tee "$out/pipeline_${selection/,/_}.txt"
done
echo "== sched_bench on gpu,cpu (its \"2 devices\" are the GPU and PoCL's one CPU device)"
POCL_DEVICES=pthread RFRECON_DEVICES=gpu,cpu build/bench/sched_bench --benchmark_out="$out/sched.json" --benchmark_out_format=json 2>&1 |
  tee "$out/sched.txt"
rm -rf "$scan"
