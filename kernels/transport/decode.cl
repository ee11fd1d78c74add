// Gray code decoding, streamed one pattern/inverse pair at a time (bodies in transport/gray_decode.h).
// gray_pair_*: adds one pair; gray_finalize_*: shadow mask from white/black, Gray -> binary, range check.
#include "common/target.h"
#include "transport/gray_decode.h"

__kernel void gray_pair_ndrange(__global const float* restrict pattern, __global const float* restrict inverse,
                                uint bit_mask, float white_threshold, __global uint* restrict code,
                                __global uchar* restrict flags, uint n) {
  const uint c = get_global_id(0);
  if (c < n) rf_gray_pair_pixel(c, pattern[c], inverse[c], bit_mask, white_threshold, code, flags);
}

RF_SINGLE_TASK
__kernel void gray_pair_single(__global const float* restrict pattern, __global const float* restrict inverse,
                               uint bit_mask, float white_threshold, __global uint* restrict code,
                               __global uchar* restrict flags, uint n) {
  rf_gray_pair_pixels(n, pattern, inverse, bit_mask, white_threshold, code, flags);
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
