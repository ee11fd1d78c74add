// Gray code decoding (bodies in transport/gray_decode.h).
//   gray_pairs_ndrange: a batch of up to RF_GRAY_PAIR_BATCH pattern/inverse pairs per launch, as RF_FRAME_BATCH
//                       frame buffers (common/frame_batch.h: pair p's pattern is frame 2p, its inverse frame 2p + 1),
//                       RF_LANES pixels per work-item.
//   gray_pairs_single:  the same batch in one buffer, pixel-major (common/frame_samples.h: pair p's pattern is a
//                       pixel's sample 2p, its inverse 2p + 1), one pixel per iteration (FPGA boards).
//   Both take `pairs`, RF_GRAY_PAIR_BATCH (bit mask, axis) pairs (axis 0: columns, code_x; 1: rows, code_y); each
//   pixel's state is read and written once per batch. The NDRange entry's frames are RF_SAMPLE, made linear with
//   (sample_black, sample_scale); the single work-item entry's are linear floats.
//   gray_finalize_*:    shadow mask from white/black, Gray -> binary, range check (NDRange: RF_LANES pixels per
//                       work-item).
#include "common/frame_batch.h"
#include "common/target.h"
#include "transport/gray_decode.h"

#if RF_NDRANGE_ENTRIES
__kernel void gray_pairs_ndrange(RF_FRAME_PARAMETERS, float sample_black, float sample_scale, int pair_count,
                                 __global const uint* restrict pairs, float white_threshold,
                                 __global uint* restrict code_x, __global uint* restrict code_y,
                                 __global uchar* restrict flags, uint n) {
  const uint c0 = get_global_id(0) * RF_LANES;
  if (c0 >= n) return;
  __global const RF_SAMPLE* frames[RF_FRAME_BATCH] = RF_FRAME_BUFFERS;
  const RfSampleMap map = {sample_black, sample_scale};
  uint masks[RF_GRAY_PAIR_BATCH];
  uint axes[RF_GRAY_PAIR_BATCH];
  rf_load_gray_pairs(pairs, masks, axes);
  if (c0 + RF_LANES <= n) {
    rf_gray_pairs_lanes(c0, pair_count, masks, axes, white_threshold, frames, map, code_x, code_y, flags);
    return;
  }
  for (uint c = c0; c < n; ++c) {  // the last work-item's tail, pixel by pixel
    uint x = code_x[c];
    uint y = code_y[c];
    uchar f = flags[c];
    for (int p = 0; p < pair_count; ++p) {
      const float pattern = rf_linear_sample(frames[2 * p], c, map);
      const float inverse = rf_linear_sample(frames[2 * p + 1], c, map);
      const uint bit = rf_gray_pair_bit(pattern, inverse, masks[p]);
      if (axes[p] != 0) {
        y |= bit;
      } else {
        x |= bit;
      }
      f |= rf_gray_pair_flag(pattern, inverse, white_threshold);
    }
    code_x[c] = x;
    code_y[c] = y;
    flags[c] = f;
  }
}
#endif

RF_SINGLE_TASK
__kernel void gray_pairs_single(__global const RfFrameSamples* restrict frames, int pair_count,
                                __global const uint* restrict pairs, float white_threshold,
                                __global uint* restrict code_x, __global uint* restrict code_y,
                                __global uchar* restrict flags, uint n) {
  rf_gray_pairs_pixels(n, pair_count, pairs, white_threshold, frames, code_x, code_y, flags);
}

#if RF_NDRANGE_ENTRIES
__kernel void gray_finalize_ndrange(__global const float* restrict white, __global const float* restrict black,
                                    float black_threshold, int projector_width, int projector_height,
                                    __global uint* restrict code_x, __global uint* restrict code_y,
                                    __global uchar* restrict flags, uint n) {
  const uint c0 = get_global_id(0) * RF_LANES;  // RF_LANES pixels per work-item; the last one's tail one by one
  if (c0 + RF_LANES <= n) {
    rf_gray_finalize_lanes(c0, vload8(0, white + c0), vload8(0, black + c0), black_threshold, projector_width,
                           projector_height, code_x, code_y, flags);
    return;
  }
  for (uint c = c0; c < n; ++c) {
    rf_gray_finalize_pixel(c, white[c], black[c], black_threshold, projector_width, projector_height, code_x, code_y,
                           flags);
  }
}
#endif

RF_SINGLE_TASK
__kernel void gray_finalize_single(__global const float* restrict white, __global const float* restrict black,
                                   float black_threshold, int projector_width, int projector_height,
                                   __global uint* restrict code_x, __global uint* restrict code_y,
                                   __global uchar* restrict flags, uint n) {
  rf_gray_finalize_pixels(n, white, black, black_threshold, projector_width, projector_height, code_x, code_y, flags);
}
