// The reciprocity ODE of a rectified row (docs/method.md) and its RK4 step, shared word for word by the OpenCL kernels
// (kernels/depth/*.cl), the HLS C++ tops (hw/hls/) and their plain C++ references (host/depth/row_solvers.cc).
//
// Rectified camera frame: camera centre at the origin, projector centre at (b, 0, 0). Rectified pixel (u, v) sees
// X = z (a, beta, 1) with a = (u - cx_cam) / f and beta = (v - cy) / f; X projects to projector column
// u_p = f (X_x - b) / z + cx_proj on the same row. e_cam and e_proj are the primal and dual images divided by the
// solid angles of their pixels (radiance-like: any common factor cancels). With w = e_c w_c / d_c^2 - e_p w_p / d_p^2,
// reciprocity gives n . w = 0, and along the row:  dz/du = z w_perp / (f (s w_x - a w_perp)),
// s = sqrt(1 + beta^2), w_perp = (beta w_y + w_z) / s.
//
// Functions that take rows exist once per kind of row (depth/row_space.h): RF_ON_CHIP(rf_slope) is the variant for
// rows in on-chip (private) buffers of the single work-item kernels, RF_LANES_FN(rf_slope) the one for RF_LANES rows
// in vector lanes.
#ifndef RFRECON_KERNELS_DEPTH_RECIPROCITY_H
#define RFRECON_KERNELS_DEPTH_RECIPROCITY_H

#include "depth/row_lanes.h"
#include "depth/row_space.h"

// Rectified geometry of one rig (pixels, millimetres).
typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  float f;        // rectified focal length, px
  float cx_cam;   // rectified principal point x of the camera, px
  float cx_proj;  // rectified principal point x of the projector, px
  float cy;       // rectified principal point y, shared, px
  float b;        // projector centre x in the rectified camera frame, mm
} RfRectifiedRig;

// The RK4 stages of one step, evaluated one slope at a time so that a single work-item kernel can interleave rows
// between the slopes (kernels/depth/row_interleave.h): k_last is the previous stage's slope, sum the weighted sum
// k1 + 2 k2 + 2 k3 + k4 so far, ok is cleared when a slope breaks down. Per kind of row (depth/row_space.h).
#define RF_RK4_STAGES_FIELDS(real, integer) \
  real k_last;                              \
  real sum;                                 \
  integer ok;
typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  RF_RK4_STAGES_FIELDS(float, int)
} RfRk4Stages;
#ifdef __OPENCL_VERSION__
typedef struct {
  RF_RK4_STAGES_FIELDS(RF_LANES_REAL, RF_LANES_INT)
} RF_LANES_FN(RfRk4Stages);
#endif

// |s w_x - a w_perp| below this fraction of |w|: the row's plane is seen at grazing angle, the ODE is singular.
#define RF_GRAZING_LIMIT 1e-3f

// The order of these includes is their meaning.
// clang-format off
#include "depth/row_kind_global.h"
#include "depth/reciprocity_rows.h"
#include "depth/row_kind_end.h"
#ifdef __OPENCL_VERSION__
#include "depth/row_kind_on_chip.h"
#include "depth/reciprocity_rows.h"
#include "depth/row_kind_end.h"
#include "depth/row_kind_lanes.h"
#include "depth/reciprocity_rows.h"
#include "depth/row_kind_end.h"
#endif
// clang-format on

#endif  // RFRECON_KERNELS_DEPTH_RECIPROCITY_H
