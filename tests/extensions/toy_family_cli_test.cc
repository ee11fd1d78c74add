// The pattern-family seam end to end: `rfrecon_toy_cli` is the CLI's main linked with
// tests/extensions/toy_pattern_family.cc, a family ("binary": plain binary code, no inverses) registered from outside
// the library. Its `patterns` writes the family's images and manifest; `simulate --family binary` renders it;
// `transport` decodes it with the family's own accumulator to the projector pixel each camera pixel sees, and `dual`
// reads the result. The plain CLI does not know the family and says which it knows.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "host/transport/transport_file.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;

testing::CliResult run_toy(const std::string& arguments) {
  return testing::run_program(RFRECON_TOY_CLI_PATH, arguments);
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

TEST(ToyPatternFamily, PatternsCommandWritesTheFamilysImagesAndManifest) {
  testing::TempDir dir("toy_family_patterns");
  const auto help = run_toy("patterns --help");
  EXPECT_NE(help.output.find("binary: test family"), std::string::npos) << help.output;
  const fs::path out = dir.path() / "patterns";
  const auto written = run_toy("-q patterns --family binary --projector 64x40 -o " + out.string());
  ASSERT_EQ(written.exit_code, 0) << written.output;
  const auto manifest = read_json(out / "manifest.json");
  EXPECT_EQ(manifest.at("family"), "binary");
  ASSERT_EQ(manifest.at("frames").size(), 2U + 6U + 6U);  // white, black, 6 column and 6 row bits
  const auto& msb = manifest.at("frames").at(2);
  EXPECT_EQ(msb.at("pattern"), "binary_col");
  EXPECT_EQ(msb.at("bit"), 0);
  const cv::Mat image = cv::imread((out / msb.at("file").get<std::string>()).string(), cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(image.size(), cv::Size(64, 40));
  EXPECT_EQ(image.at<unsigned char>(7, 31), 0);  // column 31 = 011111: MSB dark
  EXPECT_EQ(image.at<unsigned char>(7, 32), 255);

  const auto plain = run_cli("transport " + out.string() + " -o " + (dir.path() / "T.h5").string());
  EXPECT_EQ(plain.exit_code, 3) << plain.output;  // an input error naming the families it knows
  EXPECT_NE(plain.output.find("unknown pattern family 'binary' (graycode, phase)"), std::string::npos) << plain.output;
}

TEST(ToyPatternFamily, SimulatedCaptureDecodesToTheProjectorPixelSeen) {
  testing::TempDir dir("toy_family_scan");
  const fs::path scene = dir.path() / "scene";
  const auto simulated = run_toy(
      "-q simulate --scene plane-lambert --camera 80x64 --projector 64x40 --family binary -o " + scene.string());
  ASSERT_EQ(simulated.exit_code, 0) << simulated.output;
  EXPECT_EQ(read_json(scene / "capture" / "manifest.json").at("family"), "binary");
  const auto decoded = run_toy("-q transport " + (scene / "capture").string() + " -o " + (scene / "T.h5").string());
  ASSERT_EQ(decoded.exit_code, 0) << decoded.output;
  const auto dual = run_toy("-q dual " + (scene / "T.h5").string() + " -o " + (dir.path() / "dual.tiff").string());
  EXPECT_EQ(dual.exit_code, 0) << dual.output;

  // Whole-pixel codes: the projector pixel whose area holds the true point, |error| <= 0.5 px on each axis, but where
  // camera noise flips a bit of a pixel on a code boundary.
  const transport::CompressedTransport t = transport::read_transport(scene / "T.h5");
  const cv::Mat truth = cv::imread((scene / "truth" / "correspondences.tiff").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(truth.size(), t.setup.camera_size);
  std::size_t decoded_pixels = 0, within = 0;
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * truth.cols + x;
      const cv::Vec3f seen = truth.at<cv::Vec3f>(y, x);
      if ((t.flags[c] & transport::kFlagValid) == 0 || std::isnan(seen[0])) continue;
      ++decoded_pixels;
      // Pixel centres at integers: the pixel holding seen is round(seen).
      const double dx = t.correspondence[2 * c] - seen[0], dy = t.correspondence[2 * c + 1] - seen[1];
      within += std::abs(dx) <= 0.5 + 1e-4 && std::abs(dy) <= 0.5 + 1e-4 ? 1 : 0;
    }
  }
  EXPECT_GT(decoded_pixels, truth.total() / 2);
  EXPECT_GT(static_cast<double>(within), 0.95 * static_cast<double>(decoded_pixels))
      << within << " of " << decoded_pixels << " decoded pixels within half a projector pixel";
}

}  // namespace
}  // namespace rfrecon
