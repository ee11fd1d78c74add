// cv::undistortPoints over many points on every core: the points cut into chunks, each undistorted by its own call.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::calib {

// The same result as cv::undistortPoints(points, K, dist, R, P, criteria) (each point is undistorted alone), on all
// hardware threads through cv::parallel_for_ when there are many points.
std::vector<cv::Point2f> undistort_points(const std::vector<cv::Point2f>& points, const cv::Mat& camera_matrix,
                                          const cv::Mat& dist_coeffs, const cv::Mat& R, const cv::Mat& P,
                                          const cv::TermCriteria& criteria);

}  // namespace rfrecon::calib
