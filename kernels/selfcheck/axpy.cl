// Self-check kernel: y = a * x + y, used by `rfrecon selfcheck` and the runtime tests.
// Shows the project's kernel shape: one body (selfcheck/axpy.h), an NDRange entry and a single work-item (FPGA) entry.
#include "common/target.h"
#include "selfcheck/axpy.h"

#if RF_NDRANGE_ENTRIES
__kernel void axpy_ndrange(float a, __global const float* restrict x, __global float* restrict y, uint n) {
  const uint i = get_global_id(0);
  if (i < n) y[i] = rf_axpy_element(a, x[i], y[i]);
}
#endif

RF_SINGLE_TASK
__kernel void axpy_single(float a, __global const float* restrict x, __global float* restrict y, uint n) {
  rf_axpy_elements(n, a, x, y);
}
