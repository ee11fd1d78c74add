// Camera-projector stereo calibration: each device alone, then cv::stereoCalibrate and cv::stereoRectify.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/camera_calibration.h"
#include "calib/rig.h"

namespace rfrecon::calib {

// One board pose seen by both devices; corners in the same (OpenCV) order in both.
struct StereoView {
  std::string name;
  std::vector<cv::Point2f> camera_corners;     // camera pixels
  std::vector<cv::Point2f> projector_corners;  // projector pixels, found in the dual image
};

struct StereoCalibration {
  StereoRig rig;  // R, T: projector from camera; rectification filled by compute_stereo_geometry
  CameraCalibration camera;
  CameraCalibration projector;
  std::vector<double> per_view_camera_errors;     // px, after the joint refinement
  std::vector<double> per_view_projector_errors;  // px, after the joint refinement
};

// Calibrates camera and projector separately (calibrate_camera checks view count and pose diversity), then refines
// both with the stereo pose in cv::stereoCalibrate, then rectifies.
StereoCalibration calibrate_stereo(const std::vector<StereoView>& views, const BoardSpec& board, cv::Size camera_size,
                                   cv::Size projector_size, const CalibrationOptions& options = {});

}  // namespace rfrecon::calib
