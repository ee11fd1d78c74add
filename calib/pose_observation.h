// One checkerboard pose of a projector-camera calibration: the board corners found in the camera image and in the
// dual image T^T 1 seen from the projector, in the same order.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/board_overhang.h"
#include "calib/rig.h"

namespace rfrecon::calib {

struct PoseObservation {
  std::string name;                            // the pose directory
  cv::Mat camera_image;                        // CV_32F linear white frame (camera size)
  cv::Mat dual_image;                          // CV_32F T^T 1 (projector size), holes filled for detection
  std::vector<cv::Point2f> camera_corners;     // empty when the board was not found
  std::vector<cv::Point2f> projector_corners;  // empty when the board was not found; same order as camera_corners
  BoardOverhang camera_overhang;               // the board beyond the camera corners (calib/board_overhang.h)
  std::string problem;                         // why the pose is unusable; empty when both corner sets were found
  bool usable() const { return problem.empty(); }
};

// Fills the dual image's holes (projector pixels that T does not reach: `dual_reached` 0), finds the board in both
// images and puts the projector corners in the camera corners' order by mapping two camera corners through
// `correspondence` (camera pixel -> projector x, y; CV_32FC2, NaN where unknown), since the detector may number a
// board from either end. A board that is not found, or corners that cannot be put in one order, are reported in
// `problem`.
PoseObservation observe_board(const std::string& name, const cv::Mat& camera_image, const cv::Mat& dual_image,
                              const cv::Mat& dual_reached, const cv::Mat& correspondence, const BoardSpec& board);

// Reverses `projector_corners` when that matches the camera corners mapped through `correspondence` better than the
// given order. Returns why the corners cannot be put in one order (empty when they are): an end of the camera board
// maps to no known correspondence, or the ends map more than half a projector square from the dual image's board ends
// in either order (the two detections found different parts of the board, or the correspondence is wrong there).
std::string align_corner_order(const std::vector<cv::Point2f>& camera_corners, const cv::Mat& correspondence,
                               std::vector<cv::Point2f>& projector_corners);

}  // namespace rfrecon::calib
