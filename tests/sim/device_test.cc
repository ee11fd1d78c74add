// The synthetic devices follow OpenCV's camera model: projection equals cv::projectPoints, and back-projection
// (cv::undistortPoints) inverts it.
#include "sim/device.h"

#include <random>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

namespace rfrecon::sim {
namespace {

Device distorted_device() {
  Device d;
  d.size = {640, 480};
  d.fx = 820.0;
  d.fy = 815.0;
  d.cx = 322.0;
  d.cy = 236.5;
  d.distortion = {-0.12, 0.08, 0.001, -0.0007, -0.02};
  return d;
}

TEST(DeviceTest, ProjectionMatchesOpenCv) {
  // Same formula evaluated in the same precision: agreement to 1e-9 px (rounding only).
  const Device d = distorted_device();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> xy(-300.0, 300.0), z(400.0, 900.0);
  std::vector<cv::Point3d> points;
  for (int i = 0; i < 200; ++i) points.emplace_back(xy(rng), xy(rng) * 0.75, z(rng));
  std::vector<cv::Point2d> expected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), d.camera_matrix(), d.dist_coeffs(), expected);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto got = project_device_point(d, {points[i].x, points[i].y, points[i].z});
    EXPECT_NEAR(got.x(), expected[i].x, 1e-9);
    EXPECT_NEAR(got.y(), expected[i].y, 1e-9);
  }
}

TEST(DeviceTest, UndistortInvertsProjection) {
  // The renderer's rays come from undistort_pixels; re-projecting them must land on the pixel they were made for.
  // 1e-6 px: the iterative undistortion is run to convergence (1e-14), far below any effect on T.
  const Device d = distorted_device();
  std::vector<cv::Point2d> pixels;
  for (int y = 0; y < d.size.height; y += 37) {
    for (int x = 0; x < d.size.width; x += 41) pixels.emplace_back(x, y);
  }
  const auto normalized = undistort_pixels(d, pixels);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const auto back = project_device_point(d, {normalized[i].x(), normalized[i].y(), 1.0});
    EXPECT_NEAR(back.x(), pixels[i].x, 1e-6);
    EXPECT_NEAR(back.y(), pixels[i].y, 1e-6);
  }
}

}  // namespace
}  // namespace rfrecon::sim
