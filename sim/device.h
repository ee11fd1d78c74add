// A pinhole device (camera or projector) with the OpenCV intrinsics and distortion model, and its pose in the world
// (= camera) frame. Lengths in millimetres, image coordinates in pixels with pixel (x, y) centred at (x, y).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace rfrecon::sim {

struct Device {
  cv::Size size;                                                        // pixels
  double fx = 800.0, fy = 800.0;                                        // px
  double cx = 319.5, cy = 239.5;                                        // px
  std::array<double, 5> distortion{};                                   // k1 k2 p1 p2 k3 (OpenCV order)
  Eigen::Isometry3d device_from_world = Eigen::Isometry3d::Identity();  // X_dev = R X_world + t

  cv::Mat camera_matrix() const;  // 3x3 CV_64F
  cv::Mat dist_coeffs() const;    // 1x5 CV_64F
  Eigen::Vector3d centre_world() const { return device_from_world.inverse().translation(); }
};

// cv::projectPoints of a point in the device frame (z > 0): distorted pixel coordinates.
Eigen::Vector2d project_device_point(const Device& device, const Eigen::Vector3d& X_dev);

// Undistorted normalised coordinates (x, y) such that the ray (x, y, 1) in the device frame passes through each
// pixel position (cv::undistortPoints).
std::vector<Eigen::Vector2d> undistort_pixels(const Device& device, const std::vector<cv::Point2d>& pixels);

// Solid angle (sr) of the device pixel that sees the direction (x, y, 1) in the device frame, for a distortion-free
// device: cos^3(theta) / (fx fy).
double pixel_solid_angle(const Device& device, const Eigen::Vector2d& normalized);

}  // namespace rfrecon::sim
