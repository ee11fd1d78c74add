// Single-camera calibration from checkerboard views (also used for the projector, seen through dual images).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/distortion_model.h"
#include "calib/rig.h"

namespace rfrecon::calib {

// The corners found in one view (one board pose), with the name used in reports (file or pose directory).
struct BoardView {
  std::string name;
  std::vector<cv::Point2f> corners;
};

struct CameraCalibration {
  cv::Size image_size;
  cv::Mat camera_matrix;                               // 3x3, CV_64F
  cv::Mat dist_coeffs;                                 // 1x5 k1 k2 p1 p2 k3, or 1x8 for the rational model
  cv::Mat intrinsics_std;                              // 1x4: one standard deviation of fx, fy, cx, cy (px)
  cv::Mat dist_coeffs_std;                             // as dist_coeffs; 0 for coefficients held fixed
  double rms = 0.0;                                    // px over all corners
  std::vector<double> per_view_errors;                 // px RMS per view
  std::vector<std::vector<cv::Point2d>> residuals_px;  // projected - detected, per view and corner
  std::vector<std::string> view_names;
  std::vector<cv::Vec3d> board_rvecs;     // board frame to camera frame, per view
  std::vector<cv::Vec3d> board_tvecs;     // mm, per view
  std::vector<cv::Point3f> board_points;  // the board's corners (mm): nominal, or refined with refine_board
  double tilt_spread_deg = 0.0;           // largest angle between two views' board normals
  double coverage = 0.0;                  // fraction of the image the boards cover (calib/pose_diversity.h)
  std::vector<std::string> warnings;      // pose-set warnings (too few, too frontal, poor coverage)
  BoardSpec board;
};

struct CalibrationOptions {
  DistortionModel distortion = DistortionModel::standard;
  // Also estimate the board's corners (cv::calibrateCameraRO, fixing the first and last corner of the first row and
  // the square size): for a board that is not perfectly flat. Needs many poses.
  bool refine_board = false;
  int min_views = 3;
  // Dense correspondences per pose (calib/dense_correspondences.h) added to the joint adjustment of a stereo
  // calibration; 0 adjusts the corners alone.
  int dense_points = 2000;
  // Robust gating of a stereo calibration's corners and poses (calib/residual_gating.h); false keeps every
  // observation at weight 1.
  bool gating = true;
  double min_tilt_spread_deg = 5.0;  // the board normals must span at least this angle (else focal is unobservable)
};

// cv::calibrateCamera (calibrateCameraRO with refine_board) over the views, with the standard deviations of the
// intrinsics. Throws ProcessingError when there are fewer than min_views views, or when the poses are degenerate (all
// board normals within min_tilt_spread_deg of each other: e.g. all fronto-parallel).
CameraCalibration calibrate_camera(const std::vector<BoardView>& views, const BoardSpec& board, cv::Size image_size,
                                   const CalibrationOptions& options = {});

// Beyond these the intrinsics are not determined (a board that does not fit the images, too few or too similar poses)
// and no calibration file is written: a standard deviation of fx or fy over this share of its value, of cx or cy over
// this share of the image's width or height, and a reprojection RMS over kMaxCalibrationRmsPx.
inline constexpr double kMaxIntrinsicsStdShare = 0.1;
inline constexpr double kMaxCalibrationRmsPx = 2.0;

// Throws ProcessingError when `device`'s intrinsics (camera_matrix with one standard deviation each of fx, fy, cx, cy
// in intrinsics_std, from `views` views) are not determined: a focal length that is not positive, or a value beyond
// the limits above. The message names the board options, the views and the evidence, and says what to check.
void check_intrinsics_determined(const std::string& device, const cv::Mat& camera_matrix, const cv::Mat& intrinsics_std,
                                 double rms_px, cv::Size image_size, const BoardSpec& board, std::size_t views);

// Writes an OpenCV FileStorage YAML (image_size, camera_matrix, dist_coeffs, their standard deviations, rms,
// per_view_errors, views, board) atomically.
void write_camera_calibration(const CameraCalibration& calibration, const std::filesystem::path& file);

}  // namespace rfrecon::calib
