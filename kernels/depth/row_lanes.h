// RF_LANES rows side by side, one per vector lane (common/lanes.h), for the NDRange entries of the depth kernels: a
// work-item solves RF_LANES rows at once, so that the CPU's vector units evaluate their ODE slopes together
// (docs/performance.md, "Row solvers"). Layout of a group of RF_LANES rows: element u of lane l at [u * RF_LANES + l];
// the host interleaves the rows so (host/depth/row_solvers.cc). The gathers and masked stores of the row functions.
#ifndef RFRECON_KERNELS_DEPTH_ROW_LANES_H
#define RFRECON_KERNELS_DEPTH_ROW_LANES_H

#include "common/lanes.h"
#include "common/portable.h"

#ifdef __OPENCL_VERSION__
// Element i[l] of every lane l.
RF_INLINE float8 rf_lanes_gather(__global const float* row, int8 i) {
  const int8 at = i * RF_LANES + (int8)(0, 1, 2, 3, 4, 5, 6, 7);
  return (float8)(row[at.s0], row[at.s1], row[at.s2], row[at.s3], row[at.s4], row[at.s5], row[at.s6], row[at.s7]);
}

// value[l] to element i[l] of every lane l whose mask is set.
RF_INLINE void rf_lanes_store_if(__global float* row, int8 mask, int8 i, float8 value) {
  const int8 at = i * RF_LANES + (int8)(0, 1, 2, 3, 4, 5, 6, 7);
  if (mask.s0) row[at.s0] = value.s0;
  if (mask.s1) row[at.s1] = value.s1;
  if (mask.s2) row[at.s2] = value.s2;
  if (mask.s3) row[at.s3] = value.s3;
  if (mask.s4) row[at.s4] = value.s4;
  if (mask.s5) row[at.s5] = value.s5;
  if (mask.s6) row[at.s6] = value.s6;
  if (mask.s7) row[at.s7] = value.s7;
}
#endif

#endif  // RFRECON_KERNELS_DEPTH_ROW_LANES_H
