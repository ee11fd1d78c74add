// Sparse products with the compressed light transport T (camera pixels x projector pixels), shared by
// kernels/transport/spmv.cl and the HLS C++ tops (hw/hls/).
// Primal  i_c = T L_p: each camera pixel sums its RF_K ELL entries (an unrolled loop, K fixed at build time).
// Dual    i_p = T^T L_c: each projector pixel gathers over T's transpose in CSR form (row pointer per projector
// pixel, camera pixel and weight per entry), built on the host by a counting sort (host/transport/spmv.h); the single
// work-item entry also takes each entry's row (host/transport/spmv.h's entry_rows). Every output has a single writer,
// so no float atomics are needed.
#ifndef RFRECON_KERNELS_TRANSPORT_SPARSE_PRODUCTS_H
#define RFRECON_KERNELS_TRANSPORT_SPARSE_PRODUCTS_H

#include "common/params.h"
#include "common/portable.h"
#include "common/target.h"

RF_INLINE float rf_primal_pixel(unsigned c, RF_GLOBAL const int* indices, RF_GLOBAL const float* weights,
                                RF_GLOBAL const float* light) {
  float sum = 0.0f;
  RF_UNROLL
  for (int k = 0; k < RF_K; ++k) {
    const int q = indices[(size_t)c * RF_K + k];
    if (q >= 0) sum += weights[(size_t)c * RF_K + k] * light[q];
  }
  return sum;
}

RF_INLINE void rf_primal_pixels(unsigned n, RF_GLOBAL const int* indices, RF_GLOBAL const float* weights,
                                RF_GLOBAL const float* light, RF_GLOBAL float* image) {
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE_II(RF_K)  // one AXI beat per ELL entry
    image[c] = rf_primal_pixel(c, indices, weights, light);
  }
}

RF_INLINE float rf_dual_pixel(unsigned p, RF_GLOBAL const int* row_start, RF_GLOBAL const int* camera_pixel,
                              RF_GLOBAL const float* weights, RF_GLOBAL const float* light) {
  float sum = 0.0f;
  for (int j = row_start[p]; j < row_start[p + 1]; ++j) sum += weights[j] * light[camera_pixel[j]];
  return sum;
}

// The single work-item dual: the rows first set to 0 (a row may have no entry), then one loop over the entries,
// row_start[0] to row_start[n] - 1, each entry's row (its projector pixel less the first's) streamed in entry_row, so
// that no iteration's control waits on a read of memory: a row's sum is written where the next entry's row differs
// (a CSR loop would wait, every row, on row_start[p + 1] to know whether the next iteration adds or writes). Each
// row's entries are summed in rf_dual_pixel's order from 0.0f: the same result to the bit.
RF_INLINE void rf_dual_entries(unsigned n, RF_GLOBAL const int* row_start, RF_GLOBAL const int* entry_row,
                               RF_GLOBAL const int* camera_pixel, RF_GLOBAL const float* weights,
                               RF_GLOBAL const float* light, RF_GLOBAL float* image) {
  RF_PIPELINE_II(1)
  for (unsigned p = 0; p < n; ++p) {
    RF_HLS_PIPELINE
    image[p] = 0.0f;
  }
  const int first = row_start[0], entries = row_start[n] - row_start[0];
  int row = -1;
  float sum = 0.0f;
  RF_PIPELINE_II(1)
  for (int j = 0; j < entries; ++j) {
    RF_HLS_PIPELINE
    const int q = entry_row[j];
    if (q != row && row >= 0) image[row] = sum;
    sum = (q != row ? 0.0f : sum) + weights[first + j] * light[camera_pixel[first + j]];
    row = q;
  }
  if (row >= 0) image[row] = sum;
}

#endif  // RFRECON_KERNELS_TRANSPORT_SPARSE_PRODUCTS_H
