// Light transport compression per camera pixel, shared by kernels/transport/compress.cl and the HLS C++ tops
// (hw/hls/): dot-grid frames streamed into fixed-K "ELL" rows (K = RF_K projector indices and weights per camera
// pixel, strongest first; entry k of pixel c at c * RF_K + k, index -1 marks an empty slot), then the sub-pixel
// correspondence (weighted centroid).
//
// A frame with dot offset (ox, oy), 0 <= ox, oy < s, lights projector pixels with x % s == ox and y % s == oy. A lit
// camera pixel with Gray code coordinate (px, py) sees the lit dot nearest to it, qx = ox + s * floor((px - ox +
// s/2) / s) (same for y), so the s x s frames fill its window [px - (s-1)/2, px + s/2] x [py - (s-1)/2, py + s/2]:
// with x0 = px - (s-1)/2 and a = x0 mod s, qx = x0 + ((ox - a) mod s), where ox - a lies in (-s, s).
//
// Frames come in batches of up to RF_FRAME_BATCH (one array pixel-major, common/frame_samples.h, or one per frame): a
// pixel's row is read once per batch, updated in registers frame after frame in the batch's order (so the result equals
// one frame at a time, to the bit), and written back once, only when a frame of the batch reached it. The only
// remainder by the run-time spacing, a = x0 mod s, is computed once per pixel and batch: on FPGA targets a choice among
// divisions by the compile-time RF_DOT_SPACINGS (the host refuses other spacings), elsewhere a multiplication by 1 / s
// corrected to the exact remainder. The centroid's row of an entry, q / width, is a multiplication by 1 / width
// (computed once) corrected to the exact quotient.
#ifndef RFRECON_KERNELS_TRANSPORT_COMPRESSION_H
#define RFRECON_KERNELS_TRANSPORT_COMPRESSION_H

#include "common/frame_samples.h"
#include "common/lanes.h"
#include "common/params.h"
#include "common/portable.h"
#include "common/target.h"
#include "transport/ell_rows.h"
#include "transport/flags.h"
#ifdef __OPENCL_VERSION__
#include "common/frame_batch.h"
#endif

// The window arithmetic, on int for one pixel (names as below) and, in OpenCL C, on RF_LANES_INT for RF_LANES pixels
// at once (names with _lanes: transport/dot_window.h), with their conversions to and from float.
#define RF_DOT_INT int
#define RF_DOT_TO_REAL(x) ((float)(x))
#define RF_DOT_TO_INT(x) ((int)(x))
#define RF_DOT_FN(name) name
#include "transport/dot_window.h"
#undef RF_DOT_INT
#undef RF_DOT_TO_REAL
#undef RF_DOT_TO_INT
#undef RF_DOT_FN
#ifdef __OPENCL_VERSION__
#define RF_DOT_INT RF_LANES_INT
#define RF_DOT_TO_REAL(x) RF_LANES_TO_REAL(x)
#define RF_DOT_TO_INT(x) RF_LANES_TO_INT(x)
#define RF_DOT_FN(name) RF_LANES_FN(name)
#include "transport/dot_window.h"
#undef RF_DOT_INT
#undef RF_DOT_TO_REAL
#undef RF_DOT_TO_INT
#undef RF_DOT_FN
#endif

// Inserts (q, v) into a row held in registers, sorted by decreasing weight (after equal weights), dropping the
// weakest. Compare-and-shift network: slot k takes v when v beats it but not slot k-1, or slot k-1's entry when v
// beats that one too; going down from the last slot, every slot is computed from the old row, so the K slots update
// in parallel in hardware.
RF_INLINE void rf_insert_entry(int q, float v, int* index, float* weight) {
  RF_UNROLL
  for (int k = RF_K - 1; k > 0; --k) {
    if (v > weight[k]) {
      const int beats_previous = v > weight[k - 1];
      weight[k] = beats_previous ? weight[k - 1] : v;
      index[k] = beats_previous ? index[k - 1] : q;
    }
  }
  if (v > weight[0]) {
    weight[0] = v;
    index[0] = q;
  }
}

// The pixel and per-batch inputs of the dot-frame compression.
typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  int spacing;
  int projector_width;
  int projector_height;
  float noise_threshold;
} RfDotGrid;

// Pixel c's row emptied: index -1, weight 0 in every slot.
RF_INLINE void rf_empty_row(unsigned c, RF_GLOBAL RfEllIndices* indices, RF_GLOBAL RfEllWeights* weights) {
  RfEllIndices row_index;
  RfEllWeights row_weight;
  RF_UNROLL
  for (int k = 0; k < RF_K; ++k) {
    row_index.q[k] = -1;
    row_weight.w[k] = 0.0f;
  }
  indices[c] = row_index;
  weights[c] = row_weight;
}

// Pixel c's ELL row and energy updated with the batch's contributions, in the batch's order: frame f lit projector
// pixel dot[f] (-1: none) with value[f]. The row is read and written once, one word each (transport/ell_rows.h).
RF_INLINE void rf_dot_update_row(unsigned c, const float* value, const int* dot, RF_GLOBAL RfEllIndices* indices,
                                 RF_GLOBAL RfEllWeights* weights, RF_GLOBAL float* energy) {
  RfEllIndices row_index = indices[c];
  RfEllWeights row_weight = weights[c];
  int index[RF_K] RF_PARTITION_COMPLETE;
  float weight[RF_K] RF_PARTITION_COMPLETE;
  RF_UNROLL
  for (int k = 0; k < RF_K; ++k) {
    index[k] = row_index.q[k];
    weight[k] = row_weight.w[k];
  }
  float e = energy[c];
  RF_UNROLL
  for (int f = 0; f < RF_FRAME_BATCH; ++f) {
    if (dot[f] >= 0) {
      e += value[f];
      rf_insert_entry(dot[f], value[f], index, weight);
    }
  }
  RF_UNROLL
  for (int k = 0; k < RF_K; ++k) {
    row_index.q[k] = index[k];
    row_weight.w[k] = weight[k];
  }
  indices[c] = row_index;
  weights[c] = row_weight;
  energy[c] = e;
}

// Pixel c's samples of a batch of frame_count <= RF_FRAME_BATCH frames (sample[f], f < frame_count), whose dot
// offsets are offsets_x/offsets_y.
RF_INLINE void rf_dot_samples_pixel(unsigned c, const float* sample, int frame_count, const int* offsets_x,
                                    const int* offsets_y, RfDotGrid grid, RF_GLOBAL const float* black,
                                    RF_GLOBAL const unsigned char* flags, RF_GLOBAL const unsigned* projector_x,
                                    RF_GLOBAL const unsigned* projector_y, RF_GLOBAL RfEllIndices* indices,
                                    RF_GLOBAL RfEllWeights* weights, RF_GLOBAL float* energy) {
  if (!RF_COMPRESSIBLE(flags[c])) return;
  const int s = grid.spacing;
  const int x0 = rf_window_start((int)projector_x[c], s);
  const int y0 = rf_window_start((int)projector_y[c], s);
  const int ax = rf_window_residue(x0, s);
  const int ay = rf_window_residue(y0, s);
  const float dark = black[c];
  // The batch's contributions first: most pixels see no dot in most batches and keep their row untouched.
  float value[RF_FRAME_BATCH] RF_PARTITION_COMPLETE;
  int dot[RF_FRAME_BATCH] RF_PARTITION_COMPLETE;
  int reached = 0;
  RF_UNROLL
  for (int f = 0; f < RF_FRAME_BATCH; ++f) {
    const int qx = rf_window_dot(x0, ax, offsets_x[f], s);
    const int qy = rf_window_dot(y0, ay, offsets_y[f], s);
    const float v = f < frame_count ? sample[f] - dark : 0.0f;
    const int lit = f < frame_count && v > grid.noise_threshold && qx >= 0 && qx < grid.projector_width && qy >= 0 &&
                    qy < grid.projector_height;
    value[f] = lit ? v : 0.0f;
    dot[f] = lit ? qy * grid.projector_width + qx : -1;
    reached |= lit;
  }
  if (reached) rf_dot_update_row(c, value, dot, indices, weights, energy);
}

// The same with the batch pixel-major (common/frame_samples.h).
RF_INLINE void rf_dot_frames_pixel(unsigned c, int frame_count, const int* offsets_x, const int* offsets_y,
                                   RfDotGrid grid, RF_GLOBAL const RfFrameSamples* frames, RF_GLOBAL const float* black,
                                   RF_GLOBAL const unsigned char* flags, RF_GLOBAL const unsigned* projector_x,
                                   RF_GLOBAL const unsigned* projector_y, RF_GLOBAL RfEllIndices* indices,
                                   RF_GLOBAL RfEllWeights* weights, RF_GLOBAL float* energy) {
  const RfFrameSamples batch = frames[c];
  float sample[RF_FRAME_BATCH] RF_PARTITION_COMPLETE;
  RF_UNROLL
  for (int f = 0; f < RF_FRAME_BATCH; ++f) sample[f] = f < frame_count ? batch.sample[f] : 0.0f;
  rf_dot_samples_pixel(c, sample, frame_count, offsets_x, offsets_y, grid, black, flags, projector_x, projector_y,
                       indices, weights, energy);
}

#ifdef __OPENCL_VERSION__
// rf_insert_entry on RF_LANES rows at once, slot k of lane l's row in lane l of weight[k] and index[k]: lanes where
// `lit` is set take (q, v), the others keep their row. The same compare-and-shift network, with selects.
RF_INLINE void rf_insert_entry_lanes(int8 lit, int8 q, float8 v, int8* index, float8* weight) {
#pragma unroll
  for (int k = RF_K - 1; k > 0; --k) {
    const int8 beats = lit & (v > weight[k]);
    const int8 beats_previous = v > weight[k - 1];
    weight[k] = select(weight[k], select(v, weight[k - 1], beats_previous), beats);
    index[k] = select(index[k], select(q, index[k - 1], beats_previous), beats);
  }
  const int8 beats = lit & (v > weight[0]);
  weight[0] = select(weight[0], v, beats);
  index[0] = select(index[0], q, beats);
}

// The rows of pixels c0 .. c0 + RF_LANES - 1 into lanes, slot k of every row in index[k] and weight[k]. (Reading the
// rows' block as vectors and transposing it with shuffles was no faster on PoCL.)
RF_INLINE void rf_load_rows_lanes(unsigned c0, __global const int* indices, __global const float* weights, int8* index,
                                  float8* weight) {
  __global const int* row_index = indices + (size_t)c0 * RF_K;
  __global const float* row_weight = weights + (size_t)c0 * RF_K;
#pragma unroll
  for (int k = 0; k < RF_K; ++k) {
    index[k] =
        (int8)(row_index[k], row_index[RF_K + k], row_index[2 * RF_K + k], row_index[3 * RF_K + k],
               row_index[4 * RF_K + k], row_index[5 * RF_K + k], row_index[6 * RF_K + k], row_index[7 * RF_K + k]);
    weight[k] = (float8)(row_weight[k], row_weight[RF_K + k], row_weight[2 * RF_K + k], row_weight[3 * RF_K + k],
                         row_weight[4 * RF_K + k], row_weight[5 * RF_K + k], row_weight[6 * RF_K + k],
                         row_weight[7 * RF_K + k]);
  }
}

// The inverse of rf_load_rows_lanes: the lanes written back as rows.
RF_INLINE void rf_store_rows_lanes(unsigned c0, const int8* index, const float8* weight, __global int* indices,
                                   __global float* weights) {
  __global int* row_index = indices + (size_t)c0 * RF_K;
  __global float* row_weight = weights + (size_t)c0 * RF_K;
#pragma unroll
  for (int k = 0; k < RF_K; ++k) {
    int slot_index[RF_LANES];
    float slot_weight[RF_LANES];
    vstore8(index[k], 0, slot_index);
    vstore8(weight[k], 0, slot_weight);
#pragma unroll
    for (int l = 0; l < RF_LANES; ++l) {
      row_index[l * RF_K + k] = slot_index[l];
      row_weight[l * RF_K + k] = slot_weight[l];
    }
  }
}

// Empty rows (index -1, weight 0) for pixels c0 .. c0 + RF_LANES - 1: RF_LANES RF_K entries in a row, RF_K vectors.
RF_INLINE void rf_store_empty_rows_lanes(unsigned c0, __global int* indices, __global float* weights) {
#pragma unroll
  for (int k = 0; k < RF_K; ++k) {
    vstore8((int8)(-1), k, indices + (size_t)c0 * RF_K);
    vstore8((float8)(0.0f), k, weights + (size_t)c0 * RF_K);
  }
}

// The RF_LANES pixels c0 .. c0 + RF_LANES - 1 at once, one per vector lane, frame f of the batch at frames[f] (samples
// made linear with `map`). The noise test first, on every frame: a group that no frame lifts above the noise (most
// groups in most batches) stops there. Then the window arithmetic and the insertion, in lanes, for the frames that
// lift some lane; the rows are gathered into lanes (slot k of every row in one vector) and written back. With `fresh`
// (the capture's first batch) the rows start empty instead of being read, and every group writes its rows.
RF_INLINE void rf_dot_frames_lanes(unsigned c0, int fresh, int frame_count, const int* offsets_x, const int* offsets_y,
                                   RfDotGrid grid, __global const RF_SAMPLE* const* frames, RfSampleMap map,
                                   __global const float* black, __global const uchar* flags,
                                   __global const uint* projector_x, __global const uint* projector_y,
                                   __global int* indices, __global float* weights, __global float* energy) {
  const int8 compressible = RF_COMPRESSIBLE(convert_uint8(vload8(0, flags + c0)));
  if (!any(compressible)) {  // pixels the projector does not light read no frame
    if (fresh) rf_store_empty_rows_lanes(c0, indices, weights);
    return;
  }
  const float8 dark = vload8(0, black + c0);
  // Every frame's samples loaded before the first is used, so that their cache misses overlap (a profile on PoCL
  // showed the loads stalling one by one); unused frame buffers repeat frame 0, so every load is in bounds.
  float8 value[RF_FRAME_BATCH];
#pragma unroll
  for (int f = 0; f < RF_FRAME_BATCH; ++f) value[f] = rf_linear_sample_lanes(frames[f], c0, map) - dark;
  // The comparisons' masks (-1 or 0 per lane) combined bitwise: written with && between these vectors and the
  // scalar f < frame_count, no lane was ever lit under oclgrind (PoCL's were right).
  int8 above[RF_FRAME_BATCH];
  int8 any_above = 0;
#pragma unroll
  for (int f = 0; f < RF_FRAME_BATCH; ++f) {
    above[f] = (f < frame_count ? compressible : 0) & (value[f] > grid.noise_threshold);
    any_above |= above[f];
  }
  if (!any(any_above)) {
    if (fresh) rf_store_empty_rows_lanes(c0, indices, weights);
    return;
  }
  const int s = grid.spacing;
  const int8 x0 = RF_LANES_FN(rf_window_start)(convert_int8(vload8(0, projector_x + c0)), s);
  const int8 y0 = RF_LANES_FN(rf_window_start)(convert_int8(vload8(0, projector_y + c0)), s);
  const int8 ax = RF_LANES_FN(rf_window_residue)(x0, s);
  const int8 ay = RF_LANES_FN(rf_window_residue)(y0, s);
  int8 index[RF_K];
  float8 weight[RF_K];
  if (fresh) {
#pragma unroll
    for (int k = 0; k < RF_K; ++k) {
      index[k] = (int8)(-1);
      weight[k] = (float8)(0.0f);
    }
  } else {
    rf_load_rows_lanes(c0, indices, weights, index, weight);
  }
  float8 e = vload8(0, energy + c0);
#pragma unroll
  for (int f = 0; f < RF_FRAME_BATCH; ++f) {
    if (!any(above[f])) continue;
    const int8 qx = RF_LANES_FN(rf_window_dot)(x0, ax, offsets_x[f], s);
    const int8 qy = RF_LANES_FN(rf_window_dot)(y0, ay, offsets_y[f], s);
    const int8 lit = above[f] & (qx >= 0) & (qx < grid.projector_width) & (qy >= 0) & (qy < grid.projector_height);
    e = select(e, e + value[f], lit);
    rf_insert_entry_lanes(lit, qy * grid.projector_width + qx, value[f], index, weight);
  }
  vstore8(e, 0, energy + c0);
  rf_store_rows_lanes(c0, index, weight, indices, weights);
}
#endif

// The batch's RF_FRAME_BATCH (x, y) dot offsets, copied from `offsets` into private arrays.
RF_INLINE void rf_load_dot_offsets(RF_GLOBAL const int* offsets, int* offsets_x, int* offsets_y) {
  RF_UNROLL
  for (int f = 0; f < RF_FRAME_BATCH; ++f) {
    offsets_x[f] = offsets[2 * f];
    offsets_y[f] = offsets[2 * f + 1];
  }
}

// The single work-item loop over the n pixels: the batch's offsets copied on chip first.
RF_INLINE void rf_dot_frames_pixels(unsigned n, int frame_count, RF_GLOBAL const int* offsets, RfDotGrid grid,
                                    RF_GLOBAL const RfFrameSamples* frames, RF_GLOBAL const float* black,
                                    RF_GLOBAL const unsigned char* flags, RF_GLOBAL const unsigned* projector_x,
                                    RF_GLOBAL const unsigned* projector_y, RF_GLOBAL RfEllIndices* indices,
                                    RF_GLOBAL RfEllWeights* weights, RF_GLOBAL float* energy) {
  int offsets_x[RF_FRAME_BATCH] RF_PARTITION_COMPLETE;
  int offsets_y[RF_FRAME_BATCH] RF_PARTITION_COMPLETE;
  rf_load_dot_offsets(offsets, offsets_x, offsets_y);
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE  // one AXI beat each: the frame samples, the ELL row's indices and weights, read and written
    rf_dot_frames_pixel(c, frame_count, offsets_x, offsets_y, grid, frames, black, flags, projector_x, projector_y,
                        indices, weights, energy);
  }
}

// q / width for 0 <= q, without a divider: the float estimate q * (1 / width) lies within 0.001 of the quotient (a
// relative error of a few float epsilons on a quotient below 2^14), so its floor is off by at most one, and corrected.
RF_INLINE int rf_row_of(int q, int width, float inverse_width) {
  int y = (int)((float)q * inverse_width);
  if (y * width > q) {
    --y;
  } else if ((y + 1) * width <= q) {
    ++y;
  }
  return y;
}

// Gray-code-only captures (has_dots == 0) first get their single entry T[c, p(c)] = white - black. Then the
// correspondence is the weight-averaged projector pixel centre of the entries (NaN without any), and lit in-range
// pixels without an entry are flagged RF_FLAG_NO_SIGNAL.
RF_INLINE void rf_finalize_pixel(unsigned c, float white, float black, int has_dots, int projector_width,
                                 float inverse_width, float noise_threshold, RF_GLOBAL unsigned char* flags,
                                 RF_GLOBAL const unsigned* projector_x, RF_GLOBAL const unsigned* projector_y,
                                 RF_GLOBAL RfEllIndices* indices, RF_GLOBAL RfEllWeights* weights,
                                 RF_GLOBAL float* energy, RF_GLOBAL RfCorrespondence* correspondence) {
  const int valid = (flags[c] & (unsigned char)RF_FLAG_VALID) != 0;
  const float lit = white - black;
  RfEllIndices row_index = indices[c];
  RfEllWeights row_weight = weights[c];
  if (valid && has_dots == 0 && lit > noise_threshold) {
    row_index.q[0] = (int)(projector_y[c] * (unsigned)projector_width + projector_x[c]);
    row_weight.w[0] = lit;
    indices[c].q[0] = row_index.q[0];  // the one slot written (a byte-enabled part of the word on a board)
    weights[c].w[0] = lit;
    energy[c] = lit;
  }
  float sum = 0.0f;
  float sum_x = 0.0f;
  float sum_y = 0.0f;
  RF_UNROLL
  for (int k = 0; k < RF_K; ++k) {
    const int q = row_index.q[k];
    if (q >= 0) {
      const float w = row_weight.w[k];
      const int y = rf_row_of(q, projector_width, inverse_width);
      sum += w;
      sum_x += w * (float)(q - y * projector_width);
      sum_y += w * (float)y;
    }
  }
  const int found = sum > 0.0f;
  RfCorrespondence point;
  point.x = found ? sum_x / sum : NAN;
  point.y = found ? sum_y / sum : NAN;
  correspondence[c] = point;
  if (RF_COMPRESSIBLE(flags[c]) && !found) flags[c] |= (unsigned char)RF_FLAG_NO_SIGNAL;
}

RF_INLINE void rf_finalize_pixels(unsigned n, RF_GLOBAL const float* white, RF_GLOBAL const float* black, int has_dots,
                                  int projector_width, float noise_threshold, RF_GLOBAL unsigned char* flags,
                                  RF_GLOBAL const unsigned* projector_x, RF_GLOBAL const unsigned* projector_y,
                                  RF_GLOBAL RfEllIndices* indices, RF_GLOBAL RfEllWeights* weights,
                                  RF_GLOBAL float* energy, RF_GLOBAL RfCorrespondence* correspondence) {
  const float inverse_width = 1.0f / (float)projector_width;
  RF_PIPELINE_II(1)
  for (unsigned c = 0; c < n; ++c) {
    RF_HLS_PIPELINE  // one AXI beat each: the ELL row's indices and weights, the correspondence
    rf_finalize_pixel(c, white[c], black[c], has_dots, projector_width, inverse_width, noise_threshold, flags,
                      projector_x, projector_y, indices, weights, energy, correspondence);
  }
}

#endif  // RFRECON_KERNELS_TRANSPORT_COMPRESSION_H
