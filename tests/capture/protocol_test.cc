// The pattern sequence matches OpenCV's GrayCodePattern pixel for pixel and decodes to every projector coordinate.
#include "host/capture/protocol.h"

#include <gtest/gtest.h>
#include <opencv2/structured_light.hpp>

#include "host/capture/graycode_patterns.h"
#include "host/core/errors.h"

namespace rfrecon::capture {
namespace {

// Sizes chosen to cover powers of two and not (OpenCV rounds the bit count up).
class ProtocolSizes : public ::testing::TestWithParam<cv::Size> {};

TEST_P(ProtocolSizes, GrayCodeImagesEqualOpenCvs) {
  const cv::Size size = GetParam();
  cv::structured_light::GrayCodePattern::Params params;
  params.width = size.width;
  params.height = size.height;
  const auto opencv = cv::structured_light::GrayCodePattern::create(params);
  std::vector<cv::Mat> expected;
  ASSERT_TRUE(opencv->generate(expected));
  cv::Mat black;
  cv::Mat white;
  opencv->getImagesForShadowMasks(black, white);
  expected.push_back(white);
  expected.push_back(black);

  const auto sequence = opencv_graycode_protocol(size);
  ASSERT_EQ(sequence.size(), expected.size());
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const cv::Mat ours = render_pattern(sequence[i], {size, 0});
    EXPECT_EQ(cv::countNonZero(ours != expected[i]), 0) << "frame " << i << " differs from OpenCV's";
  }
}

TEST_P(ProtocolSizes, GrayCodeIsUniqueAndNeighboursDifferByOneBit) {
  const cv::Size size = GetParam();
  const int bits = gray_bits(size.width);
  ASSERT_GE(1 << bits, size.width);
  std::vector<int> codes;
  for (int x = 0; x < size.width; ++x) {
    int code = 0;
    for (int bit = 0; bit < bits; ++bit) code = (code << 1) | (gray_code_bit(x, bit, bits) ? 1 : 0);
    codes.push_back(code);
  }
  for (int x = 1; x < size.width; ++x) EXPECT_EQ(__builtin_popcount(codes[x] ^ codes[x - 1]), 1) << "x=" << x;
  std::sort(codes.begin(), codes.end());
  EXPECT_EQ(std::adjacent_find(codes.begin(), codes.end()), codes.end()) << "two columns share a code";
}

INSTANTIATE_TEST_SUITE_P(Sizes, ProtocolSizes, ::testing::Values(cv::Size(64, 48), cv::Size(100, 37)));

TEST(ProtocolTest, DotGridLightsEveryProjectorPixelExactlyOnce) {
  const cv::Size size(50, 30);
  ProtocolOptions options{size, 4};
  const auto sequence = make_protocol(options);
  ASSERT_EQ(sequence.size(), 2U + 2U * (gray_bits(50) + gray_bits(30)) + 16U);
  EXPECT_EQ(sequence[0].kind, pattern_kind::kWhite);
  EXPECT_EQ(sequence[1].kind, pattern_kind::kBlack);
  cv::Mat count(size, CV_32S, cv::Scalar(0));
  for (const auto& pattern : sequence) {
    if (pattern.kind != pattern_kind::kDot) continue;
    cv::Mat lit;
    render_pattern(pattern, options).convertTo(lit, CV_32S, 1.0 / 255);
    count += lit;
  }
  EXPECT_EQ(cv::countNonZero(count != 1), 0);
}

TEST(ProtocolTest, RejectsDegenerateOptions) {
  EXPECT_ANY_THROW(make_protocol({cv::Size(0, 480), 0}));
  EXPECT_ANY_THROW(make_protocol({cv::Size(640, 480), 1}));
  EXPECT_THROW(make_protocol({cv::Size(640, 480), 0, "stripes"}), InputError);  // no such family
}

}  // namespace
}  // namespace rfrecon::capture
