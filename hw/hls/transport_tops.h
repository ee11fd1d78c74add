// The HLS C++ top functions of the transport kernels for Vitis 2023.1 and later (decode_tops.cpp, phase_tops.cpp,
// compress_tops.cpp, spmv_tops.cpp): the single work-item bodies of kernels/transport/gray_decode.h, phase_decode.h,
// compression.h and sparse_products.h behind AXI interfaces, with the arguments and layout of
// kernels/transport/decode.cl, phase.cl, compress.cl and spmv.cl (K = RF_K, batches of RF_FRAME_BATCH frames or
// RF_GRAY_PAIR_BATCH Gray pairs). Declared here for their C simulation (tests/fpga/hls_csim_test.cc).
#pragma once

#include "common/frame_samples.h"
#include "transport/ell_rows.h"

// Vitis HLS aggregates a struct argument of an AXI4 master into one word, padded to the next power of two bits
// (UG1399, "Examples of Aggregation"): the words equal the host's layout of a pixel's samples and ELL row only when
// RF_FRAME_BATCH and RF_K are powers of two.
constexpr bool rf_power_of_two(unsigned long bytes) { return bytes != 0 && (bytes & (bytes - 1)) == 0; }
static_assert(rf_power_of_two(sizeof(RfFrameSamples)), "the HLS tops need RF_FRAME_BATCH a power of two");
static_assert(rf_power_of_two(sizeof(RfEllIndices)), "the HLS tops need RF_K a power of two");

extern "C" {

void gray_pairs_single(const RfFrameSamples* frames, int pair_count, const unsigned* pairs, float white_threshold,
                       unsigned* code_x, unsigned* code_y, unsigned char* flags, unsigned n);
void gray_finalize_single(const float* white, const float* black, float black_threshold, int projector_width,
                          int projector_height, unsigned* code_x, unsigned* code_y, unsigned char* flags, unsigned n);

void phase_steps_single(const RfFrameSamples* frames, int axis, int step_count, const float* shifts, float* sums,
                        unsigned n);
void phase_fold_single(int axis, float period, int coarsest, float middle, int steps, float white_threshold,
                       float* sums, float* estimates, unsigned char* flags, unsigned n);
void phase_beat_single(int axis, int level, int f0, int f1, int f2, float axis_pixels, int steps, float white_threshold,
                       float* sums, float* estimates, unsigned char* flags, unsigned n);
void phase_finalize_single(const float* white, const float* black, float black_threshold, float white_threshold,
                           int steps, float period_x, float period_y, int by_order, int projector_width,
                           int projector_height, int entries_per_pixel, unsigned* code_x, unsigned* code_y,
                           const float* sums, const float* estimates, unsigned char* flags, int* indices,
                           float* weights, float* energy, float* correspondence, unsigned n);

void dot_frames_single(const RfFrameSamples* frames, int frame_count, const int* offsets, int spacing,
                       int projector_width, int projector_height, float noise_threshold, const float* black,
                       const unsigned char* flags, const unsigned* projector_x, const unsigned* projector_y,
                       RfEllIndices* indices, RfEllWeights* weights, float* energy, unsigned n);
void finalize_single(const float* white, const float* black, int has_dots, int projector_width, float noise_threshold,
                     unsigned char* flags, const unsigned* projector_x, const unsigned* projector_y,
                     RfEllIndices* indices, RfEllWeights* weights, float* energy, RfCorrespondence* correspondence,
                     unsigned n);

void primal_single(const int* indices, const float* weights, const float* light, float* image, unsigned n);
void dual_single(const int* row_start, const int* entry_row, const int* camera_pixel, const float* weights,
                 const float* light, float* image, unsigned n);
}
