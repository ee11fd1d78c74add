// Test helper: a 40x30 ground truth on disk in `rfrecon simulate`'s layout, and a reconstruction of it whose errors
// are known exactly (every depth and offset is a multiple of 1/8 mm, exact in float32).
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "host/common/atomic_file.h"
#include "host/reconstruct/reconstruction.h"
#include "sim/scene.h"
#include "tests/sim/test_scenes.h"

namespace rfrecon::reconstruct::testing {

// Truth: row 0 sees nothing; rows 1..29 see z = 512 + x / 4 mm with normal (0, 0, -1). Columns 0..19 are the
// subject "cube" (objects[0], a 20 x 30 x 60 mm box: size 60 mm), columns 20..39 the infinite plane "wall"
// (objects[1]). objects[2], the sphere "ball" (r 10 mm), is not visible.
constexpr int kWidth = 40, kHeight = 30;
constexpr double kBoxSizeMm = 60.0;

inline nlohmann::json scene_json() {
  const nlohmann::json lambert{{"brdf", "lambert"}, {"diffuse", 0.5}};
  return sim::testing::small_rig(
      {{{"name", "cube"},
        {"shape", "box"},
        {"size", {20.0, 30.0, 60.0}},
        {"pose", {{"position", {0, 0, 500}}}},
        {"material", lambert}},
       {{"name", "wall"}, {"shape", "plane"}, {"pose", {{"position", {0, 0, 700}}}}, {"material", lambert}},
       {{"name", "ball"},
        {"shape", "sphere"},
        {"size", {10.0}},
        {"pose", {{"position", {300, 0, 500}}}},
        {"material", lambert}}});
}

inline float truth_depth(int x, int y) { return y == 0 ? NAN : 512.0f + 0.25f * static_cast<float>(x); }

// Writes ROOT/scene.json (resolved, as simulate does) and ROOT/truth/{depth.tiff, normals.tiff, object_id.png}.
inline void write_truth(const std::filesystem::path& root, const nlohmann::json& scene = scene_json()) {
  std::filesystem::create_directories(root / "truth");
  const auto resolved = sim::scene_to_json(sim::testing::make_scene(scene));
  write_file_atomically(root / "scene.json", resolved.dump(2));
  cv::Mat depth(kHeight, kWidth, CV_32F), normals(kHeight, kWidth, CV_32FC3), id(kHeight, kWidth, CV_16U);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      depth.at<float>(y, x) = truth_depth(x, y);
      normals.at<cv::Vec3f>(y, x) = y == 0 ? cv::Vec3f(NAN, NAN, NAN) : cv::Vec3f(0.0f, 0.0f, -1.0f);
      id.at<std::uint16_t>(y, x) = y == 0 ? 0 : x < 20 ? 1 : 2;
    }
  }
  const std::vector<int> uncompressed{cv::IMWRITE_TIFF_COMPRESSION, 1};
  cv::imwrite((root / "truth" / "depth.tiff").string(), depth, uncompressed);
  cv::imwrite((root / "truth" / "normals.tiff").string(), normals, uncompressed);
  cv::imwrite((root / "truth" / "object_id.png").string(), id);
}

// The reconstruction: on the cube, column 0 missing, even columns +1/8 mm, odd columns exact, normals tilted by
// kCubeNormalErrorDeg; on the wall, column 39 missing, every other pixel -1/4 mm, normals exact; row 0 (no truth)
// reconstructed at 600 mm, which must be ignored.
constexpr double kCubeNormalErrorDeg = 3.0;

inline Reconstruction reconstruction() {
  Reconstruction r;
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

}  // namespace rfrecon::reconstruct::testing
