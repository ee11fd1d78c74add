// The comparison of two phase-family transports, one from a float implementation (the kernels, the HLS tops: OpenCL's
// atan2 within 6 ulp) and one from the C++ reference (double): flags bit for bit, correspondences within 1e-4
// projector pixel; projector pixels (the correspondences rounded), T's rows and energies bit for bit but where a
// correspondence lies that close to a pixel edge (the pixel, and so the dots a row holds, may differ there), or where a
// low-contrast pixel (no correspondence) has its projector pixel one off.
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
  ASSERT_EQ(got.k(), expected.k());
  EXPECT_EQ(got.flags, expected.flags);
  const std::size_t k = static_cast<std::size_t>(expected.k());
  for (std::size_t c = 0; c < expected.camera_pixels(); ++c) {
    const float* u = &got.correspondence[2 * c];
    const float* e = &expected.correspondence[2 * c];
    const bool decoded = !std::isnan(e[0]);
    if (decoded) {
      EXPECT_NEAR(u[0], e[0], kToleranceProjectorPx) << c;
      EXPECT_NEAR(u[1], e[1], kToleranceProjectorPx) << c;
    } else {
      EXPECT_TRUE(std::isnan(u[0]) && std::isnan(u[1])) << c;
    }
    if (decoded && (at_pixel_edge(u[0], e[0]) || at_pixel_edge(u[1], e[1]))) continue;
    if (!decoded && (got.pixel_x[c] != expected.pixel_x[c] || got.pixel_y[c] != expected.pixel_y[c])) {
      // A low-contrast pixel's projector pixel, rounded from the same phase in float and in double, at a pixel edge.
      EXPECT_LE(std::abs(static_cast<long>(got.pixel_x[c]) - static_cast<long>(expected.pixel_x[c])), 1) << c;
      EXPECT_LE(std::abs(static_cast<long>(got.pixel_y[c]) - static_cast<long>(expected.pixel_y[c])), 1) << c;
      continue;
    }
    EXPECT_EQ(got.pixel_x[c], expected.pixel_x[c]) << c;
    EXPECT_EQ(got.pixel_y[c], expected.pixel_y[c]) << c;
    EXPECT_EQ(got.direct_energy[c], expected.direct_energy[c]) << c;
    for (std::size_t j = 0; j < k; ++j) {
      EXPECT_EQ(got.indices[c * k + j], expected.indices[c * k + j]) << c << " entry " << j;
      EXPECT_EQ(got.weights[c * k + j], expected.weights[c * k + j]) << c << " entry " << j;
    }
  }
}

}  // namespace rfrecon::transport::testing
