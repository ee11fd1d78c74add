// Single-camera calibration from checkerboard views (also used for the projector, seen through dual images).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calib {

// The corners found in one view (one board pose), with the name used in reports (file or pose directory).
struct BoardView {
  std::string name;
  std::vector<cv::Point2f> corners;
};

struct CameraCalibration {
  cv::Size image_size;
  cv::Mat camera_matrix;                // 3x3, CV_64F
  cv::Mat dist_coeffs;                  // 1x5 k1 k2 p1 p2 k3 (k3 fixed at 0 unless full distortion was asked for)
  double rms = 0.0;                     // px over all corners
  std::vector<double> per_view_errors;  // px RMS per view
  std::vector<std::string> view_names;
  std::vector<cv::Mat> board_rotations;     // Rodrigues vectors: board frame to camera frame, per view
  std::vector<cv::Mat> board_translations;  // mm, per view
  BoardSpec board;
};

struct CalibrationOptions {
  bool full_distortion = false;  // estimate k3 too (wide-angle lenses); otherwise k3 = 0, which is more stable
  int min_views = 3;
  double min_tilt_spread_deg = 5.0;  // the board normals must span at least this angle (else focal is unobservable)
};

// cv::calibrateCamera over the views. Throws ProcessingError when there are fewer than min_views views, or when the
// poses are degenerate (all board normals within min_tilt_spread_deg of each other: e.g. all fronto-parallel).
CameraCalibration calibrate_camera(const std::vector<BoardView>& views, const BoardSpec& board, cv::Size image_size,
                                   const CalibrationOptions& options = {});

// The largest angle between two board normals of a calibration, in degrees.
double board_tilt_spread_deg(const std::vector<cv::Mat>& board_rotations);

// Writes an OpenCV FileStorage YAML (image_size, camera_matrix, dist_coeffs, rms, per_view_errors, views, board)
// atomically.
void write_camera_calibration(const CameraCalibration& calibration, const std::filesystem::path& file);

}  // namespace rfrecon::calib
