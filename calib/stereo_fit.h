// What a stereo calibration's fit says about itself: each board pose in the joint solution, the reprojection
// residuals of every corner in both devices, and one standard deviation of every estimated value from the
// adjustment's covariance (as Bouguet's toolbox reports them).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "calib/distortion_model.h"
#include "calib/rig.h"

namespace rfrecon::calib {

// One board pose's corners in both devices, in the same order as its object points.
struct StereoCorners {
  std::vector<cv::Point2f> camera;
  std::vector<cv::Point2f> projector;
};

struct StereoFit {
  RigUncertainty uncertainty;
  std::vector<cv::Vec3d> board_rvecs;                            // camera from board, per view (refined jointly)
  std::vector<cv::Vec3d> board_tvecs;                            // mm
  std::vector<std::vector<cv::Point2d>> camera_residuals_px;     // projected - detected, per view and corner
  std::vector<std::vector<cv::Point2d>> projector_residuals_px;  // same for the projector
  std::vector<double> camera_view_rms_px;
  std::vector<double> projector_view_rms_px;
  double residual_sigma_px = 0.0;  // sqrt(sum of squared residuals / (residuals - parameters)), per coordinate
};

// Given the rig's intrinsics, distortion and R, T (held fixed), fits each board pose to both devices' corners
// (Gauss-Newton from cv::solvePnP on the camera corners), then linearises the joint problem (both devices'
// intrinsics and the coefficients `model` estimates, R, T and every pose) at that solution with a numerical
// Jacobian and returns sigma^2 (J^T J)^-1's diagonal as standard deviations (NaN when the problem is singular).
// `object_points` are the board's corners (one list per view: the board may be refined per view).
StereoFit analyse_stereo_fit(const StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                             const std::vector<StereoCorners>& corners, DistortionModel model);

}  // namespace rfrecon::calib
