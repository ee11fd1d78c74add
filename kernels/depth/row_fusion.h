// Fusion of triangulated positions and integrated slopes on one rectified row (docs/method.md), shared by the OpenCL
// kernels (kernels/depth/fuse.cl), the HLS C++ top (hw/hls/) and the C++ reference (host/depth/row_solvers.cc).
//
// Per run, minimise  sum_i lambda_i (z_i - t_i)^2 + mu sum_i (z_{i+1} - z_i - h_i(z_i))^2  where t_i is the
// triangulated depth, h_i the RK4 increment of the reciprocity ODE from pixel i, lambda_i = 1 / sigma_z,i^2 with
// sigma_z,i = z_i^2 sigma_d / (f |b|) (depth noise of a disparity noise sigma_d) and mu = 1 / sigma_h^2. Each
// iteration linearises h_i around the current z (h_i' by a finite difference) and solves the tridiagonal normal
// equations for the update with the Thomas algorithm; solving for the update keeps float precision. A link whose ODE
// breaks down gets no slope term. Iterations start from z (for instance the integrated depth).
//
// Runs are independent, so an iteration sweeps the whole row: forward (elimination) left to right over every pixel
// that is not masked, restarting at each run's first pixel, then backward (substitution) right to left. Both sweeps
// visit every pixel once, with no data-dependent loop bounds.
#ifndef RFRECON_KERNELS_DEPTH_ROW_FUSION_H
#define RFRECON_KERNELS_DEPTH_ROW_FUSION_H

#include "depth/reciprocity.h"
#include "depth/row_runs.h"

// Relative depth step of the finite difference that gives h_i'.
#define RF_FUSION_DIFF_STEP 1e-3f

// Constants of a fusion, computed once (outside the sweeps: no division by a run-time value in them).
typedef struct {            // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  float mu;                 // weight of a slope link, 1 / sigma_step^2, 1/mm^2
  float depth_noise_scale;  // sigma_z / z^2 = sigma_d / (f |b|), 1/mm
} RfFusionWeights;

RF_INLINE RfFusionWeights rf_fusion_weights(RfRectifiedRig rig, float sigma_disparity_px, float sigma_step_mm) {
  RfFusionWeights weights;
  weights.mu = 1.0f / (sigma_step_mm * sigma_step_mm);
  weights.depth_noise_scale = sigma_disparity_px / (rig.f * RF_FABS(rig.b));
  return weights;
}

// The forward sweep's state at the previous pixel of the run.
typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  float mu;       // weight of the link from the previous pixel to this one (0 where it has none)
  float a;        // its linearised slope 1 + h'
  float r;        // its residual
  float c, d;     // the Thomas forward sweep's coefficients at the previous pixel
} RfSweepState;

RF_INLINE void rf_sweep_state_init(RfSweepState* state) {
  state->mu = 0.0f;
  state->a = 0.0f;
  state->r = 0.0f;
  state->c = 0.0f;
  state->d = 0.0f;
}

// Run structure at pixel u (not masked) from its code and its neighbours' (prev_code for u - 1, next_code for
// u + 1; any value where the neighbour is outside the row): a run starts after a masked pixel or at RF_RUN_START,
// and ends before a pixel that does not continue it.
RF_INLINE int rf_fusion_run_starts(int u, unsigned int code, unsigned int prev_code) {
  return u == 0 || prev_code == RF_RUN_MASKED || code != RF_RUN_CONTINUE;
}
RF_INLINE int rf_fusion_run_ends(int u, int width, unsigned int next_code) {
  return u + 1 >= width || next_code != RF_RUN_CONTINUE;
}

// The backward sweep at a pixel: the update of z there, from the one at the next pixel of the run.
RF_INLINE float rf_fuse_backward(int run_ends, float c, float d, float next_update) {
  return run_ends ? d : d - c * next_update;
}

#define RF_ROW_SPACE RF_GLOBAL
#define RF_ROW_FN(name) name
#include "depth/row_fusion_rows.h"
#undef RF_ROW_SPACE
#undef RF_ROW_FN
#ifdef __OPENCL_VERSION__
#define RF_ROW_SPACE
#define RF_ROW_FN(name) RF_ON_CHIP(name)
#include "depth/row_fusion_rows.h"
#undef RF_ROW_SPACE
#undef RF_ROW_FN
#endif

// The whole row: `iterations` linearised solves of every run. z_row holds the start on entry (finite wherever the
// run code is not RF_RUN_MASKED) and the fused depth on return. c_row and d_row are scratch of the row's width.
RF_INLINE void rf_fuse_row(RfRectifiedRig rig, float beta, int width, int proj_width, int iterations,
                           float sigma_disparity_px, float sigma_step_mm, RF_GLOBAL const float* e_cam_row,
                           RF_GLOBAL const float* e_proj_row, RF_GLOBAL const float* z_tri_row,
                           RF_GLOBAL const unsigned char* run_row, RF_GLOBAL float* z_row, RF_GLOBAL float* c_row,
                           RF_GLOBAL float* d_row) {
  const RfFusionWeights weights = rf_fusion_weights(rig, sigma_disparity_px, sigma_step_mm);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    RfSweepState state;
    rf_sweep_state_init(&state);
    for (int u = 0; u < width; ++u) {
      const unsigned int code = run_row[u];
      if (code == RF_RUN_MASKED) continue;
      if (rf_fusion_run_starts(u, code, u > 0 ? run_row[u - 1] : 0u)) rf_sweep_state_init(&state);
      const int run_ends = rf_fusion_run_ends(u, width, u + 1 < width ? run_row[u + 1] : 0u);
      rf_fuse_forward(rig, beta, u, run_ends, proj_width, weights, e_cam_row, e_proj_row, z_row[u],
                      run_ends ? 0.0f : z_row[u + 1], z_tri_row[u], &state);
      c_row[u] = state.c;
      d_row[u] = state.d;
    }
    float update = 0.0f;
    for (int u = width - 1; u >= 0; --u) {
      if (run_row[u] == RF_RUN_MASKED) continue;
      update = rf_fuse_backward(rf_fusion_run_ends(u, width, u + 1 < width ? run_row[u + 1] : 0u), c_row[u], d_row[u],
                                update);
      z_row[u] += update;
    }
  }
}

#endif  // RFRECON_KERNELS_DEPTH_ROW_FUSION_H
