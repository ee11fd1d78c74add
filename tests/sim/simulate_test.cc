// The synthetic capture on disk: determinism, frames that linearize back to T L, the noise model's variance, and
// bad input rejected with the field named and nothing left behind.
#include "sim/simulate.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "host/capture/manifest.h"
#include "host/core/errors.h"
#include "sim/builtin_scenes.h"
#include "sim/frames.h"
#include "sim/render.h"
#include "tests/common/temp_dir.h"
#include "tests/sim/test_scenes.h"

namespace rfrecon::sim {
namespace {

namespace fs = std::filesystem;
using testing::kLambert;
using testing::make_scene;
using testing::small_rig;
using testing::tilted_plane;

class SimulateTest : public ::testing::Test {
 protected:
  static std::string bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  // Everything in `dir_` other than `keep`: leftovers of a failed run would show up here.
  std::vector<std::string> entries() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) out.push_back(e.path().filename().string());
    return out;
  }

  rfrecon::testing::TempDir temp_{"sim_test"};
  const fs::path dir_ = temp_.path();
};

Scene small_plane_scene() {
  auto json = small_rig({tilted_plane(kLambert)});
  json["capture"] = {{"dot_spacing", 4}, {"bit_depth", 12}};
  return make_scene(json);
}

TEST_F(SimulateTest, SameSeedGivesIdenticalBytes) {
  // The noise generator is seeded per (seed, frame): same seed, same bytes; another seed, other noise.
  Scene scene = small_plane_scene();
  simulate(scene, dir_ / "a", {2, false, {}});
  simulate(scene, dir_ / "b", {1, false, {}});
  scene.render.seed = 2;
  simulate(scene, dir_ / "c", {2, false, {}});
  const auto manifest = capture::read_manifest(dir_ / "a" / "capture");
  ASSERT_EQ(manifest.frames.size(), 2u + 2u * (7 + 6) + 16u);  // white, black, Gray code pairs, 4x4 dots
  for (const auto& frame : manifest.frames) {
    EXPECT_EQ(bytes(dir_ / "a" / "capture" / frame.file), bytes(dir_ / "b" / "capture" / frame.file)) << frame.file;
  }
  EXPECT_NE(bytes(dir_ / "a" / "capture" / manifest.frames[0].file),
            bytes(dir_ / "c" / "capture" / manifest.frames[0].file));
  EXPECT_EQ(bytes(dir_ / "a" / "truth" / "depth.tiff"), bytes(dir_ / "b" / "truth" / "depth.tiff"));
  for (const char* file : {"depth.tiff", "normals.tiff", "visibility.png", "shadow.png", "correspondences.tiff",
                           "object_id.png", "points.ply", "rig.yaml"}) {
    EXPECT_TRUE(fs::is_regular_file(dir_ / "a" / "truth" / file)) << file;
  }
  // scene.json reproduces the run.
  const Scene again = load_scene_file(dir_ / "a" / "scene.json");
  simulate(again, dir_ / "d", {2, false, {}});
  EXPECT_EQ(bytes(dir_ / "a" / "capture" / manifest.frames[5].file),
            bytes(dir_ / "d" / "capture" / manifest.frames[5].file));
}

TEST_F(SimulateTest, FramesAreUncompressedTiffsUnlessPngIsAsked) {
  // The default frame files are TIFFs holding every 16-bit sample uncompressed (read at memory speed); PNG, asked
  // for, holds the same samples losslessly in fewer bytes.
  Scene scene = small_plane_scene();
  simulate(scene, dir_ / "tiff", {2, false, {}});
  scene.capture.format = "png";
  simulate(scene, dir_ / "png", {2, false, {}});
  const auto tiffs = capture::read_manifest(dir_ / "tiff" / "capture");
  const auto pngs = capture::read_manifest(dir_ / "png" / "capture");
  ASSERT_EQ(tiffs.frames.size(), pngs.frames.size());
  const auto sample_bytes = static_cast<std::uintmax_t>(tiffs.camera_size.area()) * sizeof(std::uint16_t);
  for (std::size_t i = 0; i < tiffs.frames.size(); ++i) {
    const fs::path tiff = dir_ / "tiff" / "capture" / tiffs.frames[i].file;
    const fs::path png = dir_ / "png" / "capture" / pngs.frames[i].file;
    ASSERT_EQ(tiff.extension(), ".tiff");
    ASSERT_EQ(png.extension(), ".png");
    EXPECT_GE(fs::file_size(tiff), sample_bytes) << tiff << " is compressed";
    EXPECT_LT(fs::file_size(png), sample_bytes) << png;
    const cv::Mat a = cv::imread(tiff.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat b = cv::imread(png.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(a.type(), CV_16UC1);
    ASSERT_EQ(b.type(), CV_16UC1);
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << tiffs.frames[i].file;
  }
}

TEST_F(SimulateTest, SharedCameraRaysRenderTheSameTransport) {
  // A lens with distortion: the rays undistorted once for the whole camera (what simulate shares between a scene's
  // views) give T and the ground truth equal to the bit to those the renderer undistorts row by row.
  auto json = small_rig({tilted_plane(kLambert)});
  json["camera"]["distortion"] = {-0.2, 0.05, 0.001, -0.002, 0.0};
  const Scene scene = make_scene(json);
  const CameraRays rays = camera_rays(scene.camera, scene.render);
  ASSERT_EQ(rays.normalized.size(), static_cast<std::size_t>(scene.camera.size.area()) *
                                        (scene.render.supersample * scene.render.supersample + 1));
  const Transport shared = render_transport(scene, scene.render, &rays);
  const Transport alone = render_transport(scene);
  ASSERT_GT(alone.T.nonZeros(), 0);
  ASSERT_EQ(shared.T.nonZeros(), alone.T.nonZeros());
  const auto nnz = static_cast<std::size_t>(alone.T.nonZeros());
  EXPECT_TRUE(std::equal(alone.T.innerIndexPtr(), alone.T.innerIndexPtr() + nnz, shared.T.innerIndexPtr()));
  EXPECT_TRUE(std::equal(alone.T.valuePtr(), alone.T.valuePtr() + nnz, shared.T.valuePtr()));
  const auto same_bytes = [](const cv::Mat& a, const cv::Mat& b) {  // NaN where nothing is seen, in both
    return a.total() * a.elemSize() == b.total() * b.elemSize() &&
           std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;
  };
  EXPECT_TRUE(same_bytes(shared.truth.depth_mm, alone.truth.depth_mm));
  EXPECT_TRUE(same_bytes(shared.truth.correspondence, alone.truth.correspondence));
  RenderOptions finer = scene.render;
  finer.supersample += 1;  // rays of another supersampling are refused, not read past their end
  EXPECT_THROW(render_transport(scene, finer, &rays), std::invalid_argument);
}

TEST_F(SimulateTest, NoiseFreeFramesLinearizeToTransport) {
  // Without noise, capture::load_frame must give back T L + ambient up to quantisation: with a response
  // reading = linear^(1/gamma), linear = reading^gamma moves by at most gamma * 0.5 DN / span per half DN.
  for (const double gamma : {1.0, 2.2}) {
    Scene scene = small_plane_scene();
    scene.capture.full_well_electrons = 0;
    scene.capture.read_noise_dn = 0;
    scene.capture.ambient = 0.01;
    scene.capture.bit_depth = 16;
    scene.capture.black_level = 64;
    scene.capture.response_gamma = gamma;
    const fs::path out = dir_ / ("gamma" + std::to_string(gamma));
    simulate(scene, out, {2, false, {}});
    const auto T = render_transport(scene).T;
    const auto manifest = capture::read_manifest(out / "capture");
    const double tolerance = gamma * 0.5 / (65535.0 - 64.0) + 1e-6;
    for (std::size_t i = 0; i < manifest.frames.size(); i += 7) {
      const cv::Mat pattern = capture::render_pattern(manifest.frames[i].pattern, {scene.projector.size, 4});
      const cv::Mat expected = transport_image(T, pattern, scene.camera.size) + scene.capture.ambient;
      const cv::Mat got = capture::load_frame(out / "capture", manifest, i);
      double max_error = 0;
      cv::minMaxLoc(cv::abs(got - cv::min(expected, 1.0)), nullptr, &max_error);
      EXPECT_LT(max_error, tolerance) << manifest.frames[i].file << " gamma " << gamma;
    }
  }
}

TEST_F(SimulateTest, NoiseVarianceMatchesModel) {
  // Two seeds of the white frame of a Lambertian plane: their difference has variance 2 (I / full_well +
  // (read / span)^2 + 1/12 DN^2 quantisation). Over ~4000 pixels the variance estimate has ~2.2% standard error,
  // so the mean ratio must be 1 within 8%.
  const Scene scene = small_plane_scene();
  const auto T = render_transport(scene).T;
  const cv::Mat white(scene.projector.size, CV_8U, cv::Scalar(255));
  const cv::Mat linear = transport_image(T, white, scene.camera.size);
  const auto& s = scene.capture;
  const double span = std::ldexp(1.0, s.bit_depth) - 1.0 - s.black_level;
  cv::Mat a, b;
  camera_reading(linear, s, 1, 0).convertTo(a, CV_64F);
  camera_reading(linear, s, 2, 0).convertTo(b, CV_64F);
  double ratio_sum = 0;
  int n = 0;
  for (int y = 0; y < linear.rows; ++y) {
    for (int x = 0; x < linear.cols; ++x) {
      const double signal = linear.at<float>(y, x);
      if (signal < 0.05) continue;
      const double variance_dn =
          signal / s.full_well_electrons * span * span + s.read_noise_dn * s.read_noise_dn + 1.0 / 12.0;
      const double d = a.at<double>(y, x) - b.at<double>(y, x);
      ratio_sum += d * d / (2.0 * variance_dn);
      ++n;
    }
  }
  ASSERT_GT(n, 3000);
  EXPECT_NEAR(ratio_sum / n, 1.0, 0.08);
}

TEST_F(SimulateTest, BadInputNamesTheField) {
  const auto expect_error = [](const std::function<void()>& run, const std::string& needle) {
    try {
      run();
      ADD_FAILURE() << "no error, expected one mentioning '" << needle << "'";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
    }
  };
  expect_error([] { resolve_scene("no-such-scene"); }, "no-such-scene");
  expect_error([] { builtin_scene("cube"); }, "cube-anisotropic");  // lists the known names
  const fs::path malformed = dir_ / "malformed.json";
  std::ofstream(malformed) << "{\"name\": \"x\", \"camera\": {";
  expect_error([&] { resolve_scene(malformed.string()); }, "malformed.json");
  auto behind = small_rig({tilted_plane(kLambert)});
  behind["objects"][0]["pose"]["position"] = {0.0, 0.0, -100.0};
  expect_error([&] { make_scene(behind); }, "objects[0].pose.position");
  auto zero = small_rig({tilted_plane(kLambert)});
  zero["camera"]["size"] = {0, 480};
  expect_error([&] { make_scene(zero); }, "camera.size");
  auto bad_size = small_rig({{{"shape", "box"},
                              {"size", {10.0, -1.0, 10.0}},
                              {"pose", {{"position", {0, 0, 500}}}},
                              {"material", kLambert}}});
  expect_error([&] { make_scene(bad_size); }, "objects[0].size: must be > 0");
  auto typo = small_rig({tilted_plane(kLambert)});
  typo["objects"][0]["materail"] = kLambert;
  expect_error([&] { make_scene(typo); }, "objects[0].materail: unknown field");
  auto energy = small_rig({tilted_plane({{"brdf", "ward"}, {"diffuse", 0.6}, {"specular", 0.6}})});
  expect_error([&] { make_scene(energy); }, "objects[0].material.specular");
  EXPECT_TRUE(entries().size() == 1);  // only malformed.json
}

TEST_F(SimulateTest, FailureLeavesNothingBehind) {
  // A run that fails after rendering started (an invalid dot spacing only the protocol rejects) leaves neither the
  // output directory nor a staging directory; an existing non-empty output is refused untouched without force.
  Scene scene = small_plane_scene();
  scene.capture.dot_spacing = 1;
  EXPECT_THROW(simulate(scene, dir_ / "out", {2, false, {}}), InputError);
  EXPECT_TRUE(entries().empty());
  fs::create_directories(dir_ / "out");
  std::ofstream(dir_ / "out" / "keep.txt") << "precious";
  EXPECT_THROW(simulate(small_plane_scene(), dir_ / "out", {2, false, {}}), UsageError);
  EXPECT_EQ(bytes(dir_ / "out" / "keep.txt"), "precious");
  EXPECT_EQ(entries(), std::vector<std::string>{"out"});
  simulate(small_plane_scene(), dir_ / "out", {2, true, {}});
  EXPECT_FALSE(fs::exists(dir_ / "out" / "keep.txt"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / "capture" / "manifest.json"));
}

}  // namespace
}  // namespace rfrecon::sim
