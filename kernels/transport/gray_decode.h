// Gray code decoding per camera pixel (OpenCV GrayCodePattern semantic), shared by kernels/transport/decode.cl and
// the HLS C++ top (hw/hls/). State per pixel: the Gray words of both axes (a bit set where pattern > inverse) and the
// flags. Frames are linear camera responses in [0, 1] (host/capture/manifest.h); thresholds in the same units.
//
// Pattern / inverse pairs come in batches of up to RF_GRAY_PAIR_BATCH (pair p of the batch: samples 2p and 2p + 1 of
// a pixel's RfFrameSamples, common/frame_samples.h; or frames 2p and 2p + 1 of RF_FRAME_BATCH arrays, in lanes), so
// that a pixel's state is read once per batch, updated in registers pair after pair in the batch's order (equal to one
// pair at a time, to the bit) and written back once: one read-modify-write of memory per batch rather than per pair.
#ifndef RFRECON_KERNELS_TRANSPORT_GRAY_DECODE_H
#define RFRECON_KERNELS_TRANSPORT_GRAY_DECODE_H

#include "common/frame_samples.h"
#include "common/lanes.h"
#include "common/params.h"
#include "common/portable.h"
#include "common/target.h"
#include "transport/flags.h"
#ifdef __OPENCL_VERSION__
#include "common/frame_batch.h"
#endif

// The pairs of a batch fill the compression's batch of RF_FRAME_BATCH frames (at least 2,
// cmake/EmbedKernelsParams.cmake).
#define RF_GRAY_PAIR_BATCH (RF_FRAME_BATCH / 2)

// What one pattern / inverse pair adds at a pixel: bit `mask` of its axis' code word where the pattern is the
// brighter, and the low-contrast flag where the two differ by no more than the threshold.
RF_INLINE unsigned rf_gray_pair_bit(float pattern, float inverse, unsigned mask) {
  return pattern > inverse ? mask : 0u;
}
RF_INLINE unsigned char rf_gray_pair_flag(float pattern, float inverse, float white_threshold) {
  return RF_FABS(pattern - inverse) <= white_threshold ? (unsigned char)RF_FLAG_LOW_CONTRAST : (unsigned char)0;
}

// A batch of pair_count <= RF_GRAY_PAIR_BATCH pairs at pixel c of n, unrolled to the batch's size (the single
// work-item entries): pair p sets masks[p] in code_x (axes[p] == 0) or code_y.
RF_INLINE void rf_gray_pairs_pixel(unsigned c, int pair_count, const unsigned* masks, const unsigned* axes,
                                   float white_threshold, RF_GLOBAL const RfFrameSamples* frames,
                                   RF_GLOBAL unsigned* code_x, RF_GLOBAL unsigned* code_y,
                                   RF_GLOBAL unsigned char* flags) {
  const RfFrameSamples batch = frames[c];
  unsigned x = code_x[c];
  unsigned y = code_y[c];
  unsigned char f = flags[c];
  RF_UNROLL
  for (int p = 0; p < RF_GRAY_PAIR_BATCH; ++p) {
    const int active = p < pair_count;
    const float pattern = active ? batch.sample[2 * p] : 0.0f;
    const float inverse = active ? batch.sample[2 * p + 1] : 0.0f;
    // Selects rather than branches: one straight datapath on FPGAs.
    const unsigned bit = active ? rf_gray_pair_bit(pattern, inverse, masks[p]) : 0u;
    x |= axes[p] != 0 ? 0u : bit;
    y |= axes[p] != 0 ? bit : 0u;
    f |= active ? rf_gray_pair_flag(pattern, inverse, white_threshold) : (unsigned char)0;
  }
  code_x[c] = x;
  code_y[c] = y;
  flags[c] = f;
}

// The batch's RF_GRAY_PAIR_BATCH (bit mask, axis) pairs, copied from `pairs` into private arrays.
RF_INLINE void rf_load_gray_pairs(RF_GLOBAL const unsigned* pairs, unsigned* masks, unsigned* axes) {
  RF_UNROLL
  for (int p = 0; p < RF_GRAY_PAIR_BATCH; ++p) {
    masks[p] = pairs[(size_t)(2 * p)];
    axes[p] = pairs[(size_t)(2 * p + 1)];
  }
}

#ifdef __OPENCL_VERSION__
// The batch at the RF_LANES pixels c0 .. c0 + RF_LANES - 1 at once, one per vector lane, pair p's pattern at
// frames[2p] and its inverse at frames[2p + 1] (the NDRange entry; samples made linear with `map`): every frame's
// samples loaded before the first is used, so that their cache misses overlap; unused pairs' buffers repeat frame 0,
// so every load is in bounds.
RF_INLINE void rf_gray_pairs_lanes(uint c0, int pair_count, const uint* masks, const uint* axes, float white_threshold,
                                   __global const RF_SAMPLE* const* frames, RfSampleMap map, __global uint* code_x,
                                   __global uint* code_y, __global uchar* flags) {
  float8 pattern[RF_GRAY_PAIR_BATCH];
  float8 inverse[RF_GRAY_PAIR_BATCH];
#pragma unroll
  for (int p = 0; p < RF_GRAY_PAIR_BATCH; ++p) {
    pattern[p] = rf_linear_sample_lanes(frames[2 * p], c0, map);
    inverse[p] = rf_linear_sample_lanes(frames[2 * p + 1], c0, map);
  }
  uint8 x = vload8(0, code_x + c0);
  uint8 y = vload8(0, code_y + c0);
  int8 low_contrast = 0;  // -1 or 0 per lane, as comparisons give
  for (int p = 0; p < pair_count; ++p) {
    const uint8 bit = as_uint8(pattern[p] > inverse[p]) & masks[p];
    if (axes[p] != 0) {
      y |= bit;
    } else {
      x |= bit;
    }
    low_contrast |= fabs(pattern[p] - inverse[p]) <= white_threshold;
  }
  vstore8(x, 0, code_x + c0);
  vstore8(y, 0, code_y + c0);
  vstore8(vload8(0, flags + c0) | convert_uchar8(low_contrast & (int)RF_FLAG_LOW_CONTRAST), 0, flags + c0);
}
#endif

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

#ifdef __OPENCL_VERSION__
// rf_gray_finalize_pixel for the RF_LANES pixels c0 .. c0 + RF_LANES - 1 at once, one per vector lane.
RF_INLINE void rf_gray_finalize_lanes(uint c0, float8 white, float8 black, float black_threshold, int projector_width,
                                      int projector_height, __global uint* code_x, __global uint* code_y,
                                      __global uchar* flags) {
  uint8 x = vload8(0, code_x + c0);
  uint8 y = vload8(0, code_y + c0);
  for (uint shift = 1; shift < 32; shift <<= 1) {
    x ^= x >> shift;
    y ^= y >> shift;
  }
  vstore8(x, 0, code_x + c0);
  vstore8(y, 0, code_y + c0);
  // Flag bits set by select() on the comparisons' masks: under oclgrind, a mask of (... == 0) ANDed with a flag bit
  // gave every bit (PoCL's were right).
  const int8 none = 0;
  int8 f = convert_int8(vload8(0, flags + c0));
  f |= select(none, (int8)RF_FLAG_SHADOW, white - black <= black_threshold);
  f |= select(none, (int8)RF_FLAG_OUT_OF_RANGE, (x >= (uint)projector_width) | (y >= (uint)projector_height));
  const int8 invalid = f & (int)(RF_FLAG_SHADOW | RF_FLAG_LOW_CONTRAST | RF_FLAG_OUT_OF_RANGE);
  f |= select(none, (int8)RF_FLAG_VALID, invalid == 0);
  vstore8(convert_uchar8(f), 0, flags + c0);
}
#endif

// The single work-item loops over the n pixels (the OpenCL `_single` entries and the HLS tops); the batch's pairs
// copied on chip first.
RF_INLINE void rf_gray_pairs_pixels(unsigned n, int pair_count, RF_GLOBAL const unsigned* pairs, float white_threshold,
                                    RF_GLOBAL const RfFrameSamples* frames, RF_GLOBAL unsigned* code_x,
                                    RF_GLOBAL unsigned* code_y, RF_GLOBAL unsigned char* flags) {
  unsigned masks[RF_GRAY_PAIR_BATCH] RF_PARTITION_COMPLETE;
  unsigned axes[RF_GRAY_PAIR_BATCH] RF_PARTITION_COMPLETE;
  rf_load_gray_pairs(pairs, masks, axes);
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE  // one AXI beat of the pixel's frame samples, one of each code and the flags
    rf_gray_pairs_pixel(c, pair_count, masks, axes, white_threshold, frames, code_x, code_y, flags);
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
