// HLS C++ tops of the sparse products (Vitis 2023.1 and later): the bodies of primal_single and dual_single
// (kernels/transport/sparse_products.h) behind AXI4 masters for the buffers, AXI4-Lite for the rest.
#define RF_TARGET_HLS  // kernels/common/target.h: emit the HLS loop directives

#include "hls/transport_tops.h"
#include "transport/sparse_products.h"

extern "C" void primal_single(const int* indices, const float* weights, const float* light, float* image, unsigned n) {
#pragma HLS INTERFACE mode = m_axi port = indices offset = slave bundle = gmem0
#pragma HLS INTERFACE mode = m_axi port = weights offset = slave bundle = gmem1
#pragma HLS INTERFACE mode = m_axi port = light offset = slave bundle = gmem2
#pragma HLS INTERFACE mode = m_axi port = image offset = slave bundle = gmem3
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_primal_pixels(n, indices, weights, light, image);
}

extern "C" void dual_single(const int* row_start, const int* camera_pixel, const float* weights, const float* light,
                            float* image, unsigned n) {
#pragma HLS INTERFACE mode = m_axi port = row_start offset = slave bundle = gmem0
#pragma HLS INTERFACE mode = m_axi port = camera_pixel offset = slave bundle = gmem1
#pragma HLS INTERFACE mode = m_axi port = weights offset = slave bundle = gmem2
#pragma HLS INTERFACE mode = m_axi port = light offset = slave bundle = gmem3
#pragma HLS INTERFACE mode = m_axi port = image offset = slave bundle = gmem4
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_dual_pixels(n, row_start, camera_pixel, weights, light, image);
}
