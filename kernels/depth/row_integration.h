// Reciprocity integration of one rectified row (the paper's method, docs/method.md), shared by the OpenCL kernels
// (kernels/depth/integrate.cl) and the C++ reference (host/depth/row_solvers.cc).
//
// Each run is integrated left to right with RK4 from its seed. The seed starts as the triangulated depth of the run's
// first pixel; after each pass but the last it is rescaled so that the run's mean relative difference to the
// triangulated depths is zero (a shooting method: z(u) scales almost linearly with the seed). The seed of a run is
// kept in z[start] between passes. A step whose ODE breaks down keeps the depth of the previous pixel.
#ifndef RFRECON_KERNELS_DEPTH_ROW_INTEGRATION_H
#define RFRECON_KERNELS_DEPTH_ROW_INTEGRATION_H

#include "depth/reciprocity.h"
#include "depth/row_runs.h"

// State of the run being integrated in one row.
typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  int start;      // column of the run's first pixel, -1 outside a run
  int count;      // pixels of the run with a triangulated depth
  float sum_rel;  // sum over them of (z_tri - z) / z
  float z;        // depth at the current pixel, mm
} RfRunState;

RF_INLINE void rf_run_state_init(RfRunState* state) {
  state->start = -1;
  state->count = 0;
  state->sum_rel = 0.0f;
  state->z = 0.0f;
}

// Ends the current run; before the last pass, rescales its seed by its mean relative residual.
RF_INLINE void rf_close_run(RfRunState* state, RF_GLOBAL float* z_row, int rescale_seed) {
  if (state->start >= 0 && rescale_seed && state->count > 0) {
    z_row[state->start] *= 1.0f + state->sum_rel / (float)state->count;
  }
  state->start = -1;
}

// One pixel u of pass `pass` (of `passes`). Rows are given as pointers to their first element.
RF_INLINE void rf_integrate_pixel(RfRectifiedRig rig, float beta, int u, int proj_width, int pass, int passes,
                                  RF_GLOBAL const float* e_cam_row, RF_GLOBAL const float* e_proj_row,
                                  RF_GLOBAL const float* z_tri_row, RF_GLOBAL const unsigned char* run_row,
                                  RF_GLOBAL float* z_row, RfRunState* state) {
  const unsigned int code = run_row[u];
  if (code != RF_RUN_CONTINUE) rf_close_run(state, z_row, pass + 1 < passes);
  if (code == RF_RUN_MASKED) {
    z_row[u] = NAN;
    return;
  }
  if (code == RF_RUN_START) {
    state->start = u;
    state->count = 0;
    state->sum_rel = 0.0f;
    state->z = pass == 0 ? z_tri_row[u] : z_row[u];
  } else {
    int ok = 1;
    const float increment = rf_rk4_increment(rig, beta, u - 1, state->z, e_cam_row, e_proj_row, proj_width, &ok);
    if (ok) state->z += increment;
  }
  z_row[u] = state->z;
  const float z_tri = z_tri_row[u];
  if (z_tri == z_tri) {  // not NaN
    state->sum_rel += (z_tri - state->z) / state->z;
    state->count += 1;
  }
}

// The whole row: `passes` shooting passes (>= 1) over every run. Writes z_row (NaN where masked).
RF_INLINE void rf_integrate_row(RfRectifiedRig rig, float beta, int width, int proj_width, int passes,
                                RF_GLOBAL const float* e_cam_row, RF_GLOBAL const float* e_proj_row,
                                RF_GLOBAL const float* z_tri_row, RF_GLOBAL const unsigned char* run_row,
                                RF_GLOBAL float* z_row) {
  for (int pass = 0; pass < passes; ++pass) {
    RfRunState state;
    rf_run_state_init(&state);
    for (int u = 0; u < width; ++u) {
      rf_integrate_pixel(rig, beta, u, proj_width, pass, passes, e_cam_row, e_proj_row, z_tri_row, run_row, z_row,
                         &state);
    }
    rf_close_run(&state, z_row, pass + 1 < passes);
  }
}

#endif  // RFRECON_KERNELS_DEPTH_ROW_INTEGRATION_H
