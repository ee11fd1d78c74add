// Pixel solid angles from undistorted pixel centres and the Jacobian of undistortion (central differences).
#include "host/depth/solid_angle.h"

#include <cmath>
#include <vector>

#include <opencv2/calib3d.hpp>

namespace rfrecon::depth {

cv::Mat pixel_solid_angles(const cv::Mat& camera_matrix, const cv::Mat& dist_coeffs, cv::Size size) {
  // Per pixel: its centre and the four points half a pixel away along x and y.
  constexpr float kOffsets[5][2] = {{0.0f, 0.0f}, {-0.5f, 0.0f}, {0.5f, 0.0f}, {0.0f, -0.5f}, {0.0f, 0.5f}};
  std::vector<cv::Point2f> pixels;
  pixels.reserve(static_cast<std::size_t>(size.area()) * 5);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      for (const auto& offset : kOffsets) pixels.emplace_back(static_cast<float>(x) + offset[0], y + offset[1]);
    }
  }
  std::vector<cv::Point2f> normalised;
  cv::undistortPoints(pixels, normalised, camera_matrix, dist_coeffs);
  cv::Mat omega(size, CV_32F);
  for (int i = 0; i < size.area(); ++i) {
    const cv::Point2f* p = &normalised[static_cast<std::size_t>(i) * 5];
    const cv::Point2f dx = p[2] - p[1], dy = p[4] - p[3];
    const double area = std::abs(static_cast<double>(dx.x) * dy.y - static_cast<double>(dx.y) * dy.x);
    const double cos_theta = 1.0 / std::sqrt(1.0 + p[0].x * p[0].x + p[0].y * p[0].y);
    omega.at<float>(i / size.width, i % size.width) = static_cast<float>(cos_theta * cos_theta * cos_theta * area);
  }
  return omega;
}

}  // namespace rfrecon::depth
