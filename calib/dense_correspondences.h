// Dense camera-projector correspondences on a calibration board, for the joint adjustment (calib/joint_problem.h):
// camera pixels on the board's white squares, each with its projector position decoded from T.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::calib {

struct DenseCorrespondences {
  std::vector<cv::Point2f> camera;     // camera pixels
  std::vector<cv::Point2f> projector;  // their projector positions
};

// At most `max_points` camera pixels, spread evenly in raster order over those that lie inside the outline of the
// board's inner corners, on a white square at least 2 px from any edge (the 5 x 5 neighbourhood in the white frame
// within 15 % of its brightest pixel, and at least half the board's white level: a footprint that straddles a dark
// square pulls the correspondence toward the white side), and have a finite correspondence (CV_32FC2, camera pixel
// -> projector x, y). None for max_points 0.
DenseCorrespondences sample_dense_correspondences(const cv::Mat& white, const cv::Mat& correspondence,
                                                  const std::vector<cv::Point2f>& corners, int max_points);

}  // namespace rfrecon::calib
