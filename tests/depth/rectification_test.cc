// The depth stage's rig geometry: projector points rectified by interpolating the precomputed grid agree with their
// exact undistortion, on a rig like a real one (projector above the camera, principal point far off centre, a
// stronger lens than the built-in rigs').
#include "host/depth/rectification.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "calib/rectification.h"
#include "calib/rig.h"
#include "calib/undistort_points.h"

namespace rfrecon::depth {
namespace {

calib::StereoRig projector_above() {
  calib::StereoRig rig;
  rig.camera_size = {640, 512};
  rig.projector_size = {1024, 768};
  rig.camera_matrix = (cv::Mat_<double>(3, 3) << 1100, 0, 330, 0, 1101, 240, 0, 0, 1);
  rig.dist_coeffs = (cv::Mat_<double>(1, 5) << -0.08, 0.05, 0.0005, -0.0003, 0.0);
  rig.projector_matrix =
      (cv::Mat_<double>(3, 3) << 1500, 0, 512, 0, 1500, 40, 0, 0, 1);  // lens offset: cy near the top
  rig.projector_dist_coeffs = (cv::Mat_<double>(1, 5) << -0.15, 0.08, 0.001, -0.0008, 0.0);
  // 170 mm above the camera, tilted 15 degrees down toward the scene.
  const double tilt = 15.0 * CV_PI / 180.0;
  rig.proj_from_cam_rotation =
      (cv::Mat_<double>(3, 3) << 1, 0, 0, 0, std::cos(tilt), -std::sin(tilt), 0, std::sin(tilt), std::cos(tilt));
  rig.proj_from_cam_translation_mm = -rig.proj_from_cam_rotation * (cv::Mat_<double>(3, 1) << 20, -170, 0);
  calib::compute_stereo_geometry(rig);
  return rig;
}

TEST(DepthRectificationTest, ProjectorPointsInterpolatedOnTheGridMatchTheirUndistortion) {
  const calib::StereoRig rig = projector_above();
  const Rectification rectification = depth_rectification(rig, "test rig");
  std::mt19937 random(3);
  std::uniform_real_distribution<float> x(-0.5f, 1023.5f), y(-0.5f, 767.5f);
  std::vector<cv::Point2f> points(20000);
  for (auto& p : points) p = {x(random), y(random)};
  points.push_back({-0.5f, -0.5f});  // the image's corners, where the lens bends most
  points.push_back({1023.5f, 767.5f});
  points.push_back({-3.0f, 400.0f});  // off the grid: undistorted exactly
  points.push_back({500.0f, 770.0f});
  const auto interpolated = rectify_projector_points(points, rig, rectification);
  const auto exact =
      calib::undistort_points(points, rig.projector_matrix, rig.projector_dist_coeffs, rectification.rect_from_proj,
                              rectification.rect_proj_image_from_rect, calib::undistort_criteria());
  // Bilinear interpolation over one pixel of a smooth map errs by (1/8) px^2 times its second derivative: up to about
  // 1.2e-4 px on this lens (k1 = -0.15), with the float rounding of the grid, of the result and of the exact value
  // (up to 6e-5 px each at these coordinates). 2.5e-4 px of disparity is 0.4 um of depth at 600 mm on this rig.
  for (std::size_t i = 0; i + 2 < points.size(); ++i) {
    EXPECT_NEAR(interpolated[i].x, exact[i].x, 2.5e-4) << points[i];
    EXPECT_NEAR(interpolated[i].y, exact[i].y, 2.5e-4) << points[i];
  }
  for (std::size_t i = points.size() - 2; i < points.size(); ++i) EXPECT_EQ(interpolated[i], exact[i]) << points[i];
}

}  // namespace
}  // namespace rfrecon::depth
