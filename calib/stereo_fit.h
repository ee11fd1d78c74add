// What a stereo calibration's fit says about itself: each board pose in the joint solution, the reprojection
// residuals of every corner in both devices, and one standard deviation of every estimated value from the
// adjustment's covariance (as Bouguet's toolbox reports them).
#pragma once

#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/distortion_model.h"
#include "calib/joint_problem.h"
#include "calib/rig.h"

namespace rfrecon::calib {

struct StereoFit {
  RigUncertainty uncertainty;
  std::vector<cv::Vec3d> board_rvecs;                            // camera from board, per view (refined jointly)
  std::vector<cv::Vec3d> board_tvecs;                            // mm
  std::vector<std::vector<cv::Point2d>> camera_residuals_px;     // projected - detected, per view and corner
  std::vector<std::vector<cv::Point2d>> projector_residuals_px;  // same for the projector
  std::vector<std::vector<cv::Point2d>> dense_residuals_px;      // of the dense correspondences, per view
  std::vector<double> camera_view_rms_px;                        // over the corners kept (not dropped by gating)
  std::vector<double> projector_view_rms_px;
  std::vector<double> dense_view_rms_px;  // of the dense correspondences, per view (0 for a view without them)
  // sqrt(sum of squared weighted residuals / (residuals kept - parameters)), per coordinate
  double residual_sigma_px = 0.0;
};

// Removes from `corners` every dense correspondence farther than `max_px` from where the rig, with each board pose
// fitted to its corners alone, puts it (a misdecoded pixel, a speck on the board: the sampling keeps what T says);
// returns how many were removed.
std::size_t reject_dense_outliers(const StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                                  std::vector<StereoCorners>& corners, DistortionModel model, double max_px);

// Adjusts the rig's intrinsics, distortion (the coefficients `model` estimates) and projector pose together with every
// board pose (each started from cv::solvePnP on its camera corners) by Levenberg-Marquardt over all observations, the
// dense correspondences included, and writes the result into `rig` (pose and matrices; E, F and the rectification are
// left to compute_stereo_geometry). Returns the final RMS residual per coordinate, px.
double adjust_stereo(StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                     const std::vector<StereoCorners>& corners, DistortionModel model);

// Given the rig's intrinsics, distortion and projector pose (held fixed), fits each board pose to all its observations
// (Gauss-Newton from cv::solvePnP on the camera corners), then linearises the joint problem (both devices' intrinsics
// and the coefficients `model` estimates, the projector pose and every board pose) at that solution with a numerical
// Jacobian and returns sigma^2 (J^T J)^-1's diagonal as standard deviations (NaN when the problem is singular).
// `object_points` are the board's corners (one list per view: the board may be refined per view).
StereoFit analyse_stereo_fit(const StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                             const std::vector<StereoCorners>& corners, DistortionModel model);

}  // namespace rfrecon::calib
