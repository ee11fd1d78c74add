// Dropped-frame checks: a Gray pair adds up to white + black whatever the scene, a stale frame does not.
#include "host/acquire/frame_checks.h"

#include <cmath>

#include <gtest/gtest.h>

namespace rfrecon::acquire {
namespace {

struct Frames {
  cv::Mat white, black, pattern, inverse;
};

// A scene of uneven albedo (0.2 to 0.8) with ambient 0.05, stripes of width 4 and their inverse.
Frames linear_pair() {
  Frames f;
  const cv::Size size(64, 48);
  f.white.create(size, CV_32F);
  f.black.create(size, CV_32F);
  f.pattern.create(size, CV_32F);
  f.inverse.create(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const float albedo = 0.2f + 0.6f * static_cast<float>(x * y) / static_cast<float>(size.area());
      const bool lit = (x / 4) % 2 == 0;
      f.black.at<float>(y, x) = 0.05f;
      f.white.at<float>(y, x) = 0.05f + albedo;
      f.pattern.at<float>(y, x) = 0.05f + (lit ? albedo : 0.0f);
      f.inverse.at<float>(y, x) = 0.05f + (lit ? 0.0f : albedo);
    }
  }
  return f;
}

TEST(PairMismatch, AGrayPairAddsUpToWhitePlusBlack) {
  const Frames f = linear_pair();
  EXPECT_EQ(pair_mismatch_share(f.white, f.black, f.pattern, f.inverse), 0.0);
}

TEST(PairMismatch, AStaleInverseIsCaughtOnHalfThePixels) {
  const Frames f = linear_pair();
  // The camera handed back the pattern's frame as the inverse's: the lit half doubles, the dark half stays dark.
  EXPECT_NEAR(pair_mismatch_share(f.white, f.black, f.pattern, f.pattern), 1.0, 1e-12);
  // The inverse shows the next bit's pattern (stripes of width 2): a quarter of the pixels are lit twice, a quarter
  // never.
  Frames next = f;
  for (int y = 0; y < next.inverse.rows; ++y) {
    for (int x = 0; x < next.inverse.cols; ++x) {
      const float albedo = f.white.at<float>(y, x) - 0.05f;
      next.inverse.at<float>(y, x) = 0.05f + ((x / 2) % 2 == 0 ? albedo : 0.0f);
    }
  }
  EXPECT_NEAR(pair_mismatch_share(next.white, next.black, next.pattern, next.inverse), 0.5, 1e-12);
}

TEST(PairMismatch, NothingLitGivesNoJudgement) {
  const Frames f = linear_pair();
  EXPECT_TRUE(std::isnan(pair_mismatch_share(f.black, f.black, f.black, f.black)));
}

TEST(SameFrame, IdenticalSamplesOnly) {
  cv::Mat a(4, 4, CV_16U, cv::Scalar(7));
  cv::Mat b = a.clone();
  EXPECT_TRUE(same_frame(a, b));
  b.at<std::uint16_t>(3, 3) = 8;
  EXPECT_FALSE(same_frame(a, b));
  EXPECT_FALSE(same_frame(a, cv::Mat(4, 4, CV_8U, cv::Scalar(7))));
}

}  // namespace
}  // namespace rfrecon::acquire
