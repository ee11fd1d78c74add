// How far an estimated rig is from the true one, in the terms that matter for depth: intrinsics, baseline,
// rotation, and the depth scale error of triangulating exact correspondences with the estimated rig.
#pragma once

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calib {

struct RigComparison {
  double camera_focal_error = 0.0;         // relative, the larger of fx and fy
  double camera_principal_error_px = 0.0;  // distance between the principal points
  double projector_focal_error = 0.0;
  double projector_principal_error_px = 0.0;
  double baseline_error = 0.0;      // |T_est| / |T_true| - 1
  double rotation_error_deg = 0.0;  // angle of R_est R_true^T
  double depth_scale_error = 0.0;   // least-squares z_est / z_true - 1 over the working volume
  double depth_rms_error = 0.0;     // RMS of z_est / z_true - 1 (scale and distortion errors together)
  int points = 0;                   // working-volume points seen by both devices
};

// The working volume: a 16 x 16 grid of camera pixels at depths near_mm, (near_mm + far_mm) / 2 and far_mm, kept
// where the true projector sees them. Their exact camera and projector pixels (true rig) are triangulated with the
// estimated rig (midpoint of the two rays).
RigComparison compare_rigs(const StereoRig& estimated, const StereoRig& truth, double near_mm = 500.0,
                           double far_mm = 700.0);

}  // namespace rfrecon::calib
