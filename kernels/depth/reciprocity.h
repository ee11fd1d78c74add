// The reciprocity ODE of a rectified row (docs/method.md) and its RK4 step, shared word for word by the OpenCL kernels
// (kernels/depth/*.cl) and their plain C++ references (host/depth/row_solvers.cc).
//
// Rectified camera frame: camera centre at the origin, projector centre at (b, 0, 0). Rectified pixel (u, v) sees
// X = z (a, beta, 1) with a = (u - cx_cam) / f and beta = (v - cy) / f; X projects to projector column
// u_p = f (X_x - b) / z + cx_proj on the same row. e_cam and e_proj are the primal and dual images divided by the
// solid angles of their pixels (radiance-like: any common factor cancels). With w = e_c w_c / d_c^2 - e_p w_p / d_p^2,
// reciprocity gives n . w = 0, and along the row:  dz/du = z w_perp / (f (s w_x - a w_perp)),
// s = sqrt(1 + beta^2), w_perp = (beta w_y + w_z) / s.
#ifndef RFRECON_KERNELS_DEPTH_RECIPROCITY_H
#define RFRECON_KERNELS_DEPTH_RECIPROCITY_H

#ifdef __OPENCL_VERSION__
#define RF_GLOBAL __global
#define RF_INLINE inline
#define RF_SQRT sqrt
#define RF_FABS fabs
#else
#include <cmath>
#define RF_GLOBAL
#define RF_INLINE inline
#define RF_SQRT std::sqrt
#define RF_FABS std::fabs
#endif

// Rectified geometry of one rig (pixels, millimetres).
typedef struct {  // NOLINT(modernize-use-using): shared with OpenCL C, which has no `using`
  float f;        // rectified focal length, px
  float cx_cam;   // rectified principal point x of the camera, px
  float cx_proj;  // rectified principal point x of the projector, px
  float cy;       // rectified principal point y, shared, px
  float b;        // projector centre x in the rectified camera frame, mm
} RfRectifiedRig;

// |s w_x - a w_perp| below this fraction of |w|: the row's plane is seen at grazing angle, the ODE is singular.
#define RF_GRAZING_LIMIT 1e-3f

// Linear interpolation of row[0 .. width-1] at x (pixel centres at integers); 0 outside the row.
RF_INLINE float rf_sample_row(RF_GLOBAL const float* row, int width, float x) {
  if (!(x >= 0.0f && x <= (float)(width - 1))) return 0.0f;
  const int i = (int)x;
  if (i >= width - 1) return row[width - 1];
  const float t = x - (float)i;
  return row[i] + t * (row[i + 1] - row[i]);
}

// dz/du at column u (fractional) for depth z, given e_cam at u. Sets *ok to 0 where the ODE breaks down (no dual
// signal at the projector column, no camera signal, grazing angle) and returns 0 there.
RF_INLINE float rf_slope(RfRectifiedRig rig, float beta, float u, float z, float e_cam,
                         RF_GLOBAL const float* e_proj_row, int proj_width, int* ok) {
  const float a = (u - rig.cx_cam) / rig.f;
  const float x = z * a, y = z * beta;
  const float u_proj = rig.f * (x - rig.b) / z + rig.cx_proj;
  const float e_proj = rf_sample_row(e_proj_row, proj_width, u_proj);
  if (!(e_cam > 0.0f && e_proj > 0.0f && z > 0.0f)) {
    *ok = 0;
    return 0.0f;
  }
  // Unit vectors toward the camera (w_c = -X / d_c) and the projector (w_p = (o_p - X) / d_p), scaled by 1 / d^2.
  const float dc2 = x * x + y * y + z * z, dc = RF_SQRT(dc2);
  const float px = rig.b - x, py = -y, pz = -z;
  const float dp2 = px * px + py * py + pz * pz, dp = RF_SQRT(dp2);
  const float kc = e_cam / (dc2 * dc), kp = e_proj / (dp2 * dp);
  const float wx = -kc * x - kp * px, wy = -kc * y - kp * py, wz = -kc * z - kp * pz;
  const float s = RF_SQRT(1.0f + beta * beta);
  const float w_perp = (beta * wy + wz) / s;
  const float denominator = s * wx - a * w_perp;
  const float w_norm = RF_SQRT(wx * wx + wy * wy + wz * wz);
  if (!(RF_FABS(denominator) > RF_GRAZING_LIMIT * w_norm)) {
    *ok = 0;
    return 0.0f;
  }
  return z * w_perp / (rig.f * denominator);
}

// The RK4 increment z(u + 1) - z(u) from column u (integer, u + 1 < width) at depth z; e_cam is interpolated linearly
// between the two pixel centres. *ok is cleared when any of the four slopes breaks down.
RF_INLINE float rf_rk4_increment(RfRectifiedRig rig, float beta, int u, float z, RF_GLOBAL const float* e_cam_row,
                                 RF_GLOBAL const float* e_proj_row, int proj_width, int* ok) {
  const float e0 = e_cam_row[u], e1 = e_cam_row[u + 1], e_half = 0.5f * (e0 + e1);
  const float u0 = (float)u;
  const float k1 = rf_slope(rig, beta, u0, z, e0, e_proj_row, proj_width, ok);
  const float k2 = rf_slope(rig, beta, u0 + 0.5f, z + 0.5f * k1, e_half, e_proj_row, proj_width, ok);
  const float k3 = rf_slope(rig, beta, u0 + 0.5f, z + 0.5f * k2, e_half, e_proj_row, proj_width, ok);
  const float k4 = rf_slope(rig, beta, u0 + 1.0f, z + k3, e1, e_proj_row, proj_width, ok);
  return (k1 + 2.0f * k2 + 2.0f * k3 + k4) / 6.0f;
}

#endif  // RFRECON_KERNELS_DEPTH_RECIPROCITY_H
