// Projection and back-projection with the OpenCV pinhole and distortion model.
#include "sim/device.h"

#include <cmath>

#include <opencv2/calib3d.hpp>

namespace rfrecon::sim {

cv::Mat Device::camera_matrix() const { return (cv::Mat_<double>(3, 3) << fx, 0, cx, 0, fy, cy, 0, 0, 1); }

cv::Mat Device::dist_coeffs() const {
  return (cv::Mat_<double>(1, 5) << distortion[0], distortion[1], distortion[2], distortion[3], distortion[4]);
}

Eigen::Vector2d project_device_point(const Device& device, const Eigen::Vector3d& X_dev) {
  const double x = X_dev.x() / X_dev.z();
  const double y = X_dev.y() / X_dev.z();
  const auto& [k1, k2, p1, p2, k3] = device.distortion;
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double xd = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x);
  const double yd = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y;
  return {device.fx * xd + device.cx, device.fy * yd + device.cy};
}

std::vector<Eigen::Vector2d> undistort_pixels(const Device& device, const std::vector<cv::Point2d>& pixels) {
  std::vector<Eigen::Vector2d> normalized(pixels.size());
  if (pixels.empty()) return normalized;
  std::vector<cv::Point2d> out;
  // Many iterations: the default 5 leave ~1e-3 px residuals for strong distortion; rays must be exact.
  cv::undistortPoints(pixels, out, device.camera_matrix(), device.dist_coeffs(), cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-14));
  for (std::size_t i = 0; i < out.size(); ++i) normalized[i] = {out[i].x, out[i].y};
  return normalized;
}

double pixel_solid_angle(const Device& device, const Eigen::Vector2d& normalized) {
  const double cos_theta = 1.0 / std::sqrt(1.0 + normalized.squaredNorm());
  return cos_theta * cos_theta * cos_theta / (device.fx * device.fy);
}

}  // namespace rfrecon::sim
