// The HLS C++ top functions of the depth kernels for Vitis 2023.1 and later (integrate_tops.cpp,
// fuse_tops.cpp): the single work-item bodies of kernels/depth/row_interleave.h behind AXI interfaces, with the
// arguments and layout of kernels/depth/integrate.cl and fuse.cl. Declared here for their C simulation
// (tests/fpga/hls_csim_test.cc).
#pragma once

extern "C" {

void integrate_rows_single(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows, int width,
                           int proj_width, int passes, const float* e_cam, const float* e_proj, const float* z_tri,
                           const unsigned char* runs, float* z);

void fuse_rows_single(float f, float cx_cam, float cx_proj, float cy, float b, int first_row, int rows, int width,
                      int proj_width, int iterations, float sigma_disparity_px, float sigma_step_mm, const float* e_cam,
                      const float* e_proj, const float* z_tri, const unsigned char* runs, float* z);
}
