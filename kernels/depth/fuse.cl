// Fusion of triangulated positions and reciprocity slopes on rectified rows (kernels/depth/row_fusion.h), over the
// row tile [first_row, first_row + rows). z holds the starting depth on entry (the integrated rows) and the fused
// depth on return. Layout as in integrate.cl.
//   fuse_rows_ndrange: one work-item per RF_LANES rows, as integrate_rows_ndrange; c and d are their scratch (Thomas
//                      algorithm), of z's size and layout.
//   fuse_rows_single:  one work-item; RF_FUSE_INTERLEAVE rows at a time in on-chip buffers (scratch included), their
//                      pixels interleaved in each sweep (kernels/depth/row_interleave.h); rows of at most
//                      RF_MAX_ROW_WIDTH.
#include "common/target.h"
#include "depth/row_fusion.h"
#include "depth/row_interleave.h"

// Same arithmetic as the C++ reference: no fused multiply-add contraction.
#pragma OPENCL FP_CONTRACT OFF

#if RF_NDRANGE_ENTRIES
__kernel void fuse_rows_ndrange(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows,
                                int width, int proj_width, int iterations, float sigma_disparity_px,
                                float sigma_step_mm, __global const float* restrict e_cam,
                                __global const float* restrict e_proj, __global const float* restrict z_tri,
                                __global const uchar* restrict runs, __global float* restrict z,
                                __global float* restrict c, __global float* restrict d) {
  // The host launches rows / RF_LANES work-items, the tile padded with masked rows to whole groups of lanes.
  (void)rows;
  const int group = (int)get_global_id(0);
  const RfRectifiedRig rig = {f, cx_cam, cx_proj, cy, b};
  const int8 row = (int8)(first_row + group * RF_LANES) + (int8)(0, 1, 2, 3, 4, 5, 6, 7);
  const float8 beta = (convert_float8(row) - cy) / f;
  const size_t at = (size_t)group * RF_LANES * (size_t)width;
  RF_LANES_FN(rf_fuse_row)
  (rig, beta, width, proj_width, iterations, rf_fusion_weights(rig, sigma_disparity_px, sigma_step_mm), e_cam + at,
   e_proj + (size_t)group * RF_LANES * (size_t)proj_width, z_tri + at, runs + at, z + at, c + at, d + at);
}
#endif

RF_SINGLE_TASK
__kernel void fuse_rows_single(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows,
                               int width, int proj_width, int iterations, float sigma_disparity_px, float sigma_step_mm,
                               __global const float* restrict e_cam, __global const float* restrict e_proj,
                               __global const float* restrict z_tri, __global const uchar* restrict runs,
                               __global float* restrict z) {
  const RfRectifiedRig rig = {f, cx_cam, cx_proj, cy, b};
  rf_fuse_rows_interleaved(rig, first_row, rows, width, proj_width, iterations, sigma_disparity_px, sigma_step_mm,
                           e_cam, e_proj, z_tri, runs, z);
}
