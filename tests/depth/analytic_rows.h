// Rectified rows of an analytic scene for the depth tests: a tilted Lambertian plane seen by a rectified rig, with
// the radiance-like primal and dual images of docs/method.md computed in closed form, so that reciprocity holds
// exactly and the true depth of every pixel is known.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "host/depth/rectified_rows.h"
#include "kernels/depth/row_runs.h"

namespace rfrecon::depth::testing {

// Plane n . X = d in the rectified camera frame (n unit, facing the devices).
struct Plane {
  double nx, ny, nz, d;
  double depth(double a, double beta) const { return d / (nx * a + ny * beta + nz); }  // z along the ray (a, beta, 1)
};

// e_cam = (n . w_p) / d_p^2 and e_proj = (n . w_c) / d_c^2 (constant BRDF and gain: they cancel).
inline RectifiedRows analytic_rows(const Plane& plane, int width, int height) {
  RectifiedRows rows;
  // f = 300 px, b = 120 mm: a point 480 mm away has a disparity of 75 px, which cx_proj takes back so that both
  // images of the plane overlap on the same columns.
  const float cx_cam = 0.5f * static_cast<float>(width - 1);
  rows.rig = RfRectifiedRig{300.0f, cx_cam, cx_cam + 75.0f, 0.5f * static_cast<float>(height - 1), 120.0f};
  rows.width = width;
  rows.height = height;
  rows.proj_width = width + 16;  // the projector's image of the plane is a little wider than the camera's
  rows.e_cam.resize(rows.pixels());
  rows.e_proj.resize(static_cast<std::size_t>(rows.proj_width) * height);
  rows.z_tri.resize(rows.pixels());
  rows.runs.assign(rows.pixels(), RF_RUN_CONTINUE);
  const double f = rows.rig.f, b = rows.rig.b;
  for (int v = 0; v < height; ++v) {
    const double beta = (v - rows.rig.cy) / f;
    rows.runs[static_cast<std::size_t>(v) * width] = RF_RUN_START;
    for (int u = 0; u < width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * width + u;
      // Camera pixel u: the point it sees and its irradiance from the projector.
      const double a = (u - rows.rig.cx_cam) / f, z = plane.depth(a, beta);
      const double x = z * a, y = z * beta;
      const double px = b - x, py = -y, pz = -z, dp = std::sqrt(px * px + py * py + pz * pz);
      rows.e_cam[i] = static_cast<float>((plane.nx * px + plane.ny * py + plane.nz * pz) / (dp * dp * dp));
      rows.z_tri[i] = static_cast<float>(z);
    }
    for (int u = 0; u < rows.proj_width; ++u) {
      // Projector column u: the point its ray from (b, 0, 0) meets, seen from the camera.
      const double a_p = (u - rows.rig.cx_proj) / f;
      const double t = (plane.d - plane.nx * b) / (plane.nx * a_p + plane.ny * beta + plane.nz);
      const double xp = b + t * a_p, yp = t * beta, zp = t, dc = std::sqrt(xp * xp + yp * yp + zp * zp);
      rows.e_proj[static_cast<std::size_t>(v) * rows.proj_width + u] =
          static_cast<float>(-(plane.nx * xp + plane.ny * yp + plane.nz * zp) / (dc * dc * dc));
    }
  }
  return rows;
}

}  // namespace rfrecon::depth::testing
