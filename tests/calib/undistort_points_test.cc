// calib::undistort_points, chunked over threads, gives exactly cv::undistortPoints' points (every point is
// undistorted alone, so the split cannot change a bit), with and without rectification, for any count of points.
#include "calib/undistort_points.h"

#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "calib/rectification.h"

namespace rfrecon::calib {
namespace {

std::vector<cv::Point2f> random_pixels(std::size_t count) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> x(-0.5f, 1279.5f), y(-0.5f, 1023.5f);
  std::vector<cv::Point2f> pixels(count);
  for (auto& p : pixels) p = {x(random), y(random)};
  return pixels;
}

void expect_same_bits(const std::vector<cv::Point2f>& a, const std::vector<cv::Point2f>& b) {
  ASSERT_EQ(a.size(), b.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differing += a[i] == b[i] ? 0 : 1;
  EXPECT_EQ(differing, 0u);
}

TEST(UndistortPointsTest, EqualsOneCallOfOpenCVForEveryCount) {
  const cv::Mat K = (cv::Mat_<double>(3, 3) << 1600, 0, 655, 0, 1598, 500, 0, 0, 1);
  const cv::Mat dist = (cv::Mat_<double>(1, 5) << -0.08, 0.12, 0.0004, -0.0003, -0.05);
  cv::Mat R;
  cv::Rodrigues(cv::Vec3d(0.01, -0.02, 1.5), R);  // a rectification that turns the image by ~90 degrees
  const cv::Mat P = (cv::Mat_<double>(3, 4) << 1700, 0, 640, 0, 0, 1700, 512, 0, 0, 0, 1, 0);
  for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{32768}, std::size_t{100003}}) {
    SCOPED_TRACE(count);
    const auto pixels = random_pixels(count);
    std::vector<cv::Point2f> expected_plain, expected_rectified;
    if (count > 0) {
      cv::undistortPoints(pixels, expected_plain, K, dist, cv::noArray(), cv::noArray(), undistort_criteria());
      cv::undistortPoints(pixels, expected_rectified, K, dist, R, P, undistort_criteria());
    }
    expect_same_bits(undistort_points(pixels, K, dist, cv::Mat(), cv::Mat(), undistort_criteria()), expected_plain);
    expect_same_bits(undistort_points(pixels, K, dist, R, P, undistort_criteria()), expected_rectified);
  }
}

}  // namespace
}  // namespace rfrecon::calib
