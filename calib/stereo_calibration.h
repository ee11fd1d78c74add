// Camera-projector stereo calibration: each device alone, then the joint adjustment (cv::stereoCalibrate), its
// uncertainty, and the row rectification.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/camera_calibration.h"
#include "calib/dense_correspondences.h"
#include "calib/rig.h"
#include "calib/stereo_fit.h"

namespace rfrecon::calib {

// One board pose seen by both devices; corners in the same (OpenCV) order in both.
struct StereoView {
  std::string name;
  std::vector<cv::Point2f> camera_corners;     // camera pixels
  std::vector<cv::Point2f> projector_corners;  // projector pixels, found in the dual image
  DenseCorrespondences dense;                  // on the board's white squares (none: corners only)
};

struct StereoCalibration {
  StereoRig rig;             // R, T: projector from camera; uncertainty and rectification filled
  CameraCalibration camera;  // each device alone: the starting point of the joint adjustment
  CameraCalibration projector;
  StereoFit fit;                      // residuals and per-view errors of the joint solution
  std::vector<std::string> warnings;  // pose-set warnings (too few, too frontal, poor coverage of either image)
};

// Calibrates camera and projector separately (calibrate_camera checks view count and pose diversity), then adjusts
// every board pose, both devices and the stereo pose together in cv::stereoCalibrate on the corners and, when views
// hold dense correspondences, once more with them (adjust_stereo), then rectifies.
StereoCalibration calibrate_stereo(const std::vector<StereoView>& views, const BoardSpec& board, cv::Size camera_size,
                                   cv::Size projector_size, const CalibrationOptions& options = {});

}  // namespace rfrecon::calib
