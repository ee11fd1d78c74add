// HLS C++ tops of the phase-shifting decoding (Vitis 2023.1 and later): the bodies of phase_steps_single,
// phase_fold_single, phase_beat_single and phase_finalize_single (kernels/transport/phase_decode.h) behind AXI4 masters
// for the buffers, AXI4-Lite for the rest. The order codes go through gray_pairs_single (decode_tops.cpp).
#define RF_TARGET_HLS  // kernels/common/target.h: the HLS directives

#include "hls/hls_top.h"
#include "hls/transport_tops.h"
#include "transport/phase_decode.h"

extern "C" void phase_steps_single(const RfFrameSamples* frames, int axis, int step_count, const float* shifts,
                                   float* sums, unsigned n) {
  RF_HLS_M_AXI(frames, gmem0)
  RF_HLS_M_AXI(shifts, gmem1)
  RF_HLS_M_AXI(sums, gmem2)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_phase_steps_pixels(n, axis, step_count, shifts, frames, sums);
}

extern "C" void phase_fold_single(int axis, float period, int coarsest, float middle, int steps, float white_threshold,
                                  float* sums, float* estimates, unsigned char* flags, unsigned n) {
  RF_HLS_M_AXI(sums, gmem0)
  RF_HLS_M_AXI(estimates, gmem1)
  RF_HLS_M_AXI(flags, gmem2)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_phase_fold_pixels(n, axis, period, coarsest, middle, steps, white_threshold, sums, estimates, flags);
}

extern "C" void phase_beat_single(int axis, int level, int f0, int f1, int f2, float axis_pixels, int steps,
                                  float white_threshold, float* sums, float* estimates, unsigned char* flags,
                                  unsigned n) {
  RF_HLS_M_AXI(sums, gmem0)
  RF_HLS_M_AXI(estimates, gmem1)
  RF_HLS_M_AXI(flags, gmem2)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_phase_beat_pixels(n, axis, level, f0, f1, f2, axis_pixels, steps, white_threshold, sums, estimates, flags);
}

extern "C" void phase_finalize_single(const float* white, const float* black, float black_threshold,
                                      float white_threshold, int steps, float period_x, float period_y, int by_order,
                                      int projector_width, int projector_height, int entries_per_pixel,
                                      unsigned* code_x, unsigned* code_y, const float* sums, const float* estimates,
                                      unsigned char* flags, int* indices, float* weights, float* energy,
                                      float* correspondence, unsigned n) {
  RF_HLS_M_AXI(white, gmem0)
  RF_HLS_M_AXI(black, gmem1)
  RF_HLS_M_AXI(code_x, gmem2)
  RF_HLS_M_AXI(code_y, gmem3)
  RF_HLS_M_AXI(sums, gmem4)
  RF_HLS_M_AXI(estimates, gmem5)
  RF_HLS_M_AXI(flags, gmem6)
  RF_HLS_M_AXI(indices, gmem7)
  RF_HLS_M_AXI(weights, gmem8)
  RF_HLS_M_AXI(energy, gmem9)
  RF_HLS_M_AXI(correspondence, gmem10)
#pragma HLS INTERFACE mode = s_axilite port = return
  rf_phase_finalize_pixels(n, white, black, black_threshold, white_threshold, steps, period_x, period_y, by_order,
                           projector_width, projector_height, entries_per_pixel, code_x, code_y, sums, estimates, flags,
                           indices, weights, energy, correspondence);
}
