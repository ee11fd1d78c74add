// Phase-shifting decoding per camera pixel (the "phase" pattern family, docs/method.md "Phase shifting"), shared by
// kernels/transport/phase.cl and the HLS C++ top (hw/hls/). State per pixel: the sums S = sum I_k sin(delta_k) and
// C = sum I_k cos(delta_k) of each axis's phase steps, in four planes of n floats (sums[(2 axis) n + c] holds S,
// sums[(2 axis + 1) n + c] holds C; axis 0: columns) of the period being added, and either each axis's order code
// (Gray code of the half-period index), decoded by the Gray pair kernels (transport/gray_decode.h) into code_x /
// code_y (their low-contrast flag ignored: a pair undecided at its stripe edge leaves the half-period index off by one
// at most, which the unwrapping absorbs), or each axis's estimate unwrapped from the longer periods, coarsest first
// (estimates[axis n + c], projector pixels).
// Frames are linear camera responses in [0, 1]; thresholds in the same units.
#ifndef RFRECON_KERNELS_TRANSPORT_PHASE_DECODE_H
#define RFRECON_KERNELS_TRANSPORT_PHASE_DECODE_H

#include "common/params.h"
#include "common/portable.h"
#include "common/target.h"
#include "transport/flags.h"
#include "transport/gray_decode.h"
#ifdef __OPENCL_VERSION__
#define RF_ATAN2 atan2
#define RF_HYPOT hypot
#define RF_ROUND round
#define RF_FLOOR floor
#else
#define RF_ATAN2 std::atan2
#define RF_HYPOT std::hypot
#define RF_ROUND std::round
#define RF_FLOOR std::floor
#endif

#define RF_TWO_PI 6.28318530717958647692f

// A batch of step_count <= RF_FRAME_BATCH phase steps of one axis at pixel c: step p's frame value times
// shifts[2p] = sin(delta_p) and shifts[2p + 1] = cos(delta_p) added to the axis's sums, in the batch's order.
// `values[p]` is step p's linear frame value at c.
RF_INLINE void rf_phase_steps_add(unsigned c, unsigned n, int axis, int step_count, const float* values,
                                  const float* shifts, RF_GLOBAL float* sums) {
  const size_t s = (size_t)(2 * axis) * n + c;
  const size_t k = (size_t)(2 * axis + 1) * n + c;
  float sin_sum = sums[s];
  float cos_sum = sums[k];
  RF_UNROLL
  for (int p = 0; p < RF_FRAME_BATCH; ++p) {
    // Selects rather than branches: one straight datapath on FPGAs.
    const float value = p < step_count ? values[p] : 0.0f;
    sin_sum += value * shifts[2 * p];
    cos_sum += value * shifts[2 * p + 1];
  }
  sums[s] = sin_sum;
  sums[k] = cos_sum;
}

// The batch's RF_FRAME_BATCH (sin, cos) pairs, copied from `shifts` into a private array.
RF_INLINE void rf_load_phase_shifts(RF_GLOBAL const float* shifts, float* local_shifts) {
  RF_UNROLL
  for (int p = 0; p < 2 * RF_FRAME_BATCH; ++p) local_shifts[p] = shifts[p];
}

// The projector coordinate (pixel centres at integers) of wrapped phase theta and period `period` nearest `estimate`:
// as transport::unwrap_near (host/transport/phase_decoding.h), in float.
RF_INLINE float rf_unwrap_near(float theta, float estimate, float period) {
  float wrapped = theta / RF_TWO_PI * period;
  if (wrapped < 0.0f) wrapped += period;
  return RF_ROUND((estimate - wrapped) / period) * period + wrapped;
}

// The estimate the order code gives: the middle of its stripe `order`, `unit` half periods wide (1 or 2).
RF_INLINE float rf_order_middle(unsigned order, float period, int unit) {
  const float width = 0.5f * (float)unit * period;
  return (float)order * width + 0.5f * width - 0.5f;
}

// The modulation 2 / N hypot(S, C) of N steps' sums: the sinusoid's amplitude in linear units.
RF_INLINE float rf_phase_modulation(float sin_sum, float cos_sum, int steps) {
  return 2.0f / (float)steps * RF_HYPOT(sin_sum, cos_sum);
}

// Pixel c's sums of one of the axis's longer periods (`period`) unwrapped near the estimate of the next coarser one
// (`middle`, the axis's middle, for the coarsest) into the axis's estimate; the low-contrast flag where the
// modulation is <= white_threshold; the sums cleared for the next finer period.
RF_INLINE void rf_phase_fold_pixel(unsigned c, unsigned n, int axis, float period, int coarsest, float middle,
                                   int steps, float white_threshold, RF_GLOBAL float* sums, RF_GLOBAL float* estimates,
                                   RF_GLOBAL unsigned char* flags) {
  const size_t s = (size_t)(2 * axis) * n + c;
  const size_t k = (size_t)(2 * axis + 1) * n + c;
  const size_t e = (size_t)axis * n + c;
  const float sin_sum = sums[s], cos_sum = sums[k];
  if (!(rf_phase_modulation(sin_sum, cos_sum, steps) > white_threshold)) {
    flags[c] = (unsigned char)(flags[c] | RF_FLAG_LOW_CONTRAST);
  }
  estimates[e] = rf_unwrap_near(RF_ATAN2(sin_sum, cos_sum), coarsest ? middle : estimates[e], period);
  sums[s] = 0.0f;
  sums[k] = 0.0f;
}

// The fraction of a turn in [0, 1) of v turns.
RF_INLINE float rf_turns(float v) { return v - RF_FLOOR(v); }

// Heterodyne unwrapping of an axis of `axis_pixels` pixels by fringe counts f0 > f1 (> f2; f2 0 for two): pixel c's
// sums of level `level` (f_level fringes across the axis) with the low-contrast flag as rf_phase_fold_pixel's. Levels
// 2 and 1 keep their phase in turns (slot level - 1 of the axis: estimates[(2 (level - 1) + axis) n + c]) and clear
// the sums; level 0, the finest, keeps its sums for phase_finalize and writes the axis's estimate (projector pixels)
// into slot 0: the beat t0 - t1 has f0 - f1 fringes, and with three levels the beat of the beats,
// (t0 - t1) - (t1 - t2), has f0 - 2 f1 + f2 = 1 (one across the axis, taken as it is) and unwraps the first.
RF_INLINE void rf_phase_beat_pixel(unsigned c, unsigned n, int axis, int level, int f0, int f1, int f2,
                                   float axis_pixels, int steps, float white_threshold, RF_GLOBAL float* sums,
                                   RF_GLOBAL float* estimates, RF_GLOBAL unsigned char* flags) {
  const size_t s = (size_t)(2 * axis) * n + c;
  const size_t k = (size_t)(2 * axis + 1) * n + c;
  const size_t slot0 = (size_t)axis * n + c;
  const size_t slot1 = (size_t)(2 + axis) * n + c;
  const float sin_sum = sums[s], cos_sum = sums[k];
  if (!(rf_phase_modulation(sin_sum, cos_sum, steps) > white_threshold)) {
    flags[c] = (unsigned char)(flags[c] | RF_FLAG_LOW_CONTRAST);
  }
  const float t = rf_turns(RF_ATAN2(sin_sum, cos_sum) / RF_TWO_PI);
  if (level > 0) {
    estimates[level == 1 ? slot0 : slot1] = t;
    sums[s] = 0.0f;
    sums[k] = 0.0f;
  } else {
    const float t1 = estimates[slot0];
    const float t2 = f2 > 0 ? estimates[slot1] : 0.0f;
    const float t01 = rf_turns(t - t1);
    const float t012 = rf_turns(t01 - rf_turns(t1 - t2));
    estimates[slot0] = f2 > 0 ? rf_unwrap_near(RF_TWO_PI * t01, t012 * axis_pixels, axis_pixels / (float)(f0 - f1))
                              : t01 * axis_pixels;
  }
}

// Pixel c's flags and, where valid, its sub-pixel correspondence and T's one entry at its projector pixel (white -
// black, row c * entries_per_pixel): the finest period's sums unwrapped near the middle of the order code's stripe
// (by_order: the stripe's width in half periods, 1 or 2) or, by_order 0, near the estimates; shadow where white - black
// <= black_threshold, else out of range where the rounded position lies outside the projector, else low contrast where
// a longer period was (the flag already set; not an order pair's) or an axis's modulation is <= white_threshold, else
// valid. The projector pixel goes to code_x / code_y where valid or low contrast (where the dot grid's rows are filled,
// as Gray code's undecided pixels are), 0 elsewhere. Every other field is left as the empty transport has it.
RF_INLINE void rf_phase_finalize_pixel(unsigned c, unsigned n, float white, float black, float black_threshold,
                                       float white_threshold, int steps, float period_x, float period_y, int by_order,
                                       int projector_width, int projector_height, int entries_per_pixel,
                                       RF_GLOBAL unsigned* code_x, RF_GLOBAL unsigned* code_y,
                                       RF_GLOBAL const float* sums, RF_GLOBAL const float* estimates,
                                       RF_GLOBAL unsigned char* flags, RF_GLOBAL int* indices, RF_GLOBAL float* weights,
                                       RF_GLOBAL float* energy, RF_GLOBAL float* correspondence) {
  const float lit = white - black;
  const float estimate_x = by_order ? rf_order_middle(rf_gray_to_binary(code_x[c]), period_x, by_order) : estimates[c];
  const float estimate_y =
      by_order ? rf_order_middle(rf_gray_to_binary(code_y[c]), period_y, by_order) : estimates[(size_t)n + c];
  const float sin_x = sums[c], cos_x = sums[(size_t)n + c];
  const float sin_y = sums[(size_t)2 * n + c], cos_y = sums[(size_t)3 * n + c];
  const float modulation_x = rf_phase_modulation(sin_x, cos_x, steps);
  const float modulation_y = rf_phase_modulation(sin_y, cos_y, steps);
  const float u = rf_unwrap_near(RF_ATAN2(sin_x, cos_x), estimate_x, period_x);
  const float v = rf_unwrap_near(RF_ATAN2(sin_y, cos_y), estimate_y, period_y);
  const float qx = RF_ROUND(u), qy = RF_ROUND(v);  // halves away from zero, as the reference's lround
  const int contrasted = (by_order || (flags[c] & (unsigned char)RF_FLAG_LOW_CONTRAST) == 0) &&
                         modulation_x > white_threshold && modulation_y > white_threshold;
  const int in_range = qx >= 0.0f && qx < (float)projector_width && qy >= 0.0f && qy < (float)projector_height;
  unsigned char f = (unsigned char)RF_FLAG_VALID;
  if (!(lit > black_threshold)) {
    f = (unsigned char)RF_FLAG_SHADOW;
  } else if (!in_range) {
    f = (unsigned char)RF_FLAG_OUT_OF_RANGE;
  } else if (!contrasted) {
    f = (unsigned char)RF_FLAG_LOW_CONTRAST;
  }
  flags[c] = f;
  const int valid = f == (unsigned char)RF_FLAG_VALID;
  const int placed = valid || f == (unsigned char)RF_FLAG_LOW_CONTRAST;
  code_x[c] = placed ? (unsigned)qx : 0u;
  code_y[c] = placed ? (unsigned)qy : 0u;
  if (valid) {
    const size_t row = (size_t)c * (size_t)entries_per_pixel;
    indices[row] = (int)qy * projector_width + (int)qx;
    weights[row] = lit;
    energy[c] = lit;
    correspondence[2 * (size_t)c] = u;
    correspondence[2 * (size_t)c + 1] = v;
  }
}

// The single work-item loops over the n pixels (the OpenCL `_single` entries and the HLS tops). phase_steps: the
// batch's frames pixel-major (common/frame_samples.h); its shifts copied on chip first.
RF_INLINE void rf_phase_steps_pixels(unsigned n, int axis, int step_count, RF_GLOBAL const float* shifts,
                                     RF_GLOBAL const RfFrameSamples* frames, RF_GLOBAL float* sums) {
  float local_shifts[2 * RF_FRAME_BATCH] RF_PARTITION_COMPLETE;
  rf_load_phase_shifts(shifts, local_shifts);
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE_II(2)  // two of the pixel's sums read and written (its frame samples: one beat)
    const RfFrameSamples batch = frames[c];
    float values[RF_FRAME_BATCH] RF_PARTITION_COMPLETE;
    RF_UNROLL
    for (int p = 0; p < RF_FRAME_BATCH; ++p) values[p] = p < step_count ? batch.sample[p] : 0.0f;
    rf_phase_steps_add(c, n, axis, step_count, values, local_shifts, sums);
  }
}

RF_INLINE void rf_phase_fold_pixels(unsigned n, int axis, float period, int coarsest, float middle, int steps,
                                    float white_threshold, RF_GLOBAL float* sums, RF_GLOBAL float* estimates,
                                    RF_GLOBAL unsigned char* flags) {
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE_II(2)  // two of the pixel's sums read and written
    rf_phase_fold_pixel(c, n, axis, period, coarsest, middle, steps, white_threshold, sums, estimates, flags);
  }
}

RF_INLINE void rf_phase_beat_pixels(unsigned n, int axis, int level, int f0, int f1, int f2, float axis_pixels,
                                    int steps, float white_threshold, RF_GLOBAL float* sums, RF_GLOBAL float* estimates,
                                    RF_GLOBAL unsigned char* flags) {
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE_II(2)  // two of the pixel's sums and estimates read
    rf_phase_beat_pixel(c, n, axis, level, f0, f1, f2, axis_pixels, steps, white_threshold, sums, estimates, flags);
  }
}

RF_INLINE void rf_phase_finalize_pixels(unsigned n, RF_GLOBAL const float* white, RF_GLOBAL const float* black,
                                        float black_threshold, float white_threshold, int steps, float period_x,
                                        float period_y, int by_order, int projector_width, int projector_height,
                                        int entries_per_pixel, RF_GLOBAL unsigned* code_x, RF_GLOBAL unsigned* code_y,
                                        RF_GLOBAL const float* sums, RF_GLOBAL const float* estimates,
                                        RF_GLOBAL unsigned char* flags, RF_GLOBAL int* indices,
                                        RF_GLOBAL float* weights, RF_GLOBAL float* energy,
                                        RF_GLOBAL float* correspondence) {
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE_II(4)  // the pixel's four sums read
    rf_phase_finalize_pixel(c, n, white[c], black[c], black_threshold, white_threshold, steps, period_x, period_y,
                            by_order, projector_width, projector_height, entries_per_pixel, code_x, code_y, sums,
                            estimates, flags, indices, weights, energy, correspondence);
  }
}

#endif  // RFRECON_KERNELS_TRANSPORT_PHASE_DECODE_H
