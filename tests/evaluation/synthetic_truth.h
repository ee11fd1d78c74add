// Test helper: a 40x30 ground truth on disk in the truth format, and a reconstruction of it whose errors
// are known exactly (every depth and offset is a multiple of 1/8 mm, exact in float32).
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "host/outputs/reconstruction.h"
#include "host/truth/ground_truth.h"

namespace rfrecon::evaluation::testing {

// Truth: row 0 sees nothing; rows 1..29 see z = 512 + x / 4 mm with normal (0, 0, -1). Columns 0..19 are the
// subject "cube" (objects[0], a 20 x 30 x 60 mm box: size 60 mm), columns 20..39 the infinite plane "wall"
// (objects[1]). objects[2], the sphere "ball" (r 10 mm), is not visible.
constexpr int kWidth = 40, kHeight = 30;
constexpr double kBoxSizeMm = 60.0;

inline std::vector<truth::TruthObject> objects() {
  return {{1, "cube", "box", kBoxSizeMm, "longest edge"},
          {2, "wall", "plane", 0.0, "none (infinite plane)"},
          {3, "ball", "sphere", 20.0, "diameter"}};
}

inline float truth_depth(int x, int y) { return y == 0 ? NAN : 512.0f + 0.25f * static_cast<float>(x); }

// Writes ROOT/truth/ in the ground-truth format (truth::write_truth).
inline void write_truth(const std::filesystem::path& root) {
  std::filesystem::create_directories(root / "truth");
  truth::TruthMaps maps;
  maps.depth_mm.create(kHeight, kWidth, CV_32F);
  maps.normals.create(kHeight, kWidth, CV_32FC3);
  maps.object_id.create(kHeight, kWidth, CV_16U);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      maps.depth_mm.at<float>(y, x) = truth_depth(x, y);
      maps.normals.at<cv::Vec3f>(y, x) = y == 0 ? cv::Vec3f(NAN, NAN, NAN) : cv::Vec3f(0.0f, 0.0f, -1.0f);
      maps.object_id.at<std::uint16_t>(y, x) = y == 0 ? 0 : x < 20 ? 1 : 2;
    }
  }
  maps.points_mm = cv::Mat(kHeight, kWidth, CV_32FC3, cv::Scalar::all(NAN));
  maps.visible = cv::Mat(kHeight, kWidth, CV_8U, cv::Scalar(255));
  maps.shadow = cv::Mat::zeros(kHeight, kWidth, CV_8U);
  maps.correspondence = cv::Mat(kHeight, kWidth, CV_32FC2, cv::Scalar::all(NAN));
  truth::write_truth(root / "truth", maps, objects());
}

// The reconstruction: on the cube, column 0 missing, even columns +1/8 mm, odd columns exact, normals tilted by
// kCubeNormalErrorDeg; on the wall, column 39 missing, every other pixel -1/4 mm, normals exact; row 0 (no truth)
// reconstructed at 600 mm, which must be ignored.
constexpr double kCubeNormalErrorDeg = 3.0;

inline outputs::Reconstruction reconstruction() {
  outputs::Reconstruction r;
  r.depth_mm.create(kHeight, kWidth, CV_32F);
  r.points_mm = cv::Mat(kHeight, kWidth, CV_32FC3, cv::Scalar::all(0.0));
  r.normals.create(kHeight, kWidth, CV_32FC3);
  r.confidence = cv::Mat(kHeight, kWidth, CV_32F, cv::Scalar(1.0));
  const double tilt = kCubeNormalErrorDeg * CV_PI / 180.0;
  const cv::Vec3f tilted(static_cast<float>(std::sin(tilt)), 0.0f, static_cast<float>(-std::cos(tilt)));
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const bool cube = x < 20;
      float z = y == 0 ? 600.0f : truth_depth(x, y) + (cube ? (x % 2 == 0 ? 0.125f : 0.0f) : -0.25f);
      if (x == 0 || x == 39) z = NAN;
      r.depth_mm.at<float>(y, x) = z;
      r.normals.at<cv::Vec3f>(y, x) = std::isnan(z) ? cv::Vec3f(NAN, NAN, NAN)
                                      : cube        ? tilted
                                                    : cv::Vec3f(0.0f, 0.0f, -1.0f);
    }
  }
  return r;
}

}  // namespace rfrecon::evaluation::testing
