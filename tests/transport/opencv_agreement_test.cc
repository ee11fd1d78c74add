// Gray code decoding follows OpenCV's semantic: on the same 8-bit frames, with thresholds set to the same digital
// numbers, the reference decoder keeps exactly the pixels that OpenCV's shadow mask and GrayCodePattern::getProjPixel
// keep, with the same projector coordinates.
#include <gtest/gtest.h>
#include <opencv2/structured_light.hpp>

#include "host/capture/graycode_patterns.h"
#include "host/capture/protocol.h"
#include "tests/transport/synthetic_capture.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::transport {
namespace {

TEST(OpencvAgreementTest, SameValidPixelsAndCoordinatesAsGrayCodePattern) {
  testing::SceneOptions options;
  options.camera_size = {80, 64};
  options.projector_size = {48, 40};
  options.checker_size = 8;
  const auto scene = testing::make_plane_scene(options);
  const auto sequence = capture::opencv_graycode_protocol(options.projector_size);  // Gray pairs, white, black
  const auto frames = testing::render_frames(scene, sequence, 0, 1.0, 21);

  constexpr int kBlackDn = 10;  // OpenCV keeps |white - black| > 10 DN: for integers, > 10.5 DN
  constexpr int kWhiteDn = 5;   // OpenCV rejects |pattern - inverse| < 5 DN: keeps > 4.5 DN
  auto setup = testing::setup_for(frames, options.projector_size, 0, 1);
  setup.thresholds.black = (kBlackDn + 0.5f) / 255.0f;
  setup.thresholds.white = (kWhiteDn - 0.5f) / 255.0f;
  auto accumulator = make_reference_accumulator(setup);
  // feed_all expects each inverse right after its pattern, as OpenCV's order has it.
  const auto ours = testing::feed_all(*accumulator, sequence, testing::linearize(frames));

  cv::structured_light::GrayCodePattern::Params params;
  params.width = options.projector_size.width;
  params.height = options.projector_size.height;
  const auto graycode = cv::structured_light::GrayCodePattern::create(params);
  graycode->setBlackThreshold(kBlackDn);
  graycode->setWhiteThreshold(kWhiteDn);
  const std::vector<cv::Mat> patterns(frames.begin(), frames.end() - 2);
  const cv::Mat& white = frames[frames.size() - 2];
  const cv::Mat& black = frames.back();
  std::size_t opencv_valid = 0, disagreements = 0;
  for (int v = 0; v < options.camera_size.height; ++v) {
    for (int u = 0; u < options.camera_size.width; ++u) {
      const bool lit = std::abs(int{white.at<unsigned char>(v, u)} - int{black.at<unsigned char>(v, u)}) > kBlackDn;
      cv::Point projector;
      const bool valid = lit && !graycode->getProjPixel(patterns, u, v, projector);
      const auto c = static_cast<std::size_t>(v) * static_cast<std::size_t>(options.camera_size.width) +
                     static_cast<std::size_t>(u);
      const bool our_valid = (ours.flags[c] & kFlagValid) != 0;
      opencv_valid += valid ? 1 : 0;
      disagreements += valid != our_valid ? 1 : 0;
      if (valid && our_valid) {
        disagreements += projector != cv::Point(static_cast<int>(ours.pixel_x[c]), static_cast<int>(ours.pixel_y[c]));
      }
    }
  }
  EXPECT_GT(opencv_valid, ours.camera_pixels() / 2) << "the scene must be mostly lit";
  EXPECT_EQ(disagreements, 0u);  // the same integer comparisons: no tolerance
}

}  // namespace
}  // namespace rfrecon::transport
