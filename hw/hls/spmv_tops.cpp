// HLS C++ tops of the sparse products (Vitis 2023.1 and later): the bodies of primal_single and dual_single
// (kernels/transport/sparse_products.h) behind AXI4 masters for the buffers, AXI4-Lite for the rest.
#define RF_TARGET_HLS  // kernels/common/target.h: the HLS directives

#include "hls/hls_top.h"
#include "hls/transport_tops.h"
#include "transport/sparse_products.h"

extern "C" void primal_single(const int* indices, const float* weights, const float* light, float* image, unsigned n) {
  RF_HLS_M_AXI(indices, gmem0)
  RF_HLS_M_AXI(weights, gmem1)
  RF_HLS_M_AXI(light, gmem2)
  RF_HLS_M_AXI(image, gmem3)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_primal_pixels(n, indices, weights, light, image);
}

extern "C" void dual_single(const int* row_start, const int* entry_row, const int* camera_pixel, const float* weights,
                            const float* light, float* image, unsigned n) {
  RF_HLS_M_AXI(row_start, gmem0)
  RF_HLS_M_AXI(entry_row, gmem5)
  RF_HLS_M_AXI(camera_pixel, gmem1)
  RF_HLS_M_AXI(weights, gmem2)
  RF_HLS_M_AXI(light, gmem3)
  RF_HLS_M_AXI(image, gmem4)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_dual_entries(n, row_start, entry_row, camera_pixel, weights, light, image);
}
