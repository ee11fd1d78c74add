// The comparison of two compressed transports computed by different kernel entries or devices: everything but the
// correspondence is integer logic or one float subtraction/addition in the same order, so it must agree bit for bit;
// the centroid divides, and OpenCL's single-precision division may be off by 2.5 ulp: 1e-5 projector pixels covers
// that at the test captures' coordinates (< 64).
#pragma once

#include <cmath>

#include <gtest/gtest.h>

#include "host/transport/transport_types.h"

namespace rfrecon::transport::testing {

inline constexpr float kCorrespondenceTolerancePx = 1e-5f;

inline void expect_same_transport(const CompressedTransport& got, const CompressedTransport& expected) {
  EXPECT_EQ(got.indices, expected.indices);
  EXPECT_EQ(got.weights, expected.weights);
  EXPECT_EQ(got.pixel_x, expected.pixel_x);
  EXPECT_EQ(got.pixel_y, expected.pixel_y);
  EXPECT_EQ(got.flags, expected.flags);
  EXPECT_EQ(got.direct_energy, expected.direct_energy);
  ASSERT_EQ(got.correspondence.size(), expected.correspondence.size());
  for (std::size_t i = 0; i < got.correspondence.size(); ++i) {
    if (std::isnan(expected.correspondence[i])) {
      EXPECT_TRUE(std::isnan(got.correspondence[i])) << i;
    } else {
      EXPECT_NEAR(got.correspondence[i], expected.correspondence[i], kCorrespondenceTolerancePx) << i;
    }
  }
}

}  // namespace rfrecon::transport::testing
