// HLS C++ tops of the Gray code decoding (Vitis 2023.1 and later): the bodies of gray_pairs_single and
// gray_finalize_single (kernels/transport/gray_decode.h) behind AXI4 masters for the buffers, AXI4-Lite for the rest.
#define RF_TARGET_HLS  // kernels/common/target.h: emit the HLS loop directives

#include "hls/transport_tops.h"
#include "transport/gray_decode.h"

extern "C" void gray_pairs_single(const float* frames, int pair_count, const unsigned* pairs, float white_threshold,
                                  unsigned* code_x, unsigned* code_y, unsigned char* flags, unsigned n) {
#pragma HLS INTERFACE mode = m_axi port = frames offset = slave bundle = gmem0
#pragma HLS INTERFACE mode = m_axi port = pairs offset = slave bundle = gmem1
#pragma HLS INTERFACE mode = m_axi port = code_x offset = slave bundle = gmem2
#pragma HLS INTERFACE mode = m_axi port = code_y offset = slave bundle = gmem3
#pragma HLS INTERFACE mode = m_axi port = flags offset = slave bundle = gmem4
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_gray_pairs_pixels(n, pair_count, pairs, white_threshold, frames, code_x, code_y, flags);
}

extern "C" void gray_finalize_single(const float* white, const float* black, float black_threshold, int projector_width,
                                     int projector_height, unsigned* code_x, unsigned* code_y, unsigned char* flags,
                                     unsigned n) {
#pragma HLS INTERFACE mode = m_axi port = white offset = slave bundle = gmem0
#pragma HLS INTERFACE mode = m_axi port = black offset = slave bundle = gmem1
#pragma HLS INTERFACE mode = m_axi port = code_x offset = slave bundle = gmem2
#pragma HLS INTERFACE mode = m_axi port = code_y offset = slave bundle = gmem3
#pragma HLS INTERFACE mode = m_axi port = flags offset = slave bundle = gmem4
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_gray_finalize_pixels(n, white, black, black_threshold, projector_width, projector_height, code_x, code_y, flags);
}
