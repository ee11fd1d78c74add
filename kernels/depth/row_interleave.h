// The single work-item bodies of the depth kernels, shared by the OpenCL single work-item entries
// (kernels/depth/integrate.cl, fuse.cl) and the HLS C++ tops (hw/hls/): R rows of the tile at a time are copied into
// on-chip buffers, solved with their rows interleaved so that a row's next dependent iteration lies R iterations
// later, and written back once. R is per kernel, sized from its loop's latency (docs/fpga.md#pipelines-of-the-single-
// work-item-entries): the integration evaluates one RK4 slope per iteration (iteration i: row i % R, slope
// (i / R) % 4 of the step into pixel i / 4R), R = RF_INTEGRATE_INTERLEAVE; the fusion's sweeps handle one pixel per
// iteration (row i % R, pixel i / R), R = RF_FUSE_INTERLEAVE. With R at least the latency of the dependency from one
// iteration to its row's next, a pipeline starts one iteration per clock. Every pipelined loop has a trip count fixed
// at its entry; no loop depends on the data, none divides by a run-time value, none reads and writes global memory.
//
// Rows up to RF_MAX_ROW_WIDTH pixels, camera and projector; R and the width come from common/params.h.
// On AMD boards the largest read-only rows (the integration's e_cam, e_proj and z_tri, the fusion's copies of e_proj)
// are bound to UltraRAM and the rest to block RAM (RF_IN_URAM), so that each depth kernel fits one SLR of a U250 or a
// U280 at the widths of their presets (scripts/fpga_budget.py, docs/fpga.md#resource-budget).
#ifndef RFRECON_KERNELS_DEPTH_ROW_INTERLEAVE_H
#define RFRECON_KERNELS_DEPTH_ROW_INTERLEAVE_H

#include "common/params.h"
#include "common/target.h"
#include "depth/row_buffers.h"
#include "depth/row_fusion.h"
#include "depth/row_integration.h"

// The RK4 slopes of one step, one per iteration of the integration's interleaved loop.
#define RF_RK4_STAGES 4

// beta = (v - cy) / f of each of the `interleave` rows of the group starting at tile row r0 (the divisions outside the
// pixel loops).
RF_INLINE void rf_group_betas(RfRectifiedRig rig, int first_row, int r0, int interleave, float* betas) {
  for (int k = 0; k < interleave; ++k) betas[k] = ((float)(first_row + r0 + k) - rig.cy) / rig.f;
}

// Copies a group of `group` rows of the tile (starting at the pointers given) into the on-chip buffers, z too when
// z_start is not null (the fusion's starting depth), e_proj into `e_proj_copies` copies `copy_stride` floats apart,
// in pipelined loops of fixed trip count.
RF_INLINE void rf_load_row_group(int group, int width, int proj_width, int e_proj_copies, int copy_stride,
                                 RF_GLOBAL const float* e_cam, RF_GLOBAL const float* e_proj,
                                 RF_GLOBAL const float* z_tri, RF_GLOBAL const unsigned char* runs,
                                 RF_GLOBAL const float* z_start, float* e_cam_rows, float* e_proj_rows,
                                 float* z_tri_rows, unsigned char* run_rows, float* z_rows) {
  RF_PIPELINE_II(1)
  for (int i = 0; i < group * width; ++i) {
    RF_HLS_PIPELINE
    e_cam_rows[i] = e_cam[i];
    z_tri_rows[i] = z_tri[i];
    run_rows[i] = runs[i];
    if (z_start) z_rows[i] = z_start[i];
  }
  RF_PIPELINE_II(1)
  for (int i = 0; i < group * proj_width; ++i) {
    RF_HLS_PIPELINE
    const float e = e_proj[i];
    RF_UNROLL
    for (int c = 0; c < e_proj_copies; ++c) e_proj_rows[c * copy_stride + i] = e;
  }
}

// Writes the group's depths back, once.
RF_INLINE void rf_store_row_group(int group, int width, const float* z_rows, RF_GLOBAL float* z) {
  RF_PIPELINE_II(1)
  for (int i = 0; i < group * width; ++i) {
    RF_HLS_PIPELINE
    z[i] = z_rows[i];
  }
}

// Integration of the tile's rows (layout of kernels/depth/integrate.cl), the same arithmetic per row as
// rf_integrate_row: each iteration evaluates one slope of one row's RK4 step (rf_rk4_stage), the last slope also
// finishes the row's pixel (rf_integrate_pixel_step). The slopes of a step into a run's first pixel, or into a masked
// one, are evaluated and not used, so that every iteration does the same work.
RF_INLINE void rf_integrate_rows_interleaved(RfRectifiedRig rig, int first_row, int rows, int width, int proj_width,
                                             int passes, RF_GLOBAL const float* e_cam, RF_GLOBAL const float* e_proj,
                                             RF_GLOBAL const float* z_tri, RF_GLOBAL const unsigned char* runs,
                                             RF_GLOBAL float* z) {
  RF_HLS_STATIC float e_cam_rows[RF_INTEGRATE_BUFFER], e_proj_rows[RF_INTEGRATE_BUFFER],
      z_tri_rows[RF_INTEGRATE_BUFFER];
  RF_HLS_STATIC float z_rows[RF_INTEGRATE_BUFFER];
  RF_HLS_STATIC unsigned char run_rows[RF_INTEGRATE_BUFFER];
  RF_ON_CHIP_RAM(e_cam_rows)
  RF_IN_URAM(e_cam_rows)
  RF_ON_CHIP_RAM(e_proj_rows)
  RF_IN_URAM(e_proj_rows)
  RF_ON_CHIP_RAM(z_tri_rows)
  RF_IN_URAM(z_tri_rows)
  RF_ON_CHIP_RAM(z_rows)
  RF_ON_CHIP_RAM(run_rows)
  for (int r0 = 0; r0 < rows; r0 += RF_INTEGRATE_INTERLEAVE) {
    const int group = rows - r0 < RF_INTEGRATE_INTERLEAVE ? rows - r0 : RF_INTEGRATE_INTERLEAVE;
    const size_t base = (size_t)r0 * (size_t)width, proj_base = (size_t)r0 * (size_t)proj_width;
    rf_load_row_group(group, width, proj_width, 1, 0, e_cam + base, e_proj + proj_base, z_tri + base, runs + base, 0,
                      e_cam_rows, e_proj_rows, z_tri_rows, run_rows, z_rows);
    float betas[RF_INTEGRATE_INTERLEAVE];
    RF_ON_CHIP_RAM(betas)
    rf_group_betas(rig, first_row, r0, RF_INTEGRATE_INTERLEAVE, betas);
    for (int pass = 0; pass < passes; ++pass) {
      // In on-chip RAM, not registers: one element of each is read and written per iteration. z_befores[k] holds what
      // z_rows held at row k's pixel before this pass, read at the step's first slope, so that the last slope's
      // iteration touches z_rows twice (the pixel's depth, a closing run's seed) and no more.
      RfRunState states[RF_INTEGRATE_INTERLEAVE];
      RfRk4Stages steps[RF_INTEGRATE_INTERLEAVE];
      float z_befores[RF_INTEGRATE_INTERLEAVE];
      RF_ON_CHIP_RAM(states)
      RF_ON_CHIP_RAM(steps)
      RF_ON_CHIP_RAM(z_befores)
      for (int k = 0; k < RF_INTEGRATE_INTERLEAVE; ++k) {
        rf_run_state_init(&states[k]);
        steps[k].k_last = 0.0f;
        steps[k].sum = 0.0f;
        steps[k].ok = 1;
        z_befores[k] = 0.0f;
      }
      RF_IVDEP_SAFELEN(RF_INTEGRATE_INTERLEAVE)
      RF_PIPELINE_II(1)
      for (int i = 0, u = 0, stage = 0, k = 0; i < width * RF_RK4_STAGES * RF_INTEGRATE_INTERLEAVE; ++i) {
        RF_HLS_PIPELINE
        RF_HLS_DEPENDENCE(z_rows, RF_INTEGRATE_INTERLEAVE)
        RF_HLS_DEPENDENCE(states, RF_INTEGRATE_INTERLEAVE)
        RF_HLS_DEPENDENCE(steps, RF_INTEGRATE_INTERLEAVE)
        RF_HLS_DEPENDENCE(z_befores, RF_INTEGRATE_INTERLEAVE)
        if (k < group) {  // row k's state and step read once and written back once
          const int row = k * width, from = u > 0 ? u - 1 : 0;
          RfRunState state = states[k];
          RfRk4Stages step = steps[k];
          if (stage == 0 && pass > 0) z_befores[k] = z_rows[row + u];
          RF_ON_CHIP(rf_rk4_stage)
          (rig, betas[k], from, stage, state.z, e_cam_rows[row + from], e_cam_rows[row + u],
           e_proj_rows + k * proj_width, proj_width, &step);
          if (stage == RF_RK4_STAGES - 1) {
            RF_ON_CHIP(rf_integrate_pixel_step)
            (u, pass, passes, run_rows[row + u], z_tri_rows[row + u], z_befores[k], step.sum * (1.0f / 6.0f), step.ok,
             z_rows + row, &state);
          }
          states[k] = state;
          steps[k] = step;
        }
        if (++k == RF_INTEGRATE_INTERLEAVE) {
          k = 0;
          if (++stage == RF_RK4_STAGES) {
            stage = 0;
            ++u;
          }
        }
      }
      for (int k = 0; k < group; ++k) {
        RF_ON_CHIP(rf_close_run)(&states[k], z_rows + k * width, states[k].start >= 0, pass + 1 < passes);
      }
    }
    rf_store_row_group(group, width, z_rows, z + base);
  }
}

// Fusion of the tile's rows (layout of kernels/depth/fuse.cl; z holds the start on entry and the result on return),
// the same arithmetic per row as rf_fuse_row, its scratch on chip.
RF_INLINE void rf_fuse_rows_interleaved(RfRectifiedRig rig, int first_row, int rows, int width, int proj_width,
                                        int iterations, float sigma_disparity_px, float sigma_step_mm,
                                        RF_GLOBAL const float* e_cam, RF_GLOBAL const float* e_proj,
                                        RF_GLOBAL const float* z_tri, RF_GLOBAL const unsigned char* runs,
                                        RF_GLOBAL float* z) {
  // e_proj_rows holds one copy of the rows per slope of the forward sweep's two RK4 increments: each slope's two
  // gathers take the two ports of its own copy.
  RF_HLS_STATIC float e_cam_rows[RF_FUSE_BUFFER], e_proj_rows[RF_FUSE_SLOPES * RF_FUSE_BUFFER],
      z_tri_rows[RF_FUSE_BUFFER];
  RF_HLS_STATIC float z_rows[RF_FUSE_BUFFER], c_rows[RF_FUSE_BUFFER], d_rows[RF_FUSE_BUFFER];
  RF_HLS_STATIC unsigned char run_rows[RF_FUSE_BUFFER];
  RF_ON_CHIP_RAM(e_cam_rows)
  RF_ON_CHIP_BANKS(e_proj_rows, RF_FUSE_SLOPES)
  RF_IN_URAM(e_proj_rows)
  RF_ON_CHIP_RAM(z_tri_rows)
  RF_ON_CHIP_RAM(z_rows)
  RF_ON_CHIP_RAM(c_rows)
  RF_ON_CHIP_RAM(d_rows)
  RF_ON_CHIP_RAM(run_rows)
  const RfFusionWeights weights = rf_fusion_weights(rig, sigma_disparity_px, sigma_step_mm);
  for (int r0 = 0; r0 < rows; r0 += RF_FUSE_INTERLEAVE) {
    const int group = rows - r0 < RF_FUSE_INTERLEAVE ? rows - r0 : RF_FUSE_INTERLEAVE;
    const size_t base = (size_t)r0 * (size_t)width, proj_base = (size_t)r0 * (size_t)proj_width;
    rf_load_row_group(group, width, proj_width, RF_FUSE_SLOPES, RF_FUSE_BUFFER, e_cam + base, e_proj + proj_base,
                      z_tri + base, runs + base, z + base, e_cam_rows, e_proj_rows, z_tri_rows, run_rows, z_rows);
    float betas[RF_FUSE_INTERLEAVE];
    RF_ON_CHIP_RAM(betas)
    rf_group_betas(rig, first_row, r0, RF_FUSE_INTERLEAVE, betas);
    for (int iteration = 0; iteration < iterations; ++iteration) {
      // In on-chip RAM, not registers (a dependence through registers cannot be waived): one element of each is read
      // and written per iteration. codes[k] and next_codes[k] carry the run codes at row k's pixel and the next one,
      // so that the sweep reads one code of run_rows per pixel.
      RfSweepState sweeps[RF_FUSE_INTERLEAVE];
      unsigned char codes[RF_FUSE_INTERLEAVE], next_codes[RF_FUSE_INTERLEAVE];
      RF_ON_CHIP_RAM(sweeps)
      RF_ON_CHIP_RAM(codes)
      RF_ON_CHIP_RAM(next_codes)
      for (int k = 0; k < RF_FUSE_INTERLEAVE; ++k) rf_sweep_state_init(&sweeps[k]);
      RF_IVDEP_SAFELEN(RF_FUSE_INTERLEAVE)
      RF_PIPELINE_II(1)
      for (int i = 0, u = 0, k = 0; i < width * RF_FUSE_INTERLEAVE; ++i) {
        RF_HLS_PIPELINE
        RF_HLS_DEPENDENCE(sweeps, RF_FUSE_INTERLEAVE)
        RF_HLS_DEPENDENCE(codes, RF_FUSE_INTERLEAVE)
        RF_HLS_DEPENDENCE(next_codes, RF_FUSE_INTERLEAVE)
        const int at = k * width + u;
        int code = RF_RUN_MASKED, prev_code = RF_RUN_MASKED, next_code = RF_RUN_MASKED;
        if (k < group) {
          code = u > 0 ? next_codes[k] : run_rows[at];
          prev_code = u > 0 ? codes[k] : RF_RUN_MASKED;
          next_code = u + 1 < width ? run_rows[at + 1] : RF_RUN_MASKED;
          codes[k] = (unsigned char)code;
          next_codes[k] = (unsigned char)next_code;
        }
        if (code != RF_RUN_MASKED) {  // row k's sweep state read once and written back once
          RfSweepState sweep = sweeps[k];
          if (rf_fusion_run_starts(code, prev_code)) rf_sweep_state_init(&sweep);
          const int run_ends = rf_fusion_run_ends(next_code);
          RF_ON_CHIP(rf_fuse_forward)
          (rig, betas[k], u, width, run_ends == 0, proj_width, weights, e_cam_rows + k * width,
           e_proj_rows + k * proj_width, RF_FUSE_BUFFER, z_rows[at], run_ends ? 0.0f : z_rows[at + 1], z_tri_rows[at],
           &sweep);
          sweeps[k] = sweep;
          c_rows[at] = sweep.c;
          d_rows[at] = sweep.d;
        }
        if (++k == RF_FUSE_INTERLEAVE) {
          k = 0;
          ++u;
        }
      }
      float updates[RF_FUSE_INTERLEAVE];
      RF_ON_CHIP_RAM(updates)
      for (int k = 0; k < RF_FUSE_INTERLEAVE; ++k) updates[k] = 0.0f;
      RF_IVDEP_SAFELEN(RF_FUSE_INTERLEAVE)
      RF_PIPELINE_II(1)
      for (int i = 0, u = width - 1, k = 0; i < width * RF_FUSE_INTERLEAVE; ++i) {
        RF_HLS_PIPELINE
        RF_HLS_DEPENDENCE(updates, RF_FUSE_INTERLEAVE)
        RF_HLS_DEPENDENCE(z_rows, RF_FUSE_INTERLEAVE)
        const int at = k * width + u;
        if (k < group && run_rows[at] != RF_RUN_MASKED) {
          const int run_ends = rf_fusion_run_ends(u + 1 < width ? run_rows[at + 1] : RF_RUN_MASKED);
          updates[k] = rf_fuse_backward(run_ends, c_rows[at], d_rows[at], updates[k]);
          z_rows[at] += updates[k];
        }
        if (++k == RF_FUSE_INTERLEAVE) {
          k = 0;
          --u;
        }
      }
    }
    rf_store_row_group(group, width, z_rows, z + base);
  }
}

#endif  // RFRECON_KERNELS_DEPTH_ROW_INTERLEAVE_H
