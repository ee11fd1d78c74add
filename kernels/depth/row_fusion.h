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

// The forward sweep's state at the previous pixel of the run (per kind of row, depth/row_space.h): mu, the weight of
// the link from the previous pixel to this one (0 where it has none), a its linearised slope 1 + h', r its residual,
// c and d the Thomas forward sweep's coefficients at the previous pixel.
#define RF_SWEEP_STATE_FIELDS(real) \
  real mu;                          \
  real a;                           \
  real r;                           \
  real c;                           \
  real d;
typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  RF_SWEEP_STATE_FIELDS(float)
} RfSweepState;
#ifdef __OPENCL_VERSION__
typedef struct {
  RF_SWEEP_STATE_FIELDS(RF_LANES_REAL)
} RF_LANES_FN(RfSweepState);
#endif

// The order of these includes is their meaning.
// clang-format off
#include "depth/row_kind_global.h"
#include "depth/row_fusion_rows.h"
#include "depth/row_kind_end.h"
#ifdef __OPENCL_VERSION__
#include "depth/row_kind_on_chip.h"
#include "depth/row_fusion_rows.h"
#include "depth/row_kind_end.h"
#include "depth/row_kind_lanes.h"
#include "depth/row_fusion_rows.h"
#include "depth/row_kind_end.h"
#endif
// clang-format on

#endif  // RFRECON_KERNELS_DEPTH_ROW_FUSION_H
