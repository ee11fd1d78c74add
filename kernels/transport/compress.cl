// Light transport compression: streams the dot-grid frames into fixed-K "ELL" rows (K projector indices and
// weights per camera pixel, strongest first), then finalizes the sub-pixel correspondence (weighted centroid).
// K: RF_K (common/params.h). ELL layout: entry k of camera pixel c at c * RF_K + k; index -1 marks an empty slot.
// A frame with dot offset (ox, oy) lights projector pixels with x % s == ox and y % s == oy; a lit camera pixel
// with Gray code coordinate (px, py) sees the lit dot nearest to it, qx = ox + s * floor((px - ox + s/2) / s)
// (same for y), so the s x s frames fill its window [px - (s-1)/2, px + s/2] x [py - (s-1)/2, py + s/2].
#include "common/target.h"

// Exact agreement with the C++ reference: no fused multiply-add contraction.
#pragma OPENCL FP_CONTRACT OFF
#include "common/params.h"
#include "transport/flags.h"

inline int floor_div(int a, int b) { return a >= 0 ? a / b : -((b - 1 - a) / b); }

// Inserts (q, v) into the pixel's K entries sorted by decreasing weight (after equal weights), dropping the weakest.
inline void insert_entry(uint c, int q, float v, __global int* restrict indices, __global float* restrict weights) {
  __global int* row_index = indices + (size_t)c * RF_K;
  __global float* row_weight = weights + (size_t)c * RF_K;
  if (!(v > row_weight[RF_K - 1])) return;
  float w[RF_K] RF_PARTITION_COMPLETE;
  int i[RF_K] RF_PARTITION_COMPLETE;
  RF_UNROLL
  for (int k = 0; k < RF_K; ++k) {
    w[k] = row_weight[k];
    i[k] = row_index[k];
  }
  // Compare-and-shift network: slot k takes v when v beats it but not slot k-1, or slot k-1's entry when v beats
  // that one too; every slot is computed from the old row, so the K slots update in parallel.
  RF_UNROLL
  for (int k = RF_K - 1; k > 0; --k) {
    if (v > w[k]) {
      const bool beats_previous = v > w[k - 1];
      row_weight[k] = beats_previous ? w[k - 1] : v;
      row_index[k] = beats_previous ? i[k - 1] : q;
    }
  }
  if (v > w[0]) {
    row_weight[0] = v;
    row_index[0] = q;
  }
}

inline void dot_frame_pixel(uint c, float value, float black, int offset_x, int offset_y, int spacing,
                            int projector_width, int projector_height, float noise_threshold,
                            __global const uchar* restrict flags, __global const uint* restrict projector_x,
                            __global const uint* restrict projector_y, __global int* restrict indices,
                            __global float* restrict weights, __global float* restrict energy) {
  if (!RF_COMPRESSIBLE(flags[c])) return;
  const float v = value - black;
  if (!(v > noise_threshold)) return;
  const int qx = offset_x + spacing * floor_div((int)projector_x[c] - offset_x + spacing / 2, spacing);
  const int qy = offset_y + spacing * floor_div((int)projector_y[c] - offset_y + spacing / 2, spacing);
  if (qx < 0 || qx >= projector_width || qy < 0 || qy >= projector_height) return;
  energy[c] += v;
  insert_entry(c, qy * projector_width + qx, v, indices, weights);
}

__kernel void dot_frame_ndrange(__global const float* restrict frame, __global const float* restrict black,
                                int offset_x, int offset_y, int spacing, int projector_width, int projector_height,
                                float noise_threshold, __global const uchar* restrict flags,
                                __global const uint* restrict projector_x, __global const uint* restrict projector_y,
                                __global int* restrict indices, __global float* restrict weights,
                                __global float* restrict energy, uint n) {
  const uint c = get_global_id(0);
  if (c < n) {
    dot_frame_pixel(c, frame[c], black[c], offset_x, offset_y, spacing, projector_width, projector_height,
                    noise_threshold, flags, projector_x, projector_y, indices, weights, energy);
  }
}

RF_SINGLE_TASK
__kernel void dot_frame_single(__global const float* restrict frame, __global const float* restrict black, int offset_x,
                               int offset_y, int spacing, int projector_width, int projector_height,
                               float noise_threshold, __global const uchar* restrict flags,
                               __global const uint* restrict projector_x, __global const uint* restrict projector_y,
                               __global int* restrict indices, __global float* restrict weights,
                               __global float* restrict energy, uint n) {
  RF_PIPELINE_II(1)
  for (uint c = 0; c < n; ++c) {
    dot_frame_pixel(c, frame[c], black[c], offset_x, offset_y, spacing, projector_width, projector_height,
                    noise_threshold, flags, projector_x, projector_y, indices, weights, energy);
  }
}

// Gray-code-only captures (has_dots == 0) first get their single entry T[c, p(c)] = white - black. Then the
// correspondence is the weight-averaged projector pixel centre of the entries (NaN without any), and lit in-range
// pixels without an entry are flagged RF_FLAG_NO_SIGNAL.
inline void finalize_pixel(uint c, float white, float black, int has_dots, int projector_width, float noise_threshold,
                           __global uchar* restrict flags, __global const uint* restrict projector_x,
                           __global const uint* restrict projector_y, __global int* restrict indices,
                           __global float* restrict weights, __global float* restrict energy,
                           __global float* restrict correspondence) {
  const bool valid = (flags[c] & (uchar)RF_FLAG_VALID) != 0;
  const float lit = white - black;
  if (valid && has_dots == 0 && lit > noise_threshold) {
    indices[(size_t)c * RF_K] = (int)(projector_y[c] * (uint)projector_width + projector_x[c]);
    weights[(size_t)c * RF_K] = lit;
    energy[c] = lit;
  }
  float sum = 0.0f;
  float sum_x = 0.0f;
  float sum_y = 0.0f;
  RF_UNROLL
  for (int k = 0; k < RF_K; ++k) {
    const int q = indices[(size_t)c * RF_K + k];
    if (q >= 0) {
      const float w = weights[(size_t)c * RF_K + k];
      // x from y without `%`: LLVM would pair the division and remainder through a `freeze`, which oclgrind's
      // uninitialized-value checker cannot run.
      const int y = q / projector_width;
      sum += w;
      sum_x += w * (float)(q - y * projector_width);
      sum_y += w * (float)y;
    }
  }
  const bool found = sum > 0.0f;
  correspondence[2 * (size_t)c] = found ? sum_x / sum : NAN;
  correspondence[2 * (size_t)c + 1] = found ? sum_y / sum : NAN;
  if (RF_COMPRESSIBLE(flags[c]) && !found) flags[c] |= (uchar)RF_FLAG_NO_SIGNAL;
}

__kernel void finalize_ndrange(__global const float* restrict white, __global const float* restrict black, int has_dots,
                               int projector_width, float noise_threshold, __global uchar* restrict flags,
                               __global const uint* restrict projector_x, __global const uint* restrict projector_y,
                               __global int* restrict indices, __global float* restrict weights,
                               __global float* restrict energy, __global float* restrict correspondence, uint n) {
  const uint c = get_global_id(0);
  if (c < n) {
    finalize_pixel(c, white[c], black[c], has_dots, projector_width, noise_threshold, flags, projector_x, projector_y,
                   indices, weights, energy, correspondence);
  }
}

RF_SINGLE_TASK
__kernel void finalize_single(__global const float* restrict white, __global const float* restrict black, int has_dots,
                              int projector_width, float noise_threshold, __global uchar* restrict flags,
                              __global const uint* restrict projector_x, __global const uint* restrict projector_y,
                              __global int* restrict indices, __global float* restrict weights,
                              __global float* restrict energy, __global float* restrict correspondence, uint n) {
  RF_PIPELINE_II(1)
  for (uint c = 0; c < n; ++c) {
    finalize_pixel(c, white[c], black[c], has_dots, projector_width, noise_threshold, flags, projector_x, projector_y,
                   indices, weights, energy, correspondence);
  }
}
