// Gray code decoding per camera pixel (OpenCV GrayCodePattern semantic), shared by kernels/transport/decode.cl and
// the HLS C++ top (hw/hls/). State per pixel: the Gray words of both axes (a bit set where pattern > inverse) and the
// flags. Frames are linear camera responses in [0, 1] (host/capture/manifest.h); thresholds in the same units.
#ifndef RFRECON_KERNELS_TRANSPORT_GRAY_DECODE_H
#define RFRECON_KERNELS_TRANSPORT_GRAY_DECODE_H

#include "common/portable.h"
#include "common/target.h"
#include "transport/flags.h"

// One pattern / inverse pair at pixel c.
RF_INLINE void rf_gray_pair_pixel(unsigned c, float pattern, float inverse, unsigned bit_mask, float white_threshold,
                                  RF_GLOBAL unsigned* code, RF_GLOBAL unsigned char* flags) {
  if (pattern > inverse) code[c] |= bit_mask;
  if (RF_FABS(pattern - inverse) <= white_threshold) flags[c] |= (unsigned char)RF_FLAG_LOW_CONTRAST;
}

RF_INLINE unsigned rf_gray_to_binary(unsigned gray) {
  unsigned binary = gray;
  RF_UNROLL
  for (unsigned shift = 1; shift < 32; shift <<= 1) binary ^= binary >> shift;
  return binary;
}

// Turns the Gray words of pixel c into projector coordinates (written over the codes) and sets the flags: shadow
// from white - black, the range check, valid when neither they nor a low-contrast pair flagged it.
RF_INLINE void rf_gray_finalize_pixel(unsigned c, float white, float black, float black_threshold, int projector_width,
                                      int projector_height, RF_GLOBAL unsigned* code_x, RF_GLOBAL unsigned* code_y,
                                      RF_GLOBAL unsigned char* flags) {
  const unsigned x = rf_gray_to_binary(code_x[c]);
  const unsigned y = rf_gray_to_binary(code_y[c]);
  code_x[c] = x;
  code_y[c] = y;
  unsigned char f = flags[c];
  if (white - black <= black_threshold) f |= (unsigned char)RF_FLAG_SHADOW;
  if (x >= (unsigned)projector_width || y >= (unsigned)projector_height) f |= (unsigned char)RF_FLAG_OUT_OF_RANGE;
  if ((f & (unsigned char)(RF_FLAG_SHADOW | RF_FLAG_LOW_CONTRAST | RF_FLAG_OUT_OF_RANGE)) == 0) {
    f |= (unsigned char)RF_FLAG_VALID;
  }
  flags[c] = f;
}

// The single work-item loops over the n pixels (the OpenCL `_single` entries and the HLS tops).
RF_INLINE void rf_gray_pair_pixels(unsigned n, RF_GLOBAL const float* pattern, RF_GLOBAL const float* inverse,
                                   unsigned bit_mask, float white_threshold, RF_GLOBAL unsigned* code,
                                   RF_GLOBAL unsigned char* flags) {
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE
    rf_gray_pair_pixel(c, pattern[c], inverse[c], bit_mask, white_threshold, code, flags);
  }
}

RF_INLINE void rf_gray_finalize_pixels(unsigned n, RF_GLOBAL const float* white, RF_GLOBAL const float* black,
                                       float black_threshold, int projector_width, int projector_height,
                                       RF_GLOBAL unsigned* code_x, RF_GLOBAL unsigned* code_y,
                                       RF_GLOBAL unsigned char* flags) {
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE
    rf_gray_finalize_pixel(c, white[c], black[c], black_threshold, projector_width, projector_height, code_x, code_y,
                           flags);
  }
}

#endif  // RFRECON_KERNELS_TRANSPORT_GRAY_DECODE_H
