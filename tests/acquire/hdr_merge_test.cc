// HDR merging: the merged frame is the exposure-weighted mean of the unsaturated readings, to their quantisation.
#include "host/acquire/hdr_merge.h"

#include <cmath>

#include <gtest/gtest.h>

namespace rfrecon::acquire {
namespace {

capture::CaptureManifest camera_8bit(double black) {
  capture::CaptureManifest camera;
  camera.bit_depth = 8;
  camera.black_level = black;
  return camera;
}

// An 8-bit reading of radiance `r` (in units of the shortest exposure's full scale) at exposure ratio `ratio`.
std::uint8_t reading(double r, double ratio, double black) {
  const double span = 255.0 - black;
  return static_cast<std::uint8_t>(std::lround(black + span * std::min(1.0, r * ratio)));
}

TEST(HdrMerge, MergedFrameIsRadianceToTheQuantisationOfTheExposuresUsed) {
  const double black = 8.0;
  const double span = 255.0 - black;
  const std::vector<double> exposures{4000.0, 1000.0, 16000.0};  // any order
  const int n = 2000;
  std::vector<cv::Mat> raw(3, cv::Mat(1, n, CV_8U));
  std::vector<double> radiance(n);
  for (auto& frame : raw) frame = cv::Mat(1, n, CV_8U);
  for (int x = 0; x < n; ++x) {
    radiance[x] = 0.9 * std::pow(10.0, -3.0 + 3.0 * x / (n - 1));  // 0.0009 .. 0.9: 30 dB
    for (int e = 0; e < 3; ++e) raw[e].at<std::uint8_t>(0, x) = reading(radiance[x], exposures[e] / 1000.0, black);
  }
  const cv::Mat merged = merge_exposures(raw, exposures, camera_8bit(black));
  ASSERT_EQ(merged.type(), CV_16U);
  for (int x = 0; x < n; ++x) {
    // Exposures below the top code contribute; the error is t_min * sum(q_e) / sum(t_e), |q_e| <= 0.5 / span, plus
    // the 16-bit rounding.
    double used_time = 0.0;
    int used = 0;
    for (int e = 0; e < 3; ++e) {
      if (raw[e].at<std::uint8_t>(0, x) < 255) {
        used_time += exposures[e];
        ++used;
      }
    }
    const double bound = 1000.0 * used * 0.5 / span / used_time + 0.5 / 65535.0 + 1e-9;
    EXPECT_NEAR(merged.at<std::uint16_t>(0, x) / 65535.0, radiance[x], bound) << "pixel " << x;
  }
}

TEST(HdrMerge, PixelSaturatedAtEveryExposureStaysSaturated) {
  const std::vector<cv::Mat> raw{cv::Mat(2, 2, CV_8U, cv::Scalar(255)), cv::Mat(2, 2, CV_8U, cv::Scalar(255))};
  const cv::Mat merged = merge_exposures(raw, {100.0, 400.0}, camera_8bit(0.0));
  EXPECT_EQ(cv::countNonZero(merged != 65535), 0);
}

TEST(HdrMerge, TenBitSamplesAreReadWithTheirBlackLevel) {
  capture::CaptureManifest camera;
  camera.bit_depth = 10;
  camera.black_level = 64.0;
  const cv::Mat short_exposure(1, 1, CV_16U, cv::Scalar(64 + 100));  // 100 / 959 of full scale
  const cv::Mat long_exposure(1, 1, CV_16U, cv::Scalar(64 + 400));
  const cv::Mat merged = merge_exposures({short_exposure, long_exposure}, {1.0, 4.0}, camera);
  EXPECT_NEAR(merged.at<std::uint16_t>(0, 0) / 65535.0, (100.0 + 400.0) / 959.0 / 5.0, 1.0 / 65535.0);
}

}  // namespace
}  // namespace rfrecon::acquire
