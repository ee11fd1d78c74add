// Inputs and tolerance shared by the tests that compare the row solvers' kernels (OpenCL entries, HLS C++ tops)
// with their C++ references: noisy analytic rows of a tilted plane with one masked pixel.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "tests/depth/analytic_rows.h"

namespace rfrecon::depth::testing {

inline Plane tilted_plane() {
  // Normal tilted 20 degrees about y and 6 about x, facing the devices, through (10, 0, 500) mm.
  const double nx = 0.34, ny = -0.1, nz = -0.93, length = std::sqrt(nx * nx + ny * ny + nz * nz);
  Plane plane{nx / length, ny / length, nz / length, 0.0};
  plane.d = plane.nx * 10.0 + plane.nz * 500.0;
  return plane;
}

// Deterministic "noise" in [-1, 1].
inline float pseudo_noise(std::size_t i) {
  return static_cast<float>(std::sin(12.9898 * static_cast<double>(i) + 1.0));
}

// `height` rows of 24 pixels, +-0.5 mm noise on the triangulated depths, one masked pixel then a new run in row 5.
inline RectifiedRows kernel_test_rows(int height = 11) {
  RectifiedRows rows = analytic_rows(tilted_plane(), 24, height);
  for (std::size_t i = 0; i < rows.z_tri.size(); ++i) rows.z_tri[i] += 0.5f * pseudo_noise(i);
  rows.runs[5 * 24 + 7] = RF_RUN_MASKED;
  rows.runs[5 * 24 + 8] = RF_RUN_START;
  return rows;
}

// Same float arithmetic as the reference (FP_CONTRACT OFF), but OpenCL's sqrt and division may differ from the
// host's by an ulp or two: 1e-5 relative (6 um at 600 mm) bounds their effect after a row of RK4 steps.
inline void expect_close(const std::vector<float>& actual, const std::vector<float>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    if (std::isnan(expected[i])) {
      EXPECT_TRUE(std::isnan(actual[i])) << "pixel " << i;
    } else {
      EXPECT_NEAR(actual[i], expected[i], 1e-5 * std::abs(expected[i])) << "pixel " << i;
    }
  }
}

}  // namespace rfrecon::depth::testing
