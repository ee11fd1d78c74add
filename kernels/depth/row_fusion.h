// Fusion of triangulated positions and integrated slopes on one rectified row (docs/method.md), shared by the OpenCL
// kernels (kernels/depth/fuse.cl) and the C++ reference (host/depth/row_solvers.cc).
//
// Per run, minimise  sum_i lambda_i (z_i - t_i)^2 + mu sum_i (z_{i+1} - z_i - h_i(z_i))^2  where t_i is the
// triangulated depth, h_i the RK4 increment of the reciprocity ODE from pixel i, lambda_i = 1 / sigma_z,i^2 with
// sigma_z,i = z_i^2 sigma_d / (f |b|) (depth noise of a disparity noise sigma_d) and mu = 1 / sigma_h^2. Each
// iteration linearises h_i around the current z (h_i' by a finite difference) and solves the tridiagonal normal
// equations for the update with the Thomas algorithm; solving for the update keeps float precision. A link whose ODE
// breaks down gets no slope term. Iterations start from z (for instance the integrated depth).
#ifndef RFRECON_KERNELS_DEPTH_ROW_FUSION_H
#define RFRECON_KERNELS_DEPTH_ROW_FUSION_H

#include "depth/reciprocity.h"
#include "depth/row_runs.h"

// Relative depth step of the finite difference that gives h_i'.
#define RF_FUSION_DIFF_STEP 1e-3f

// Solves the run [first, last] once and adds the update to z_row. c_row and d_row are scratch of the row's width.
RF_INLINE void rf_fuse_run_iteration(RfRectifiedRig rig, float beta, int first, int last, int proj_width,
                                     float sigma_disparity_px, float sigma_step_mm, RF_GLOBAL const float* e_cam_row,
                                     RF_GLOBAL const float* e_proj_row, RF_GLOBAL const float* z_tri_row,
                                     RF_GLOBAL float* z_row, RF_GLOBAL float* c_row, RF_GLOBAL float* d_row) {
  const float mu = 1.0f / (sigma_step_mm * sigma_step_mm);
  const float depth_noise_scale = sigma_disparity_px / (rig.f * RF_FABS(rig.b));
  float mu_prev = 0.0f, a_prev = 0.0f, r_prev = 0.0f;  // the link from i - 1 to i
  float c_prev = 0.0f, d_prev = 0.0f;                  // the forward sweep at i - 1 (kept in registers)
  for (int i = first; i <= last; ++i) {
    const float z = z_row[i];
    const float t = z_tri_row[i];
    const float sigma_z = z * z * depth_noise_scale;
    const float lambda = t == t ? 1.0f / (sigma_z * sigma_z) : 0.0f;
    float mu_next = 0.0f, a = 0.0f, r = 0.0f;  // the link from i to i + 1
    if (i < last) {
      int ok = 1;
      const float dz = RF_FUSION_DIFF_STEP * z;
      const float h = rf_rk4_increment(rig, beta, i, z, e_cam_row, e_proj_row, proj_width, &ok);
      const float h_shifted = rf_rk4_increment(rig, beta, i, z + dz, e_cam_row, e_proj_row, proj_width, &ok);
      if (ok) {
        mu_next = mu;
        a = 1.0f + (h_shifted - h) / dz;
        r = z_row[i + 1] - z - h;
      }
    }
    const float lower = -mu_prev * a_prev;
    const float upper = -mu_next * a;
    const float diagonal = lambda + mu_prev + mu_next * a * a;
    const float rhs = (t == t ? lambda * (t - z) : 0.0f) - mu_prev * r_prev + mu_next * a * r;
    const float pivot = diagonal - lower * c_prev;
    c_prev = upper / pivot;
    d_prev = (rhs - lower * d_prev) / pivot;
    c_row[i] = c_prev;
    d_row[i] = d_prev;
    mu_prev = mu_next;
    a_prev = a;
    r_prev = r;
  }
  float update = d_prev;  // the forward sweep's value at `last`
  z_row[last] += update;
  for (int i = last - 1; i >= first; --i) {
    update = d_row[i] - c_row[i] * update;
    z_row[i] += update;
  }
}

// The whole row: `iterations` linearised solves of every run. z_row holds the start on entry (finite wherever the
// run code is not RF_RUN_MASKED) and the fused depth on return.
RF_INLINE void rf_fuse_row(RfRectifiedRig rig, float beta, int width, int proj_width, int iterations,
                           float sigma_disparity_px, float sigma_step_mm, RF_GLOBAL const float* e_cam_row,
                           RF_GLOBAL const float* e_proj_row, RF_GLOBAL const float* z_tri_row,
                           RF_GLOBAL const unsigned char* run_row, RF_GLOBAL float* z_row, RF_GLOBAL float* c_row,
                           RF_GLOBAL float* d_row) {
  int first = 0;
  while (first < width) {
    if (run_row[first] == RF_RUN_MASKED) {
      ++first;
      continue;
    }
    int last = first;
    while (last + 1 < width && run_row[last + 1] == RF_RUN_CONTINUE) ++last;
    for (int iteration = 0; iteration < iterations; ++iteration) {
      rf_fuse_run_iteration(rig, beta, first, last, proj_width, sigma_disparity_px, sigma_step_mm, e_cam_row,
                            e_proj_row, z_tri_row, z_row, c_row, d_row);
    }
    first = last + 1;
  }
}

#endif  // RFRECON_KERNELS_DEPTH_ROW_FUSION_H
