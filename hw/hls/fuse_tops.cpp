// HLS C++ top of the fusion (Vitis 2023.1 and later): the body of fuse_rows_single (kernels/depth/row_interleave.h)
// behind AXI4 masters for the rows and AXI4-Lite for the scalars; the Thomas scratch is on chip.
#define RF_TARGET_HLS  // kernels/common/target.h: the HLS directives

#include "depth/row_interleave.h"
#include "hls/depth_tops.h"
#include "hls/hls_top.h"

extern "C" void fuse_rows_single(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows,
                                 int width, int proj_width, int iterations, float sigma_disparity_px,
                                 float sigma_step_mm, const float* e_cam, const float* e_proj, const float* z_tri,
                                 const unsigned char* runs, float* z) {
  RF_HLS_M_AXI(e_cam, gmem0)
  RF_HLS_M_AXI(e_proj, gmem1)
  RF_HLS_M_AXI(z_tri, gmem2)
  RF_HLS_M_AXI(runs, gmem3)
  RF_HLS_M_AXI(z, gmem4)
#pragma HLS INTERFACE mode = s_axilite port = return
  const RfRectifiedRig rig = {f, cx_cam, cx_proj, cy, b};
  rf_fuse_rows_interleaved(rig, first_row, rows, width, proj_width, iterations, sigma_disparity_px, sigma_step_mm,
                           e_cam, e_proj, z_tri, runs, z);
}
