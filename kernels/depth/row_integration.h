// Reciprocity integration of one rectified row (the paper's method, docs/method.md), shared by the OpenCL kernels
// (kernels/depth/integrate.cl), the HLS C++ top (hw/hls/) and the C++ reference (host/depth/row_solvers.cc).
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
  float seed;     // depth at the run's first pixel, mm
  float z;        // depth at the current pixel, mm
} RfRunState;

RF_INLINE void rf_run_state_init(RfRunState* state) {
  state->start = -1;
  state->count = 0;
  state->sum_rel = 0.0f;
  state->seed = 0.0f;
  state->z = 0.0f;
}

#define RF_ROW_SPACE RF_GLOBAL
#define RF_ROW_FN(name) name
#include "depth/row_integration_rows.h"
#undef RF_ROW_SPACE
#undef RF_ROW_FN
#ifdef __OPENCL_VERSION__
#define RF_ROW_SPACE
#define RF_ROW_FN(name) RF_ON_CHIP(name)
#include "depth/row_integration_rows.h"
#undef RF_ROW_SPACE
#undef RF_ROW_FN
#endif

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
      RF_ROWS_IN_STEP();
    }
    rf_close_run(&state, z_row, pass + 1 < passes);
  }
}

#endif  // RFRECON_KERNELS_DEPTH_ROW_INTEGRATION_H
