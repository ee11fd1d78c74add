// Reciprocity integration of rectified rows (kernels/depth/row_integration.h), over the row tile
// [first_row, first_row + rows). Buffers hold the tile's rows only: e_cam, z_tri, runs and z are rows x width,
// e_proj is rows x proj_width.
//   integrate_rows_ndrange: one work-item per row.
//   integrate_rows_single:  one work-item; RF_ROW_INTERLEAVE rows advance together, one pixel each in turn, so the
//                           dependency of z(u + 1) on z(u) lies RF_ROW_INTERLEAVE loop iterations apart and an FPGA
//                           pipeline can start an iteration every clock.
#include "common/target.h"
#include "depth/row_integration.h"

// Same arithmetic as the C++ reference: no fused multiply-add contraction.
#pragma OPENCL FP_CONTRACT OFF

#ifndef RF_ROW_INTERLEAVE
#define RF_ROW_INTERLEAVE 8
#endif

__kernel void integrate_rows_ndrange(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows,
                                     int width, int proj_width, int passes, __global const float* restrict e_cam,
                                     __global const float* restrict e_proj, __global const float* restrict z_tri,
                                     __global const uchar* restrict runs, __global float* restrict z) {
  const int r = (int)get_global_id(0);
  if (r >= rows) return;
  const RfRectifiedRig rig = {f, cx_cam, cx_proj, cy, b};
  const float beta = ((float)(first_row + r) - cy) / f;
  const size_t row = (size_t)r * (size_t)width;
  rf_integrate_row(rig, beta, width, proj_width, passes, e_cam + row, e_proj + (size_t)r * (size_t)proj_width,
                   z_tri + row, runs + row, z + row);
}

RF_SINGLE_TASK
__kernel void integrate_rows_single(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows,
                                    int width, int proj_width, int passes, __global const float* restrict e_cam,
                                    __global const float* restrict e_proj, __global const float* restrict z_tri,
                                    __global const uchar* restrict runs, __global float* restrict z) {
  const RfRectifiedRig rig = {f, cx_cam, cx_proj, cy, b};
  for (int r0 = 0; r0 < rows; r0 += RF_ROW_INTERLEAVE) {
    for (int pass = 0; pass < passes; ++pass) {
      RfRunState states[RF_ROW_INTERLEAVE] RF_PARTITION_COMPLETE;
      for (int k = 0; k < RF_ROW_INTERLEAVE; ++k) rf_run_state_init(&states[k]);
      RF_IVDEP_SAFELEN(RF_ROW_INTERLEAVE)
      for (int i = 0; i < width * RF_ROW_INTERLEAVE; ++i) {
        const int u = i / RF_ROW_INTERLEAVE, k = i % RF_ROW_INTERLEAVE, r = r0 + k;
        if (r < rows) {
          const size_t row = (size_t)r * (size_t)width;
          const float beta = ((float)(first_row + r) - cy) / f;
          rf_integrate_pixel(rig, beta, u, proj_width, pass, passes, e_cam + row,
                             e_proj + (size_t)r * (size_t)proj_width, z_tri + row, runs + row, z + row, &states[k]);
        }
      }
      for (int k = 0; k < RF_ROW_INTERLEAVE && r0 + k < rows; ++k) {
        rf_close_run(&states[k], z + (size_t)(r0 + k) * (size_t)width, pass + 1 < passes);
      }
    }
  }
}
