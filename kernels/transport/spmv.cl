// Sparse products with the compressed light transport T (bodies in transport/sparse_products.h): primal_* = T L_p
// over the ELL rows (K = RF_K entries per camera pixel), dual_* = T^T L_c over T's transpose in CSR form.
#include "common/target.h"

// Exact agreement with the C++ reference: no fused multiply-add contraction.
#pragma OPENCL FP_CONTRACT OFF
#include "transport/sparse_products.h"

#if RF_NDRANGE_ENTRIES
__kernel void primal_ndrange(__global const int* restrict indices, __global const float* restrict weights,
                             __global const float* restrict light, __global float* restrict image, uint n) {
  const uint c = get_global_id(0);
  if (c < n) image[c] = rf_primal_pixel(c, indices, weights, light);
}
#endif

RF_SINGLE_TASK
__kernel void primal_single(__global const int* restrict indices, __global const float* restrict weights,
                            __global const float* restrict light, __global float* restrict image, uint n) {
  rf_primal_pixels(n, indices, weights, light, image);
}

#if RF_NDRANGE_ENTRIES
__kernel void dual_ndrange(__global const int* restrict row_start, __global const int* restrict camera_pixel,
                           __global const float* restrict weights, __global const float* restrict light,
                           __global float* restrict image, uint n) {
  const uint p = get_global_id(0);
  if (p < n) image[p] = rf_dual_pixel(p, row_start, camera_pixel, weights, light);
}
#endif

RF_SINGLE_TASK
__kernel void dual_single(__global const int* restrict row_start, __global const int* restrict entry_row,
                          __global const int* restrict camera_pixel, __global const float* restrict weights,
                          __global const float* restrict light, __global float* restrict image, uint n) {
  rf_dual_entries(n, row_start, entry_row, camera_pixel, weights, light, image);
}
