// Sparse products with the compressed light transport T (camera pixels x projector pixels), shared by
// kernels/transport/spmv.cl and the HLS C++ tops (hw/hls/).
// Primal  i_c = T L_p: each camera pixel sums its RF_K ELL entries (an unrolled loop, K fixed at build time).
// Dual    i_p = T^T L_c: each projector pixel gathers over T's transpose in CSR form (row pointer per projector
// pixel, camera pixel and weight per entry), built on the host by a counting sort (host/transport/spmv.h). Every
// output has a single writer, so no float atomics are needed.
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

// One flattened loop over the entries and the rows: each iteration either adds an entry to the current row's sum or
// writes that row and moves to the next, so the trip count (entries + n) is fixed at entry and no loop depends on a
// row's length. The entries are summed in the same order as rf_dual_pixel's, so the result is the same to the bit.
RF_INLINE void rf_dual_pixels(unsigned n, RF_GLOBAL const int* row_start, RF_GLOBAL const int* camera_pixel,
                              RF_GLOBAL const float* weights, RF_GLOBAL const float* light, RF_GLOBAL float* image) {
  const int entries = row_start[n] - row_start[0];
  int j = row_start[0];
  int row_end = row_start[1 < n ? 1 : n];
  unsigned p = 0;
  float sum = 0.0f;
  RF_PIPELINE_II(1)
  for (int i = 0; i < (int)n + entries; ++i) {
    RF_HLS_PIPELINE
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

#endif  // RFRECON_KERNELS_TRANSPORT_SPARSE_PRODUCTS_H
