// Phase-shifting decoding (bodies in transport/phase_decode.h); the order codes go through decode.cl's Gray pairs.
//   phase_steps_ndrange: a batch of up to RF_FRAME_BATCH phase steps of one axis per launch, as RF_FRAME_BATCH frame
//                        buffers (common/frame_batch.h; unused ones repeat frame 0) of RF_SAMPLE made linear with
//                        (sample_black, sample_scale), RF_LANES pixels per work-item, one after another.
//   phase_steps_single:  the same batch in one buffer of linear floats, pixel-major (common/frame_samples.h: step p
//                        is a pixel's sample p), one pixel per iteration (FPGA boards).
//   Both take `shifts`, RF_FRAME_BATCH (sin, cos) pairs of the steps' phase shifts, and add to `sums` (four planes
//   of n floats: S and C of the columns, then of the rows).
//   phase_fold_*:        after the steps of one of an axis's longer periods: its phase unwrapped into the axis's
//                        estimate, its sums cleared (NDRange: RF_LANES pixels per work-item).
//   phase_beat_*:        heterodyne unwrapping, after the steps of each level of an axis: the coarser levels' phases
//                        kept, the finest's beats made into the axis's estimate (NDRange: RF_LANES pixels per
//                        work-item).
//   phase_finalize_*:    the finest period's phase and modulation, unwrapped near the order code's stripe (by_order:
//                        its width in half periods) or the estimate (by_order 0); flags, T's entry and the sub-pixel
//                        correspondence.
#include "common/frame_batch.h"
#include "common/target.h"
#include "transport/phase_decode.h"

#if RF_NDRANGE_ENTRIES
__kernel void phase_steps_ndrange(RF_FRAME_PARAMETERS, float sample_black, float sample_scale, int axis, int step_count,
                                  __global const float* restrict shifts, __global float* restrict sums, uint n) {
  const uint c0 = get_global_id(0) * RF_LANES;
  __global const RF_SAMPLE* frames[RF_FRAME_BATCH] = RF_FRAME_BUFFERS;
  const RfSampleMap map = {sample_black, sample_scale};
  float local_shifts[2 * RF_FRAME_BATCH];
  rf_load_phase_shifts(shifts, local_shifts);
  const uint end = min(c0 + RF_LANES, n);
  for (uint c = c0; c < end; ++c) {
    float values[RF_FRAME_BATCH];
#pragma unroll
    for (int p = 0; p < RF_FRAME_BATCH; ++p) values[p] = rf_linear_sample(frames[p], c, map);
    rf_phase_steps_add(c, n, axis, step_count, values, local_shifts, sums);
  }
}
#endif

RF_SINGLE_TASK
__kernel void phase_steps_single(__global const RfFrameSamples* restrict frames, int axis, int step_count,
                                 __global const float* restrict shifts, __global float* restrict sums, uint n) {
  rf_phase_steps_pixels(n, axis, step_count, shifts, frames, sums);
}

#if RF_NDRANGE_ENTRIES
__kernel void phase_fold_ndrange(int axis, float period, int coarsest, float middle, int steps, float white_threshold,
                                 __global float* restrict sums, __global float* restrict estimates,
                                 __global uchar* restrict flags, uint n) {
  const uint c0 = get_global_id(0) * RF_LANES;
  const uint end = min(c0 + RF_LANES, n);
  for (uint c = c0; c < end; ++c) {
    rf_phase_fold_pixel(c, n, axis, period, coarsest, middle, steps, white_threshold, sums, estimates, flags);
  }
}
#endif

RF_SINGLE_TASK
__kernel void phase_fold_single(int axis, float period, int coarsest, float middle, int steps, float white_threshold,
                                __global float* restrict sums, __global float* restrict estimates,
                                __global uchar* restrict flags, uint n) {
  rf_phase_fold_pixels(n, axis, period, coarsest, middle, steps, white_threshold, sums, estimates, flags);
}

#if RF_NDRANGE_ENTRIES
__kernel void phase_beat_ndrange(int axis, int level, int f0, int f1, int f2, float axis_pixels, int steps,
                                 float white_threshold, __global float* restrict sums,
                                 __global float* restrict estimates, __global uchar* restrict flags, uint n) {
  const uint c0 = get_global_id(0) * RF_LANES;
  const uint end = min(c0 + RF_LANES, n);
  for (uint c = c0; c < end; ++c) {
    rf_phase_beat_pixel(c, n, axis, level, f0, f1, f2, axis_pixels, steps, white_threshold, sums, estimates, flags);
  }
}
#endif

RF_SINGLE_TASK
__kernel void phase_beat_single(int axis, int level, int f0, int f1, int f2, float axis_pixels, int steps,
                                float white_threshold, __global float* restrict sums,
                                __global float* restrict estimates, __global uchar* restrict flags, uint n) {
  rf_phase_beat_pixels(n, axis, level, f0, f1, f2, axis_pixels, steps, white_threshold, sums, estimates, flags);
}

#if RF_NDRANGE_ENTRIES
__kernel void phase_finalize_ndrange(__global const float* restrict white, __global const float* restrict black,
                                     float black_threshold, float white_threshold, int steps, float period_x,
                                     float period_y, int by_order, int projector_width, int projector_height,
                                     int entries_per_pixel, __global uint* restrict code_x,
                                     __global uint* restrict code_y, __global const float* restrict sums,
                                     __global const float* restrict estimates, __global uchar* restrict flags,
                                     __global int* restrict indices, __global float* restrict weights,
                                     __global float* restrict energy, __global float* restrict correspondence, uint n) {
  const uint c0 = get_global_id(0) * RF_LANES;
  const uint end = min(c0 + RF_LANES, n);
  for (uint c = c0; c < end; ++c) {
    rf_phase_finalize_pixel(c, n, white[c], black[c], black_threshold, white_threshold, steps, period_x, period_y,
                            by_order, projector_width, projector_height, entries_per_pixel, code_x, code_y, sums,
                            estimates, flags, indices, weights, energy, correspondence);
  }
}
#endif

RF_SINGLE_TASK
__kernel void phase_finalize_single(__global const float* restrict white, __global const float* restrict black,
                                    float black_threshold, float white_threshold, int steps, float period_x,
                                    float period_y, int by_order, int projector_width, int projector_height,
                                    int entries_per_pixel, __global uint* restrict code_x,
                                    __global uint* restrict code_y, __global const float* restrict sums,
                                    __global const float* restrict estimates, __global uchar* restrict flags,
                                    __global int* restrict indices, __global float* restrict weights,
                                    __global float* restrict energy, __global float* restrict correspondence, uint n) {
  rf_phase_finalize_pixels(n, white, black, black_threshold, white_threshold, steps, period_x, period_y, by_order,
                           projector_width, projector_height, entries_per_pixel, code_x, code_y, sums, estimates, flags,
                           indices, weights, energy, correspondence);
}
