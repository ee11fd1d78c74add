// How far detected board corners are from the true ones (a rendered capture's truth): the corner detector's bias
// and noise per device, in pixels.
#pragma once

#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calib {

struct CornerErrors {
  cv::Point2d mean_px;  // mean of detected - true, per axis
  double rms_px = 0.0;  // RMS of detected - true per axis: sqrt(mean(dx^2 + dy^2) / 2)
  double max_px = 0.0;  // the largest |detected - true|
  int corners = 0;
};

struct CornerComparison {
  CornerErrors camera;
  CornerErrors projector;
};

// One view: the board's true inner corners in the camera frame (mm, OpenCV's order) and the corners found in the
// camera and dual images (`calibrate`'s corners.json; the detector may have numbered them from the other end).
struct ViewCorners {
  std::vector<cv::Point3d> true_corners_cam_mm;
  std::vector<cv::Point2f> camera_px;
  std::vector<cv::Point2f> projector_px;
};

// The views of `corners` (calibrate's corners.json) with the true corners of the same view in `board_poses`
// (simulate's truth/board_poses.json), matched by name. Throws InputError naming the file for a missing or malformed
// file, a view without truth or a view whose corner counts differ from its board's.
std::vector<ViewCorners> read_view_corners(const std::filesystem::path& corners,
                                           const std::filesystem::path& board_poses);

// The true corners projected with the true rig's models against the detected ones, over all views. Throws
// std::invalid_argument when a view's corner counts differ.
CornerComparison compare_corners(const std::vector<ViewCorners>& views, const StereoRig& truth);

}  // namespace rfrecon::calib
