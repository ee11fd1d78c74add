// Gray code decoding (OpenCV GrayCodePattern semantic), streamed one pattern/inverse pair at a time.
// State per camera pixel: the Gray code words of both axes (bit set from pattern > inverse) and the flags.
// gray_pair_*: adds one pair; gray_finalize_*: shadow mask from white/black, Gray -> binary, range check.
// Frames are linear camera responses in [0, 1] (host/capture/manifest.h); thresholds in the same units.
#include "common/target.h"
#include "transport/flags.h"

inline void gray_pair_pixel(uint c, float pattern, float inverse, uint bit_mask, float white_threshold,
                            __global uint* restrict code, __global uchar* restrict flags) {
  if (pattern > inverse) code[c] |= bit_mask;
  if (fabs(pattern - inverse) <= white_threshold) flags[c] |= (uchar)RF_FLAG_LOW_CONTRAST;
}

__kernel void gray_pair_ndrange(__global const float* restrict pattern, __global const float* restrict inverse,
                                uint bit_mask, float white_threshold, __global uint* restrict code,
                                __global uchar* restrict flags, uint n) {
  const uint c = get_global_id(0);
  if (c < n) gray_pair_pixel(c, pattern[c], inverse[c], bit_mask, white_threshold, code, flags);
}

RF_SINGLE_TASK
__kernel void gray_pair_single(__global const float* restrict pattern, __global const float* restrict inverse,
                               uint bit_mask, float white_threshold, __global uint* restrict code,
                               __global uchar* restrict flags, uint n) {
  RF_PIPELINE_II(1)
  for (uint c = 0; c < n; ++c) gray_pair_pixel(c, pattern[c], inverse[c], bit_mask, white_threshold, code, flags);
}

inline uint gray_to_binary(uint gray) {
  uint binary = gray;
  RF_UNROLL
  for (uint shift = 1; shift < 32; shift <<= 1) binary ^= binary >> shift;
  return binary;
}

// Turns the Gray words of pixel c into projector coordinates (written over the codes) and sets the flags.
inline void gray_finalize_pixel(uint c, float white, float black, float black_threshold, int projector_width,
                                int projector_height, __global uint* restrict code_x, __global uint* restrict code_y,
                                __global uchar* restrict flags) {
  const uint x = gray_to_binary(code_x[c]);
  const uint y = gray_to_binary(code_y[c]);
  code_x[c] = x;
  code_y[c] = y;
  uchar f = flags[c];
  if (white - black <= black_threshold) f |= (uchar)RF_FLAG_SHADOW;
  if (x >= (uint)projector_width || y >= (uint)projector_height) f |= (uchar)RF_FLAG_OUT_OF_RANGE;
  if ((f & (uchar)(RF_FLAG_SHADOW | RF_FLAG_LOW_CONTRAST | RF_FLAG_OUT_OF_RANGE)) == 0) f |= (uchar)RF_FLAG_VALID;
  flags[c] = f;
}

__kernel void gray_finalize_ndrange(__global const float* restrict white, __global const float* restrict black,
                                    float black_threshold, int projector_width, int projector_height,
                                    __global uint* restrict code_x, __global uint* restrict code_y,
                                    __global uchar* restrict flags, uint n) {
  const uint c = get_global_id(0);
  if (c < n) {
    gray_finalize_pixel(c, white[c], black[c], black_threshold, projector_width, projector_height, code_x, code_y,
                        flags);
  }
}

RF_SINGLE_TASK
__kernel void gray_finalize_single(__global const float* restrict white, __global const float* restrict black,
                                   float black_threshold, int projector_width, int projector_height,
                                   __global uint* restrict code_x, __global uint* restrict code_y,
                                   __global uchar* restrict flags, uint n) {
  RF_PIPELINE_II(1)
  for (uint c = 0; c < n; ++c) {
    gray_finalize_pixel(c, white[c], black[c], black_threshold, projector_width, projector_height, code_x, code_y,
                        flags);
  }
}
