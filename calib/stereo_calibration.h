// Camera-projector stereo calibration: each device alone, then the joint adjustment (cv::stereoCalibrate), its
// uncertainty, and the row rectification.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/camera_calibration.h"
#include "calib/dense_correspondences.h"
#include "calib/residual_gating.h"
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
  StereoRig rig;             // uncertainty and rectification filled
  CameraCalibration camera;  // each device alone: the starting point of the joint adjustment
  CameraCalibration projector;
  StereoFit fit;                      // residuals and per-view errors of the joint solution
  std::vector<std::string> warnings;  // pose-set warnings (too few, too frontal, poor coverage of either image)
  GatingThresholds gating_thresholds;
  std::vector<GatingDecision> gating;                         // every corner dropped and pose down-weighted, in order
  std::vector<std::vector<unsigned char>> camera_dropped;     // per view and corner: 1 where gating dropped it
  std::vector<std::vector<unsigned char>> projector_dropped;  // (empty for a view with none dropped)
  double rms_all_px = 0.0;  // the stereo RMS over every corner, the dropped ones included (rig.rms: the kept ones)
};

// Calibrates camera and projector separately (calibrate_camera checks view count and pose diversity), then adjusts
// every board pose, both devices and the stereo pose together in cv::stereoCalibrate on the corners and, when views
// hold dense correspondences, once more with them (adjust_stereo); with options.gating, gates the residuals
// (calib/residual_gating.h) and adjusts again with the corners dropped and the poses down-weighted, up to three
// rounds while a round decides something; then rectifies. Throws ProcessingError, naming the board options, when
// either device's intrinsics are not determined (check_intrinsics_determined), alone or jointly adjusted, or the rig
// cannot be rectified.
StereoCalibration calibrate_stereo(const std::vector<StereoView>& views, const BoardSpec& board, cv::Size camera_size,
                                   cv::Size projector_size, const CalibrationOptions& options = {});

}  // namespace rfrecon::calib
