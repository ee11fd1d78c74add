// Sparse products with the compressed light transport T (camera pixels x projector pixels).
// Primal  i_c = T L_p: one work-item per camera pixel sums its K ELL entries.
// Dual    i_p = T^T L_c: one work-item per projector pixel gathers over T's transpose in CSR form (row pointer per
// projector pixel, camera pixel and weight per entry), built on the host by a counting sort
// (host/transport/spmv.h). Every output has a single writer, so no float atomics are needed. The single work-item
// dual is one flattened loop (below); the single work-item primal still loops over k_per_row per pixel (its unroll to
// RF_K waits for K in the kernels' parameters header, docs/fpga.md).
#include "common/target.h"

// Exact agreement with the C++ reference: no fused multiply-add contraction.
#pragma OPENCL FP_CONTRACT OFF

inline float primal_pixel(uint c, uint k_per_row, __global const int* restrict indices,
                          __global const float* restrict weights, __global const float* restrict light) {
  float sum = 0.0f;
  for (uint k = 0; k < k_per_row; ++k) {
    const int q = indices[(size_t)c * k_per_row + k];
    if (q >= 0) sum += weights[(size_t)c * k_per_row + k] * light[q];
  }
  return sum;
}

__kernel void primal_ndrange(uint k_per_row, __global const int* restrict indices,
                             __global const float* restrict weights, __global const float* restrict light,
                             __global float* restrict image, uint n) {
  const uint c = get_global_id(0);
  if (c < n) image[c] = primal_pixel(c, k_per_row, indices, weights, light);
}

RF_SINGLE_TASK
__kernel void primal_single(uint k_per_row, __global const int* restrict indices,
                            __global const float* restrict weights, __global const float* restrict light,
                            __global float* restrict image, uint n) {
  RF_PIPELINE_II(1)
  for (uint c = 0; c < n; ++c) image[c] = primal_pixel(c, k_per_row, indices, weights, light);
}

inline float dual_pixel(uint p, __global const int* restrict row_start, __global const int* restrict camera_pixel,
                        __global const float* restrict weights, __global const float* restrict light) {
  float sum = 0.0f;
  for (int j = row_start[p]; j < row_start[p + 1]; ++j) sum += weights[j] * light[camera_pixel[j]];
  return sum;
}

__kernel void dual_ndrange(__global const int* restrict row_start, __global const int* restrict camera_pixel,
                           __global const float* restrict weights, __global const float* restrict light,
                           __global float* restrict image, uint n) {
  const uint p = get_global_id(0);
  if (p < n) image[p] = dual_pixel(p, row_start, camera_pixel, weights, light);
}

// One flattened loop over the entries and the rows: each iteration either adds an entry to the current row's sum or
// writes that row and moves to the next, so the trip count (entries + n) is fixed at entry and no loop depends on a
// row's length. The entries are summed in the same order as dual_pixel's, so the result is the same to the bit.
RF_SINGLE_TASK
__kernel void dual_single(__global const int* restrict row_start, __global const int* restrict camera_pixel,
                          __global const float* restrict weights, __global const float* restrict light,
                          __global float* restrict image, uint n) {
  const int entries = row_start[n] - row_start[0];
  int j = row_start[0], row_end = row_start[1 < n ? 1 : n];
  uint p = 0;
  float sum = 0.0f;
  RF_PIPELINE_II(1)
  for (int i = 0; i < (int)n + entries; ++i) {
    if (j < row_end) {
      sum += weights[j] * light[camera_pixel[j]];
      ++j;
    } else {
      image[p] = sum;
      sum = 0.0f;
      ++p;
      row_end = row_start[p < n ? p + 1 : n];
    }
  }
}
