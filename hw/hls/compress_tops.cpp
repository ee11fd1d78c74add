// HLS C++ tops of the transport compression (Vitis 2023.1 and later): the bodies of dot_frames_single and
// finalize_single (kernels/transport/compression.h) behind AXI4 masters for the buffers, AXI4-Lite for the rest.
#define RF_TARGET_HLS  // kernels/common/target.h: the HLS directives

#include "hls/hls_top.h"
#include "hls/transport_tops.h"
#include "transport/compression.h"

extern "C" void dot_frames_single(const RfFrameSamples* frames, int frame_count, const int* offsets, int spacing,
                                  int projector_width, int projector_height, float noise_threshold, const float* black,
                                  const unsigned char* flags, const unsigned* projector_x, const unsigned* projector_y,
                                  RfEllIndices* indices, RfEllWeights* weights, float* energy, unsigned n) {
  RF_HLS_M_AXI(frames, gmem0)
  RF_HLS_M_AXI(offsets, gmem1)
  RF_HLS_M_AXI(black, gmem2)
  RF_HLS_M_AXI(flags, gmem3)
  RF_HLS_M_AXI(projector_x, gmem4)
  RF_HLS_M_AXI(projector_y, gmem5)
  RF_HLS_M_AXI(indices, gmem6)
  RF_HLS_M_AXI(weights, gmem7)
  RF_HLS_M_AXI(energy, gmem8)
#pragma HLS INTERFACE mode = s_axilite port = return
  const RfDotGrid grid = {spacing, projector_width, projector_height, noise_threshold};
  rf_dot_frames_pixels(n, frame_count, offsets, grid, frames, black, flags, projector_x, projector_y, indices, weights,
                       energy);
}

extern "C" void finalize_single(const float* white, const float* black, int has_dots, int projector_width,
                                float noise_threshold, unsigned char* flags, const unsigned* projector_x,
                                const unsigned* projector_y, RfEllIndices* indices, RfEllWeights* weights,
                                float* energy, RfCorrespondence* correspondence, unsigned n) {
  RF_HLS_M_AXI(white, gmem0)
  RF_HLS_M_AXI(black, gmem1)
  RF_HLS_M_AXI(flags, gmem2)
  RF_HLS_M_AXI(projector_x, gmem3)
  RF_HLS_M_AXI(projector_y, gmem4)
  RF_HLS_M_AXI(indices, gmem5)
  RF_HLS_M_AXI(weights, gmem6)
  RF_HLS_M_AXI(energy, gmem7)
  RF_HLS_M_AXI(correspondence, gmem8)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_finalize_pixels(n, white, black, has_dots, projector_width, noise_threshold, flags, projector_x, projector_y,
                     indices, weights, energy, correspondence);
}
