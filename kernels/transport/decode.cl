// Gray code decoding (bodies in transport/gray_decode.h).
//   gray_pairs_ndrange: one pattern/inverse pair per launch (CPUs and GPUs decode a pair while its two frames are
//                       still in their caches; the host passes the frames' own memory), into its axis' code word.
//   gray_pairs_single:  a batch of up to RF_GRAY_PAIR_BATCH pairs per launch (pair p's pattern at 2p * n, its inverse
//                       at (2p + 1) * n; `pairs` holds RF_GRAY_PAIR_BATCH (bit mask, axis) pairs, axis 0: columns,
//                       code_x; 1: rows, code_y), each pixel's state read and written once per batch (FPGA boards).
//   gray_finalize_*:    shadow mask from white/black, Gray -> binary, range check.
#include "common/target.h"
#include "transport/gray_decode.h"

__kernel void gray_pairs_ndrange(__global const float* restrict pattern, __global const float* restrict inverse,
                                 uint bit_mask, float white_threshold, __global uint* restrict code,
                                 __global uchar* restrict flags, uint n) {
  const uint c = get_global_id(0);
  if (c >= n) return;
  const uint bit = rf_gray_pair_bit(pattern[c], inverse[c], bit_mask);
  if (bit) code[c] |= bit;
  const uchar flag = rf_gray_pair_flag(pattern[c], inverse[c], white_threshold);
  if (flag) flags[c] |= flag;
}

RF_SINGLE_TASK
__kernel void gray_pairs_single(__global const float* restrict frames, int pair_count,
                                __global const uint* restrict pairs, float white_threshold,
                                __global uint* restrict code_x, __global uint* restrict code_y,
                                __global uchar* restrict flags, uint n) {
  rf_gray_pairs_pixels(n, pair_count, pairs, white_threshold, frames, code_x, code_y, flags);
}

__kernel void gray_finalize_ndrange(__global const float* restrict white, __global const float* restrict black,
                                    float black_threshold, int projector_width, int projector_height,
                                    __global uint* restrict code_x, __global uint* restrict code_y,
                                    __global uchar* restrict flags, uint n) {
  const uint c = get_global_id(0);
  if (c < n) {
    rf_gray_finalize_pixel(c, white[c], black[c], black_threshold, projector_width, projector_height, code_x, code_y,
                           flags);
  }
}

RF_SINGLE_TASK
__kernel void gray_finalize_single(__global const float* restrict white, __global const float* restrict black,
                                   float black_threshold, int projector_width, int projector_height,
                                   __global uint* restrict code_x, __global uint* restrict code_y,
                                   __global uchar* restrict flags, uint n) {
  rf_gray_finalize_pixels(n, white, black, black_threshold, projector_width, projector_height, code_x, code_y, flags);
}
