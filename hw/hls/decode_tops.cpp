// HLS C++ tops of the Gray code decoding (Vitis 2023.1 and later): the bodies of gray_pairs_single and
// gray_finalize_single (kernels/transport/gray_decode.h) behind AXI4 masters for the buffers, AXI4-Lite for the rest.
#define RF_TARGET_HLS  // kernels/common/target.h: the HLS directives

#include "hls/hls_top.h"
#include "hls/transport_tops.h"
#include "transport/gray_decode.h"

extern "C" void gray_pairs_single(const RfFrameSamples* frames, int pair_count, const unsigned* pairs,
                                  float white_threshold, unsigned* code_x, unsigned* code_y, unsigned char* flags,
                                  unsigned n) {
  RF_HLS_M_AXI(frames, gmem0)
  RF_HLS_M_AXI(pairs, gmem1)
  RF_HLS_M_AXI(code_x, gmem2)
  RF_HLS_M_AXI(code_y, gmem3)
  RF_HLS_M_AXI(flags, gmem4)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_gray_pairs_pixels(n, pair_count, pairs, white_threshold, frames, code_x, code_y, flags);
}

extern "C" void gray_finalize_single(const float* white, const float* black, float black_threshold, int projector_width,
                                     int projector_height, unsigned* code_x, unsigned* code_y, unsigned char* flags,
                                     unsigned n) {
  RF_HLS_M_AXI(white, gmem0)
  RF_HLS_M_AXI(black, gmem1)
  RF_HLS_M_AXI(code_x, gmem2)
  RF_HLS_M_AXI(code_y, gmem3)
  RF_HLS_M_AXI(flags, gmem4)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_gray_finalize_pixels(n, white, black, black_threshold, projector_width, projector_height, code_x, code_y, flags);
}
