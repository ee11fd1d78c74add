// HLS C++ tops of the transport compression (Vitis 2023.1 and later): the bodies of dot_frames_single and
// finalize_single (kernels/transport/compression.h) behind AXI4 masters for the buffers, AXI4-Lite for the rest.
#define RF_TARGET_HLS  // kernels/common/target.h: emit the HLS loop directives

#include "hls/transport_tops.h"
#include "transport/compression.h"

extern "C" void dot_frames_single(const float* frames, int frame_count, const int* offsets, int spacing,
                                  int projector_width, int projector_height, float noise_threshold, const float* black,
                                  const unsigned char* flags, const unsigned* projector_x, const unsigned* projector_y,
                                  int* indices, float* weights, float* energy, unsigned n) {
#pragma HLS INTERFACE mode = m_axi port = frames offset = slave bundle = gmem0
#pragma HLS INTERFACE mode = m_axi port = offsets offset = slave bundle = gmem1
#pragma HLS INTERFACE mode = m_axi port = black offset = slave bundle = gmem2
#pragma HLS INTERFACE mode = m_axi port = flags offset = slave bundle = gmem3
#pragma HLS INTERFACE mode = m_axi port = projector_x offset = slave bundle = gmem4
#pragma HLS INTERFACE mode = m_axi port = projector_y offset = slave bundle = gmem5
#pragma HLS INTERFACE mode = m_axi port = indices offset = slave bundle = gmem6
#pragma HLS INTERFACE mode = m_axi port = weights offset = slave bundle = gmem7
#pragma HLS INTERFACE mode = m_axi port = energy offset = slave bundle = gmem8
#pragma HLS INTERFACE mode = s_axilite port = return
  const RfDotGrid grid = {spacing, projector_width, projector_height, noise_threshold};
  rf_dot_frames_pixels(n, frame_count, offsets, grid, frames, black, flags, projector_x, projector_y, indices, weights,
                       energy);
}

extern "C" void finalize_single(const float* white, const float* black, int has_dots, int projector_width,
                                float noise_threshold, unsigned char* flags, const unsigned* projector_x,
                                const unsigned* projector_y, int* indices, float* weights, float* energy,
                                float* correspondence, unsigned n) {
#pragma HLS INTERFACE mode = m_axi port = white offset = slave bundle = gmem0
#pragma HLS INTERFACE mode = m_axi port = black offset = slave bundle = gmem1
#pragma HLS INTERFACE mode = m_axi port = flags offset = slave bundle = gmem2
#pragma HLS INTERFACE mode = m_axi port = projector_x offset = slave bundle = gmem3
#pragma HLS INTERFACE mode = m_axi port = projector_y offset = slave bundle = gmem4
#pragma HLS INTERFACE mode = m_axi port = indices offset = slave bundle = gmem5
#pragma HLS INTERFACE mode = m_axi port = weights offset = slave bundle = gmem6
#pragma HLS INTERFACE mode = m_axi port = energy offset = slave bundle = gmem7
#pragma HLS INTERFACE mode = m_axi port = correspondence offset = slave bundle = gmem8
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_finalize_pixels(n, white, black, has_dots, projector_width, noise_threshold, flags, projector_x, projector_y,
                     indices, weights, energy, correspondence);
}
