// The depth-method seam end to end: `rfrecon_toy_cli` is the CLI's main linked with tests/depth/toy_depth_method.cc,
// a method registered from outside host/depth. Its `reconstruct --method toy-scale` runs through the whole command
// (options, summary, outputs) and gives exactly 1.01 times the triangulated depth on the same pixels, on a plane seen
// by a camera and a projector of different sizes; the plain CLI does not know the method and says which it knows.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;

TEST(ToyDepthMethod, RegisteredOutsideTheDepthLayerRunsThroughTheCli) {
  testing::TempDir dir("toy_method");
  const fs::path scene = dir.path() / "scene";
  ASSERT_EQ(
      run_cli("-q simulate --scene plane-lambert --camera 80x64 --projector 64x40 -o " + scene.string()).exit_code, 0);
  ASSERT_EQ(run_cli("-q transport " + (scene / "capture").string() + " -o " + (scene / "T.h5").string()).exit_code, 0);
  const std::string inputs = (scene / "T.h5").string() + " --calib " + (scene / "truth" / "rig.yaml").string() + " -o ";

  const auto help = testing::run_program(RFRECON_TOY_CLI_PATH, "reconstruct --help");
  EXPECT_NE(help.output.find("toy-scale: test method"), std::string::npos) << help.output;
  const auto plain = run_cli("reconstruct " + inputs + (dir.path() / "plain").string() + " --method toy-scale");
  EXPECT_EQ(plain.exit_code, 2) << plain.output;
  EXPECT_NE(plain.output.find("fused"), std::string::npos) << plain.output;

  const auto triangulated = run_cli("reconstruct " + inputs + (dir.path() / "tri").string() + " --method triangulate");
  ASSERT_EQ(triangulated.exit_code, 0) << triangulated.output;
  const auto toy = testing::run_program(
      RFRECON_TOY_CLI_PATH, "reconstruct " + inputs + (dir.path() / "toy").string() + " --method toy-scale");
  ASSERT_EQ(toy.exit_code, 0) << toy.output;

  std::ifstream summary_file(dir.path() / "toy" / "summary.json");
  const auto summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary.at("method"), "toy-scale");
  const cv::Mat tri = cv::imread((dir.path() / "tri" / "depth.tiff").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat scaled = cv::imread((dir.path() / "toy" / "depth.tiff").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(tri.type(), CV_32F);
  ASSERT_EQ(scaled.size(), tri.size());
  int pixels = 0;
  double worst = 0.0;
  for (int y = 0; y < tri.rows; ++y) {
    for (int x = 0; x < tri.cols; ++x) {
      const float z = tri.at<float>(y, x);
      const float z_toy = scaled.at<float>(y, x);
      ASSERT_EQ(std::isnan(z), std::isnan(z_toy)) << "pixel " << x << "," << y << ": not the same pixels";
      if (std::isnan(z)) continue;
      ++pixels;
      worst = std::max(worst, std::abs(z_toy / z - 1.01));
    }
  }
  EXPECT_GT(pixels, tri.rows * tri.cols / 4);
  EXPECT_LT(worst, 1e-5) << "depth ratio off 1.01 by up to " << worst;  // float rounding of X = R1^T z (a, b, 1)
}

}  // namespace
}  // namespace rfrecon
