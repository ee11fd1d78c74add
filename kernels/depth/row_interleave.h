// The single work-item bodies of the depth kernels, shared by the OpenCL single work-item entries
// (kernels/depth/integrate.cl, fuse.cl) and the HLS C++ tops (hw/hls/): RF_ROW_INTERLEAVE rows of the tile at a time
// are copied into on-chip buffers, solved with their pixels interleaved (iteration i handles pixel i / R of row
// i % R, R = RF_ROW_INTERLEAVE), so that the dependency of a row's pixel on the previous one lies R iterations apart
// and a pipeline can start one iteration per clock once R covers the step's latency (docs/fpga.md), and written back
// once. Every pipelined loop has a trip count fixed at its entry (R x width); no loop depends on the data, none
// divides by a run-time value, none reads and writes global memory.
//
// Rows up to RF_MAX_ROW_WIDTH pixels, camera and projector; R and the width come from common/params.h.
#ifndef RFRECON_KERNELS_DEPTH_ROW_INTERLEAVE_H
#define RFRECON_KERNELS_DEPTH_ROW_INTERLEAVE_H

#include "common/params.h"
#include "common/target.h"
#include "depth/row_fusion.h"
#include "depth/row_integration.h"

// The on-chip buffers: one row of each input per interleaved row.
#define RF_ROW_BUFFER (RF_ROW_INTERLEAVE * RF_MAX_ROW_WIDTH)

// The Vitis HLS dependence directive of the interleaved loops (RF_HLS_PIPELINE: kernels/common/target.h).
// clang-format off
#if defined(RF_TARGET_HLS)
#define RF_HLS_DEPENDENCE(var) RF_PRAGMA_(HLS DEPENDENCE variable=var inter RAW distance=RF_ROW_INTERLEAVE true)
#else
#define RF_HLS_DEPENDENCE(var)
#endif
// clang-format on

// beta = (v - cy) / f of each row of the group starting at tile row r0 (the divisions outside the pixel loops).
RF_INLINE void rf_group_betas(RfRectifiedRig rig, int first_row, int r0, float* betas) {
  for (int k = 0; k < RF_ROW_INTERLEAVE; ++k) betas[k] = ((float)(first_row + r0 + k) - rig.cy) / rig.f;
}

// Copies a group of `group` rows of the tile (starting at the pointers given) into the on-chip buffers, z too when
// z_start is not null (the fusion's starting depth), in pipelined loops of fixed trip count.
RF_INLINE void rf_load_row_group(int group, int width, int proj_width, RF_GLOBAL const float* e_cam,
                                 RF_GLOBAL const float* e_proj, RF_GLOBAL const float* z_tri,
                                 RF_GLOBAL const unsigned char* runs, RF_GLOBAL const float* z_start, float* e_cam_rows,
                                 float* e_proj_rows, float* z_tri_rows, unsigned char* run_rows, float* z_rows) {
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
    e_proj_rows[i] = e_proj[i];
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
// rf_integrate_row.
RF_INLINE void rf_integrate_rows_interleaved(RfRectifiedRig rig, int first_row, int rows, int width, int proj_width,
                                             int passes, RF_GLOBAL const float* e_cam, RF_GLOBAL const float* e_proj,
                                             RF_GLOBAL const float* z_tri, RF_GLOBAL const unsigned char* runs,
                                             RF_GLOBAL float* z) {
  float e_cam_rows[RF_ROW_BUFFER], e_proj_rows[RF_ROW_BUFFER], z_tri_rows[RF_ROW_BUFFER], z_rows[RF_ROW_BUFFER];
  unsigned char run_rows[RF_ROW_BUFFER];
  for (int r0 = 0; r0 < rows; r0 += RF_ROW_INTERLEAVE) {
    const int group = rows - r0 < RF_ROW_INTERLEAVE ? rows - r0 : RF_ROW_INTERLEAVE;
    const size_t base = (size_t)r0 * (size_t)width, proj_base = (size_t)r0 * (size_t)proj_width;
    rf_load_row_group(group, width, proj_width, e_cam + base, e_proj + proj_base, z_tri + base, runs + base, 0,
                      e_cam_rows, e_proj_rows, z_tri_rows, run_rows, z_rows);
    float betas[RF_ROW_INTERLEAVE];
    rf_group_betas(rig, first_row, r0, betas);
    for (int pass = 0; pass < passes; ++pass) {
      RfRunState states[RF_ROW_INTERLEAVE] RF_PARTITION_COMPLETE;
      for (int k = 0; k < RF_ROW_INTERLEAVE; ++k) rf_run_state_init(&states[k]);
      RF_IVDEP_SAFELEN(RF_ROW_INTERLEAVE)
      RF_PIPELINE_II(1)
      for (int i = 0, u = 0, k = 0; i < width * RF_ROW_INTERLEAVE; ++i) {
        RF_HLS_PIPELINE
        RF_HLS_DEPENDENCE(z_rows)
        RF_HLS_DEPENDENCE(states)
        if (k < group) {
          const int row = k * width;
          RF_ON_CHIP(rf_integrate_pixel)
          (rig, betas[k], u, proj_width, pass, passes, e_cam_rows + row, e_proj_rows + k * proj_width, z_tri_rows + row,
           run_rows + row, z_rows + row, &states[k]);
        }
        if (++k == RF_ROW_INTERLEAVE) {
          k = 0;
          ++u;
        }
      }
      for (int k = 0; k < group; ++k) RF_ON_CHIP(rf_close_run)(&states[k], z_rows + k * width, pass + 1 < passes);
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
  float e_cam_rows[RF_ROW_BUFFER], e_proj_rows[RF_ROW_BUFFER], z_tri_rows[RF_ROW_BUFFER], z_rows[RF_ROW_BUFFER];
  float c_rows[RF_ROW_BUFFER], d_rows[RF_ROW_BUFFER];
  unsigned char run_rows[RF_ROW_BUFFER];
  const RfFusionWeights weights = rf_fusion_weights(rig, sigma_disparity_px, sigma_step_mm);
  for (int r0 = 0; r0 < rows; r0 += RF_ROW_INTERLEAVE) {
    const int group = rows - r0 < RF_ROW_INTERLEAVE ? rows - r0 : RF_ROW_INTERLEAVE;
    const size_t base = (size_t)r0 * (size_t)width, proj_base = (size_t)r0 * (size_t)proj_width;
    rf_load_row_group(group, width, proj_width, e_cam + base, e_proj + proj_base, z_tri + base, runs + base, z + base,
                      e_cam_rows, e_proj_rows, z_tri_rows, run_rows, z_rows);
    float betas[RF_ROW_INTERLEAVE];
    rf_group_betas(rig, first_row, r0, betas);
    for (int iteration = 0; iteration < iterations; ++iteration) {
      RfSweepState sweeps[RF_ROW_INTERLEAVE] RF_PARTITION_COMPLETE;
      for (int k = 0; k < RF_ROW_INTERLEAVE; ++k) rf_sweep_state_init(&sweeps[k]);
      RF_IVDEP_SAFELEN(RF_ROW_INTERLEAVE)
      RF_PIPELINE_II(1)
      for (int i = 0, u = 0, k = 0; i < width * RF_ROW_INTERLEAVE; ++i) {
        RF_HLS_PIPELINE
        RF_HLS_DEPENDENCE(sweeps)
        const int at = k * width + u;
        if (k < group && run_rows[at] != RF_RUN_MASKED) {
          if (rf_fusion_run_starts(u, run_rows[at], u > 0 ? run_rows[at - 1] : 0u)) rf_sweep_state_init(&sweeps[k]);
          const int run_ends = rf_fusion_run_ends(u, width, u + 1 < width ? run_rows[at + 1] : 0u);
          RF_ON_CHIP(rf_fuse_forward)
          (rig, betas[k], u, run_ends, proj_width, weights, e_cam_rows + k * width, e_proj_rows + k * proj_width,
           z_rows[at], run_ends ? 0.0f : z_rows[at + 1], z_tri_rows[at], &sweeps[k]);
          c_rows[at] = sweeps[k].c;
          d_rows[at] = sweeps[k].d;
        }
        if (++k == RF_ROW_INTERLEAVE) {
          k = 0;
          ++u;
        }
      }
      float updates[RF_ROW_INTERLEAVE] RF_PARTITION_COMPLETE;
      for (int k = 0; k < RF_ROW_INTERLEAVE; ++k) updates[k] = 0.0f;
      RF_IVDEP_SAFELEN(RF_ROW_INTERLEAVE)
      RF_PIPELINE_II(1)
      for (int i = 0, u = width - 1, k = 0; i < width * RF_ROW_INTERLEAVE; ++i) {
        RF_HLS_PIPELINE
        RF_HLS_DEPENDENCE(updates)
        const int at = k * width + u;
        if (k < group && run_rows[at] != RF_RUN_MASKED) {
          const int run_ends = rf_fusion_run_ends(u, width, u + 1 < width ? run_rows[at + 1] : 0u);
          updates[k] = rf_fuse_backward(run_ends, c_rows[at], d_rows[at], updates[k]);
          z_rows[at] += updates[k];
        }
        if (++k == RF_ROW_INTERLEAVE) {
          k = 0;
          --u;
        }
      }
    }
    rf_store_row_group(group, width, z_rows, z + base);
  }
}

#endif  // RFRECON_KERNELS_DEPTH_ROW_INTERLEAVE_H
