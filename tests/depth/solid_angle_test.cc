// Pixel solid angles: cos^3(theta) / (fx fy) for a pinhole, and with lens distortion the solid angle of the pixel's
// square (its four corners undistorted, the quadrilateral's area) to within the central differences' error.
#include "host/depth/solid_angle.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

namespace rfrecon::depth {
namespace {

const cv::Mat kCameraMatrix = (cv::Mat_<double>(3, 3) << 800, 0, 300, 0, 790, 90, 0, 0, 1);  // centre far off
const cv::Size kSize(640, 512);

double cos_cubed(double x_n, double y_n) { return std::pow(1.0 + x_n * x_n + y_n * y_n, -1.5); }

TEST(SolidAngleTest, PinholePixelsSeeCosCubedOverFocalLengths) {
  const cv::Mat omega = pixel_solid_angles(kCameraMatrix, cv::Mat(), kSize);
  for (const cv::Point pixel : {cv::Point(0, 0), cv::Point(300, 90), cv::Point(639, 511), cv::Point(17, 400)}) {
    const double x_n = (pixel.x - 300.0) / 800.0, y_n = (pixel.y - 90.0) / 790.0;
    const double expected = cos_cubed(x_n, y_n) / (800.0 * 790.0);
    // float32 normalised coordinates (6e-8 of ~0.5) differenced over half a pixel (6e-4): 1e-4 relative.
    EXPECT_NEAR(omega.at<float>(pixel), expected, 1e-4 * expected) << pixel;
  }
}

TEST(SolidAngleTest, DistortedPixelsSeeTheirUndistortedSquare) {
  const cv::Mat dist = (cv::Mat_<double>(1, 5) << -0.12, 0.08, 0.001, -0.0005, 0.0);
  const cv::Mat omega = pixel_solid_angles(kCameraMatrix, dist, kSize);
  for (const cv::Point pixel : {cv::Point(0, 0), cv::Point(300, 90), cv::Point(639, 511), cv::Point(17, 400)}) {
    const std::vector<cv::Point2f> corners = {{pixel.x - 0.5f, pixel.y - 0.5f},
                                              {pixel.x + 0.5f, pixel.y - 0.5f},
                                              {pixel.x + 0.5f, pixel.y + 0.5f},
                                              {pixel.x - 0.5f, pixel.y + 0.5f}};
    std::vector<cv::Point2f> n;
    cv::undistortPoints(corners, n, kCameraMatrix, dist, cv::noArray(), cv::noArray(),
                        {cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-12});
    double area = 0.0;  // shoelace, in double about the first corner (float products would cancel)
    for (int i = 1; i + 1 < 4; ++i) {
      const cv::Point2d a = cv::Point2d(n[i]) - cv::Point2d(n[0]), b = cv::Point2d(n[i + 1]) - cv::Point2d(n[0]);
      area += a.x * b.y - a.y * b.x;
    }
    const cv::Point2f centre = (n[0] + n[1] + n[2] + n[3]) * 0.25f;
    const double expected = cos_cubed(centre.x, centre.y) * std::abs(area) / 2.0;
    // Central differences, float32 points and OpenCV's 5 undistortion iterations against the quadrilateral: 1e-4.
    EXPECT_NEAR(omega.at<float>(pixel), expected, 1e-4 * expected) << pixel;
  }
}

}  // namespace
}  // namespace rfrecon::depth
