// Reciprocity integration of rectified rows (kernels/depth/row_integration.h), over the row tile
// [first_row, first_row + rows). Buffers hold the tile's rows only: e_cam, z_tri, runs and z are rows x width,
// e_proj is rows x proj_width.
//   integrate_rows_ndrange: one work-item per RF_LANES rows, one per vector lane, in the interleaved layout of
//                           kernels/depth/row_lanes.h (the host interleaves them, padding the tile with masked rows).
//   integrate_rows_single:  one work-item; RF_INTEGRATE_INTERLEAVE rows at a time in on-chip buffers, advancing
//                           together one RK4 slope each in turn (kernels/depth/row_interleave.h), so that each slope
//                           depends on the one RF_INTEGRATE_INTERLEAVE loop iterations earlier; rows of at most
//                           RF_MAX_ROW_WIDTH.
#include "common/target.h"
#include "depth/row_integration.h"

// Same arithmetic as the C++ reference: no fused multiply-add contraction.
#pragma OPENCL FP_CONTRACT OFF

#include "common/params.h"
#include "depth/row_interleave.h"

#if RF_NDRANGE_ENTRIES
__kernel void integrate_rows_ndrange(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows,
                                     int width, int proj_width, int passes, __global const float* restrict e_cam,
                                     __global const float* restrict e_proj, __global const float* restrict z_tri,
                                     __global const uchar* restrict runs, __global float* restrict z) {
  // The host launches rows / RF_LANES work-items, the tile padded with masked rows to whole groups of lanes.
  (void)rows;
  const int group = (int)get_global_id(0);
  const RfRectifiedRig rig = {f, cx_cam, cx_proj, cy, b};
  const int8 row = (int8)(first_row + group * RF_LANES) + (int8)(0, 1, 2, 3, 4, 5, 6, 7);
  const float8 beta = (convert_float8(row) - cy) / f;
  const size_t at = (size_t)group * RF_LANES * (size_t)width;
  RF_LANES_FN(rf_integrate_row)
  (rig, beta, width, proj_width, passes, e_cam + at, e_proj + (size_t)group * RF_LANES * (size_t)proj_width, z_tri + at,
   runs + at, z + at);
}
#endif

RF_SINGLE_TASK
__kernel void integrate_rows_single(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows,
                                    int width, int proj_width, int passes, __global const float* restrict e_cam,
                                    __global const float* restrict e_proj, __global const float* restrict z_tri,
                                    __global const uchar* restrict runs, __global float* restrict z) {
  const RfRectifiedRig rig = {f, cx_cam, cx_proj, cy, b};
  rf_integrate_rows_interleaved(rig, first_row, rows, width, proj_width, passes, e_cam, e_proj, z_tri, runs, z);
}
