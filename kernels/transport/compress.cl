// Light transport compression (bodies in transport/compression.h): dot_frames_* streams a batch of up to
// RF_FRAME_BATCH dot-grid frames into the ELL rows (the NDRange entry RF_LANES pixels per work-item), finalize_*
// computes the sub-pixel correspondence. The NDRange entry takes the batch's frames as RF_FRAME_BATCH buffers
// (common/frame_batch.h: RF_SAMPLE, made linear with sample_black and sample_scale), the single work-item entry in one
// of linear floats, pixel-major (`frames`, common/frame_samples.h: one wide word per pixel, as an FPGA board reads
// them). `offsets`: RF_FRAME_BATCH (x, y) dot offsets (unused ones 0). The NDRange entry's `fresh` batch (the first)
// writes every row, empty where no frame reached it, so that in an earlier transport's memory the host need not fill
// T's rows (84 MB at 1280x1024 and K = 8) in a pass of its own first; the single work-item entry's rows come filled
// from the host. Each pixel's rows are read and written once per batch; batches of 32 and 64 frames measured slower on
// PoCL and hold more frames until their launch (so RF_FRAME_BATCH is 16; docs/performance.md's git history).
#include "common/target.h"

// Exact agreement with the C++ reference: no fused multiply-add contraction.
#pragma OPENCL FP_CONTRACT OFF
#include "common/frame_batch.h"
#include "transport/compression.h"

#if RF_NDRANGE_ENTRIES
__kernel void dot_frames_ndrange(RF_FRAME_PARAMETERS, float sample_black, float sample_scale, int fresh,
                                 int frame_count, __global const int* restrict offsets, int spacing,
                                 int projector_width, int projector_height, float noise_threshold,
                                 __global const float* restrict black, __global const uchar* restrict flags,
                                 __global const uint* restrict projector_x, __global const uint* restrict projector_y,
                                 __global int* restrict indices, __global float* restrict weights,
                                 __global float* restrict energy, uint n) {
  // Work-item i: pixels i RF_LANES .. (i + 1) RF_LANES - 1, in vector lanes; the last one's tail pixel by pixel.
  const uint c0 = get_global_id(0) * RF_LANES;
  if (c0 >= n) return;
  __global const RF_SAMPLE* frames[RF_FRAME_BATCH] = RF_FRAME_BUFFERS;
  const RfSampleMap map = {sample_black, sample_scale};
  int offsets_x[RF_FRAME_BATCH];
  int offsets_y[RF_FRAME_BATCH];
  rf_load_dot_offsets(offsets, offsets_x, offsets_y);
  const RfDotGrid grid = {spacing, projector_width, projector_height, noise_threshold};
  if (c0 + RF_LANES <= n) {
    rf_dot_frames_lanes(c0, fresh, frame_count, offsets_x, offsets_y, grid, frames, map, black, flags, projector_x,
                        projector_y, indices, weights, energy);
    return;
  }
  for (uint c = c0; c < n; ++c) {
    // This tail's rows as single work-item loops take them (transport/ell_rows.h): the same memory.
    __global RfEllIndices* row_indices = (__global RfEllIndices*)indices;
    __global RfEllWeights* row_weights = (__global RfEllWeights*)weights;
    if (fresh) rf_empty_row(c, row_indices, row_weights);
    float sample[RF_FRAME_BATCH];
    for (int f = 0; f < RF_FRAME_BATCH; ++f) sample[f] = f < frame_count ? rf_linear_sample(frames[f], c, map) : 0.0f;
    rf_dot_samples_pixel(c, sample, frame_count, offsets_x, offsets_y, grid, black, flags, projector_x, projector_y,
                         row_indices, row_weights, energy);
  }
}
#endif

RF_SINGLE_TASK
__kernel void dot_frames_single(__global const RfFrameSamples* restrict frames, int frame_count,
                                __global const int* restrict offsets, int spacing, int projector_width,
                                int projector_height, float noise_threshold, __global const float* restrict black,
                                __global const uchar* restrict flags, __global const uint* restrict projector_x,
                                __global const uint* restrict projector_y, __global RfEllIndices* restrict indices,
                                __global RfEllWeights* restrict weights, __global float* restrict energy, uint n) {
  const RfDotGrid grid = {spacing, projector_width, projector_height, noise_threshold};
  rf_dot_frames_pixels(n, frame_count, offsets, grid, frames, black, flags, projector_x, projector_y, indices, weights,
                       energy);
}

#if RF_NDRANGE_ENTRIES
__kernel void finalize_ndrange(__global const float* restrict white, __global const float* restrict black, int has_dots,
                               int projector_width, float noise_threshold, __global uchar* restrict flags,
                               __global const uint* restrict projector_x, __global const uint* restrict projector_y,
                               __global int* restrict indices, __global float* restrict weights,
                               __global float* restrict energy, __global float* restrict correspondence, uint n) {
  const uint c = get_global_id(0);
  if (c < n) {
    rf_finalize_pixel(c, white[c], black[c], has_dots, projector_width, 1.0f / (float)projector_width, noise_threshold,
                      flags, projector_x, projector_y, (__global RfEllIndices*)indices, (__global RfEllWeights*)weights,
                      energy, (__global RfCorrespondence*)correspondence);
  }
}
#endif

RF_SINGLE_TASK
__kernel void finalize_single(__global const float* restrict white, __global const float* restrict black, int has_dots,
                              int projector_width, float noise_threshold, __global uchar* restrict flags,
                              __global const uint* restrict projector_x, __global const uint* restrict projector_y,
                              __global RfEllIndices* restrict indices, __global RfEllWeights* restrict weights,
                              __global float* restrict energy, __global RfCorrespondence* restrict correspondence,
                              uint n) {
  rf_finalize_pixels(n, white, black, has_dots, projector_width, noise_threshold, flags, projector_x, projector_y,
                     indices, weights, energy, correspondence);
}
