// Self-check kernel: y = a * x + y, used by `rfrecon selfcheck` and the runtime tests.
// Shows the project's kernel shape: one inline body, an NDRange entry and a single work-item (FPGA) entry.
#include "common/target.h"

inline float axpy_element(float a, float x, float y) { return fma(a, x, y); }

__kernel void axpy_ndrange(float a, __global const float* restrict x, __global float* restrict y, uint n) {
  const uint i = get_global_id(0);
  if (i < n) y[i] = axpy_element(a, x[i], y[i]);
}

RF_SINGLE_TASK
__kernel void axpy_single(float a, __global const float* restrict x, __global float* restrict y, uint n) {
  RF_PIPELINE_II(1)
  for (uint i = 0; i < n; ++i) y[i] = axpy_element(a, x[i], y[i]);
}
