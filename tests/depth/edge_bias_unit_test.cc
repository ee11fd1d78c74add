// correct_edge_bias on fields with a known answer: a white frame that rises linearly under an affine camera ->
// projector map moves every interior correspondence by exactly S2 grad(w) / w through the map's Jacobian; at a sharp
// step the move stops at half the footprint's width; pixels without a correspondence stay NaN.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "host/depth/edge_bias.h"

namespace rfrecon::depth {
namespace {

const cv::Size kCamera{40, 30};

struct Fields {
  std::vector<float> correspondence;  // projector x = 0.5 x + 3, y = 0.25 y + 0.1 x
  std::vector<float> white;
};

template <typename White>
Fields affine_map_under(White white_at) {
  Fields fields;
  for (int y = 0; y < kCamera.height; ++y) {
    for (int x = 0; x < kCamera.width; ++x) {
      fields.correspondence.push_back(0.5f * static_cast<float>(x) + 3.0f);
      fields.correspondence.push_back(0.25f * static_cast<float>(y) + 0.1f * static_cast<float>(x));
      fields.white.push_back(white_at(x, y));
    }
  }
  return fields;
}

TEST(EdgeBiasUnitTest, LinearWhiteMovesEachCorrespondenceByTheFootprintsMomentTimesTheRelativeGradient) {
  const Fields fields = affine_map_under([](int x, int y) { return 0.2f + 0.01f * x + 0.004f * y; });
  const double s2 = 0.25;
  const auto corrected = correct_edge_bias(fields.correspondence, fields.white, kCamera, s2);
  for (int y = 6; y < kCamera.height - 6; ++y) {
    for (int x = 6; x < kCamera.width - 6; ++x) {
      const std::size_t c = static_cast<std::size_t>(y * kCamera.width + x);
      const double w = 0.2 + 0.01 * x + 0.004 * y;
      const double dx = s2 * 0.01 / w, dy = s2 * 0.004 / w;  // camera px toward the bright side
      EXPECT_NEAR(corrected[2 * c], fields.correspondence[2 * c] - 0.5 * dx, 1e-5) << x << "," << y;
      EXPECT_NEAR(corrected[2 * c + 1], fields.correspondence[2 * c + 1] - (0.1 * dx + 0.25 * dy), 1e-5)
          << x << "," << y;
    }
  }
}

TEST(EdgeBiasUnitTest, AStepMovesAtMostHalfTheFootprintAndNaNStaysNaN) {
  Fields fields = affine_map_under([](int x, int) { return x < 20 ? 0.01f : 0.8f; });
  fields.correspondence[2 * (15 * kCamera.width + 5)] = NAN;
  fields.correspondence[2 * (15 * kCamera.width + 5) + 1] = NAN;
  const double s2 = 1.0 / 12.0;
  const auto corrected = correct_edge_bias(fields.correspondence, fields.white, kCamera, s2);
  const double half_width_px = std::sqrt(3.0 * s2);  // 0.5: a square pixel's half width
  for (int x = 17; x < 23; ++x) {
    const std::size_t c = static_cast<std::size_t>(15 * kCamera.width + x);
    const double moved = fields.correspondence[2 * c] - corrected[2 * c];
    EXPECT_GE(moved, 0.0) << x;  // toward the dark side, against the bright one's pull
    EXPECT_LE(moved, 0.5 * half_width_px + 1e-6) << x;
  }
  const auto moved_at = [&](int x) {
    const std::size_t c = static_cast<std::size_t>(15 * kCamera.width + x);
    return fields.correspondence[2 * c] - corrected[2 * c];
  };
  // The dark pixel beside the step: its relative gradient asks for 3.3 px, half the width (0.5 px) is what it gets.
  EXPECT_NEAR(moved_at(19), 0.5 * half_width_px, 1e-5);
  // The bright one: (0.8 - 0.01) / 2 per px over 0.8, times 1/12, through d(projector x)/d(camera x) = 0.5.
  EXPECT_NEAR(moved_at(20), 0.5 * s2 * 0.395 / 0.8, 1e-5);
  EXPECT_TRUE(std::isnan(corrected[2 * (15 * kCamera.width + 5)]));
  // Away from the step the white frame is uniform: nothing moves.
  const std::size_t far = static_cast<std::size_t>(15 * kCamera.width + 30);
  EXPECT_FLOAT_EQ(corrected[2 * far], fields.correspondence[2 * far]);
}

}  // namespace
}  // namespace rfrecon::depth
