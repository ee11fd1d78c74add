// Pixel solid angles from undistorted pixel centres and the Jacobian of undistortion (central differences).
#include "host/depth/solid_angle.h"

#include <cmath>
#include <vector>

#include "calib/undistort_points.h"

namespace rfrecon::depth {

cv::Mat pixel_solid_angles(const cv::Mat& camera_matrix, const cv::Mat& dist_coeffs, cv::Size size) {
  // Every pixel's centre, and the points half a pixel away along x and y, each undistorted once: the point right of
  // pixel x is the one left of pixel x + 1. Centres first, then (x - 0.5, y) for x = 0..W, then (x, y - 0.5) for
  // y = 0..H.
  const std::size_t w = static_cast<std::size_t>(size.width), h = static_cast<std::size_t>(size.height);
  std::vector<cv::Point2f> pixels;
  pixels.reserve(w * h + (w + 1) * h + w * (h + 1));
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) pixels.emplace_back(static_cast<float>(x), static_cast<float>(y));
  }
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x <= size.width; ++x) pixels.emplace_back(static_cast<float>(x) - 0.5f, static_cast<float>(y));
  }
  for (int y = 0; y <= size.height; ++y) {
    for (int x = 0; x < size.width; ++x) pixels.emplace_back(static_cast<float>(x), static_cast<float>(y) - 0.5f);
  }
  // OpenCV's default 5 iterations: enough for a smooth factor (tests/depth/solid_angle_test.cc), and 2 to 3 times
  // faster here than calib::undistort_criteria().
  const std::vector<cv::Point2f> normalised = calib::undistort_points(
      pixels, camera_matrix, dist_coeffs, cv::Mat(), cv::Mat(), cv::TermCriteria(cv::TermCriteria::COUNT, 5, 0.01));
  const cv::Point2f* centre = normalised.data();
  const cv::Point2f* along_x = centre + w * h;         // (x - 0.5, y) at along_x[y (W + 1) + x]
  const cv::Point2f* along_y = along_x + (w + 1) * h;  // (x, y - 0.5) at along_y[y W + x]
  cv::Mat omega(size, CV_32F);
  for (std::size_t y = 0; y < h; ++y) {
    for (std::size_t x = 0; x < w; ++x) {
      const cv::Point2f& p = centre[y * w + x];
      const cv::Point2f dx = along_x[y * (w + 1) + x + 1] - along_x[y * (w + 1) + x];
      const cv::Point2f dy = along_y[(y + 1) * w + x] - along_y[y * w + x];
      const double area = std::abs(static_cast<double>(dx.x) * dy.y - static_cast<double>(dx.y) * dy.x);
      const double cos_theta = 1.0 / std::sqrt(1.0 + p.x * p.x + p.y * p.y);
      omega.at<float>(static_cast<int>(y), static_cast<int>(x)) =
          static_cast<float>(cos_theta * cos_theta * cos_theta * area);
    }
  }
  return omega;
}

}  // namespace rfrecon::depth
