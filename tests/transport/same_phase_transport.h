// The comparison of two phase-family transports, one from a float implementation (the kernels, the HLS tops: OpenCL's
// atan2 within 6 ulp) and one from the C++ reference (double): flags, energies and T's weights bit for bit,
// correspondences within 1e-4 projector pixel, projector pixels (the correspondences rounded, and T's one entry there)
// equal but where a correspondence lies that close to a pixel edge.
#pragma once

#include <cmath>

#include <gtest/gtest.h>

#include "host/transport/transport_types.h"

namespace rfrecon::transport::testing {

inline constexpr float kToleranceProjectorPx = 1e-4f;
// Whether `a` and `b`, within kToleranceProjectorPx, may round to different projector pixels.
inline bool at_pixel_edge(float a, float b) {
  return std::abs(a - b) <= kToleranceProjectorPx &&
         std::abs(std::abs(a - std::trunc(a)) - 0.5f) <= kToleranceProjectorPx;
}

inline void expect_same_phase_transport(const CompressedTransport& got, const CompressedTransport& expected) {
  ASSERT_EQ(got.camera_pixels(), expected.camera_pixels());
  EXPECT_EQ(got.flags, expected.flags);
  EXPECT_EQ(got.weights, expected.weights);
  EXPECT_EQ(got.direct_energy, expected.direct_energy);
  const std::size_t k = static_cast<std::size_t>(expected.k());
  for (std::size_t c = 0; c < expected.camera_pixels(); ++c) {
    const float* u = &got.correspondence[2 * c];
    const float* e = &expected.correspondence[2 * c];
    if (std::isnan(e[0])) {
      EXPECT_TRUE(std::isnan(u[0]) && std::isnan(u[1])) << c;
      EXPECT_EQ(got.gray_x[c], expected.gray_x[c]) << c;
      EXPECT_EQ(got.gray_y[c], expected.gray_y[c]) << c;
      EXPECT_EQ(got.indices[c * k], expected.indices[c * k]) << c;
      continue;
    }
    EXPECT_NEAR(u[0], e[0], kToleranceProjectorPx) << c;
    EXPECT_NEAR(u[1], e[1], kToleranceProjectorPx) << c;
    const bool edge = at_pixel_edge(u[0], e[0]) || at_pixel_edge(u[1], e[1]);
    if (!edge) {
      EXPECT_EQ(got.gray_x[c], expected.gray_x[c]) << c;
      EXPECT_EQ(got.gray_y[c], expected.gray_y[c]) << c;
      EXPECT_EQ(got.indices[c * k], expected.indices[c * k]) << c;
    }
    for (std::size_t j = 1; j < k; ++j) EXPECT_EQ(got.indices[c * k + j], -1) << c;
  }
}

}  // namespace rfrecon::transport::testing
