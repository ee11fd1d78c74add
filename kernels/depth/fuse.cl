// Fusion of triangulated positions and reciprocity slopes on rectified rows (kernels/depth/row_fusion.h), over the
// row tile [first_row, first_row + rows). z holds the starting depth on entry (the integrated rows) and the fused
// depth on return. Layout as in integrate.cl.
//   fuse_rows_ndrange: one work-item per row; c and d are its scratch (Thomas algorithm), of z's size.
//   fuse_rows_single:  one work-item; RF_FUSE_INTERLEAVE rows at a time in on-chip buffers (scratch included), their
//                      pixels interleaved in each sweep (kernels/depth/row_interleave.h); rows of at most
//                      RF_MAX_ROW_WIDTH.
#include "common/target.h"
#include "depth/row_fusion.h"
#include "depth/row_interleave.h"

// Same arithmetic as the C++ reference: no fused multiply-add contraction.
#pragma OPENCL FP_CONTRACT OFF

__kernel void fuse_rows_ndrange(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows,
                                int width, int proj_width, int iterations, float sigma_disparity_px,
                                float sigma_step_mm, __global const float* restrict e_cam,
                                __global const float* restrict e_proj, __global const float* restrict z_tri,
                                __global const uchar* restrict runs, __global float* restrict z,
                                __global float* restrict c, __global float* restrict d) {
  const int r = (int)get_global_id(0);
  if (r >= rows) return;
  const RfRectifiedRig rig = {f, cx_cam, cx_proj, cy, b};
  const float beta = ((float)(first_row + r) - cy) / f;
  const size_t row = (size_t)r * (size_t)width;
  rf_fuse_row(rig, beta, width, proj_width, iterations, sigma_disparity_px, sigma_step_mm, e_cam + row,
              e_proj + (size_t)r * (size_t)proj_width, z_tri + row, runs + row, z + row, c + row, d + row);
}

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
