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

// State of the run being integrated in one row (per kind of row, depth/row_space.h): start is the column of the
// run's first pixel (-1 outside a run), count its pixels with a triangulated depth, sum_rel
// the sum over them of (z_tri - z) / z, seed the depth at its first pixel (mm), z the depth at the current pixel (mm).
#define RF_RUN_STATE_FIELDS(real, integer) \
  integer start;                           \
  integer count;                           \
  real sum_rel;                            \
  real seed;                               \
  real z;
typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  RF_RUN_STATE_FIELDS(float, int)
} RfRunState;
#ifdef __OPENCL_VERSION__
typedef struct {
  RF_RUN_STATE_FIELDS(RF_LANES_REAL, RF_LANES_INT)
} RF_LANES_FN(RfRunState);
#endif

// The order of these includes is their meaning.
// clang-format off
#include "depth/row_kind_global.h"
#include "depth/row_integration_rows.h"
#include "depth/row_kind_end.h"
#ifdef __OPENCL_VERSION__
#include "depth/row_kind_on_chip.h"
#include "depth/row_integration_rows.h"
#include "depth/row_kind_end.h"
#include "depth/row_kind_lanes.h"
#include "depth/row_integration_rows.h"
#include "depth/row_kind_end.h"
#endif
// clang-format on

#endif  // RFRECON_KERNELS_DEPTH_ROW_INTEGRATION_H
