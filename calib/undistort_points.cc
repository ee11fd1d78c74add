// Chunked, parallel cv::undistortPoints.
#include "calib/undistort_points.h"

#include <algorithm>

#include <opencv2/calib3d.hpp>

namespace rfrecon::calib {

std::vector<cv::Point2f> undistort_points(const std::vector<cv::Point2f>& points, const cv::Mat& camera_matrix,
                                          const cv::Mat& dist_coeffs, const cv::Mat& R, const cv::Mat& P,
                                          const cv::TermCriteria& criteria) {
  constexpr int kChunk = 1 << 15;  // points per call: large enough that a call's setup does not count
  std::vector<cv::Point2f> undistorted(points.size());
  const cv::Mat in(points), out(undistorted);  // N x 1 CV_32FC2 headers on the vectors' memory
  const int chunks = static_cast<int>((points.size() + kChunk - 1) / kChunk);
  cv::parallel_for_(cv::Range(0, chunks), [&](const cv::Range& range) {
    for (int chunk = range.start; chunk < range.end; ++chunk) {
      const int begin = chunk * kChunk, end = std::min(static_cast<int>(points.size()), begin + kChunk);
      cv::Mat part = out.rowRange(begin, end);  // written in place: undistortPoints keeps a buffer of the right size
      cv::undistortPoints(in.rowRange(begin, end), part, camera_matrix, dist_coeffs, R, P, criteria);
      CV_Assert(part.data == out.ptr(begin));
    }
  });
  return undistorted;
}

}  // namespace rfrecon::calib
