// Whether a set of board poses can calibrate a device well: the spread of the board's tilts, how much of the image
// the boards cover, and the warnings a user gets before trusting the result (docs/calibration.md, "Capturing poses").
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calib {

// Below these a calibration still runs, with a warning: too few poses leave the focal lengths and the baseline
// uncertain, small tilts leave the focal length weakly observable, uncovered image regions leave the distortion
// unconstrained there.
inline constexpr int kRecommendedPoses = 10;
inline constexpr double kRecommendedTiltSpreadDeg = 30.0;
inline constexpr double kRecommendedCoverage = 0.6;
// The coverage grid: the image is cut into this many cells along its longer side (square cells).
inline constexpr int kCoverageCellsLongSide = 8;

// The largest angle between two board normals, in degrees (board rotations as Rodrigues vectors, board to device).
double board_tilt_spread_deg(const std::vector<cv::Vec3d>& board_rvecs);

// How many views' boards cover each pixel: CV_32S, image_size. A board covers the quadrilateral of its printed
// pattern (the inner corners' grid extended by one square on each side), since the outer squares must be seen too.
cv::Mat board_coverage_counts(const std::vector<std::vector<cv::Point2f>>& corners, const BoardSpec& board,
                              cv::Size image_size);

// The fraction of coverage-grid cells whose centre at least one board covers.
double covered_fraction(const cv::Mat& coverage_counts);

// The warnings for a pose set: too few poses, too small a tilt spread.
std::vector<std::string> pose_set_warnings(int views, double tilt_spread_deg);

// The warning for a device whose image the boards cover too little (empty when coverage is enough).
std::string coverage_warning(const std::string& device, double coverage);

}  // namespace rfrecon::calib
