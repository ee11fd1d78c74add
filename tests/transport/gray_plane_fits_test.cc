// The plane fits of Gray-code-only captures (host/transport/gray_plane_fits.h), in every build this CPU runs:
// boundary points on a known plane, two per pixel (the most a window can hold), give back the plane's value at each
// pixel, also with points of another surface among them; pixels not valid or without a position are left alone; and
// the builds agree with each other.
#include "host/transport/gray_plane_fits.h"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "host/transport/gray_subpixel.h"
#include "kernels/transport/flags.h"

namespace rfrecon::transport::gray_fits {
namespace {

constexpr int kWidth = 40;
constexpr int kHeight = 30;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Projector px at camera position (X, Y) px: a plane of about the slope a real capture's codes have.
double plane_at(double x, double y) { return 300.0 + 0.8 * x - 0.3 * y; }

// Every pixel's right and lower pair has a point, at fractions spread over [0, 1); `outlier_every` > 0 moves every
// so many points 3 px off the plane (another surface, close enough to pass the same-surface test where far away).
struct Points {
  std::vector<std::uint32_t> first_at;
  std::vector<std::int32_t> u;
  std::vector<float> x_fraction;
  std::vector<float> y_fraction;
  std::vector<float> value;

  explicit Points(int outlier_every) {
    for (int v = 0; v < kHeight; ++v) {
      for (int pixel = 0; pixel <= kWidth; ++pixel) {
        first_at.push_back(static_cast<std::uint32_t>(u.size()));
        if (pixel == kWidth) break;
        for (int direction = 0; direction < 2; ++direction) {
          if (direction == 0 ? pixel + 1 >= kWidth : v + 1 >= kHeight) continue;
          const double t = std::fmod(0.37 * pixel + 0.61 * v + 0.29 * direction, 1.0);
          const double x = pixel + (direction == 0 ? t : 0.0);
          const double y = v + (direction == 0 ? 0.0 : t);
          const bool outlier = outlier_every > 0 && u.size() % outlier_every == 0;
          u.push_back(pixel);
          x_fraction.push_back(direction == 0 ? static_cast<float>(t) : 0.0f);
          y_fraction.push_back(direction == 0 ? 0.0f : static_cast<float>(t));
          value.push_back(static_cast<float>(plane_at(x, y) + (outlier ? 3.0 : 0.0)));
        }
      }
    }
    u.resize(u.size() + kMaxLanes, 0);
    for (auto* field : {&x_fraction, &y_fraction, &value}) field->resize(field->size() + kMaxLanes, 0.0f);
  }

  BoundaryRowsView view() const {
    return {kWidth, kHeight, first_at.data(), u.data(), x_fraction.data(), y_fraction.data(), value.data()};
  }
};

constexpr int kInvalid = 17 * kWidth + 20;    // a pixel not valid
constexpr int kNoPosition = 12 * kWidth + 9;  // a valid pixel without a decoded position

// Each pixel's decoded position 0.25 px off the plane (within max_code_offset_px), fitted with the default options in
// two bands of rows.
std::vector<float> fitted(const Build& build, const Points& points) {
  std::vector<std::uint8_t> flags(kWidth * kHeight, RF_FLAG_VALID);
  flags[kInvalid] = 0;
  std::vector<float> correspondence(2 * flags.size(), kNaN);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) correspondence[2 * (y * kWidth + x)] = static_cast<float>(plane_at(x, y) + 0.25);
  }
  correspondence[2 * kNoPosition] = kNaN;
  const FitSettings settings = fit_settings(GraySubpixelOptions{});
  const std::size_t field_slots = window_slots(settings.radius_px);
  std::vector<float> scratch(kScratchFields * field_slots);
  for (const auto& [begin, end] : {std::pair{0, 11}, std::pair{11, kHeight}}) {
    Band band;
    band.flags = flags.data();
    band.correspondence = correspondence.data();
    band.axis = 0;
    band.y_begin = begin;
    band.y_end = end;
    band.scratch = scratch.data();
    band.field_slots = field_slots;
    build.fit_rows(points.view(), settings, band);
  }
  return correspondence;
}

// At least `min_refined` pixels refined, each to the plane's value.
void expect_plane(const Build& build, int outlier_every, int min_refined) {
  const Points points(outlier_every);
  const std::vector<float> out = fitted(build, points);
  int refined = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const int c = y * kWidth + x;
      EXPECT_TRUE(std::isnan(out[2 * c + 1])) << "the other axis is not written";
      if (c == kNoPosition) {
        EXPECT_TRUE(std::isnan(out[2 * c])) << build.name;
        continue;
      }
      const double decoded = plane_at(x, y) + 0.25;
      if (c == kInvalid || std::fabs(out[2 * c] - decoded) < 1e-3) continue;  // left at its decoded position
      ++refined;
      // Float positions of about 300 px carry 3e-5 px; the fit adds a few of those.
      EXPECT_NEAR(out[2 * c], plane_at(x, y), 2e-4) << build.name << " at (" << x << ", " << y << ")";
    }
  }
  EXPECT_FLOAT_EQ(out[2 * kInvalid], static_cast<float>(plane_at(20, 17) + 0.25)) << build.name;
  EXPECT_GE(refined, min_refined) << build.name;
}

TEST(GrayPlaneFitsTest, PointsOnAPlaneGiveItsValue) {
  for (const Build& build : builds_for_this_cpu()) {
    SCOPED_TRACE(build.name);
    // Every valid pixel with a position has points on both sides in both directions, even at the image's border.
    expect_plane(build, 0, kWidth * kHeight - 2);
  }
}

TEST(GrayPlaneFitsTest, PointsOfAnotherSurfaceAreDropped) {
  for (const Build& build : builds_for_this_cpu()) {
    SCOPED_TRACE(build.name);
    // A few pixels' first planes leave too few points or a plane that is not trusted.
    expect_plane(build, 7, (kWidth * kHeight - 2) * 99 / 100);
  }
}

TEST(GrayPlaneFitsTest, BuildsAgree) {
  const std::vector<Build> builds = builds_for_this_cpu();
  std::cout << builds.size() << " builds on this CPU, the first " << builds.front().name << "\n";
  const Points points(7);
  const std::vector<float> first = fitted(builds.front(), points);
  for (const Build& build : builds) {
    const std::vector<float> out = fitted(build, points);
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (std::isnan(first[i])) {
        EXPECT_TRUE(std::isnan(out[i])) << build.name << " at " << i;
      } else {
        EXPECT_NEAR(out[i], first[i], 1e-4) << build.name << " at " << i;
      }
    }
  }
}

}  // namespace
}  // namespace rfrecon::transport::gray_fits
