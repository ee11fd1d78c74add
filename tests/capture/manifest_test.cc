// Manifests round-trip, reject inconsistent content with messages naming the file, and frames linearize correctly.
#include "host/capture/manifest.h"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <sys/stat.h>

#include "host/capture/graycode_patterns.h"
#include "host/core/errors.h"
#include "tests/common/temp_dir.h"
#include "tests/core/refusal_in_child.h"

namespace rfrecon::capture {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class ManifestTest : public ::testing::Test {
 protected:
  // A complete capture of a 32x16 projector seen by a 20x10 camera, frames written as 8-bit PNG.
  CaptureManifest write_capture(int dot_spacing) {
    CaptureManifest manifest;
    manifest.projector_size = {32, 16};
    manifest.camera_size = {20, 10};
    manifest.dot_spacing = dot_spacing;
    manifest.black_level = 5;
    const auto sequence = make_protocol({manifest.projector_size, dot_spacing});
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const std::string name = "frame_" + std::to_string(i) + ".png";
      cv::imwrite((dir_ / name).string(), cv::Mat(manifest.camera_size, CV_8UC1, cv::Scalar(100)));
      manifest.frames.push_back({sequence[i], name});
    }
    write_manifest(manifest, dir_);
    return manifest;
  }

  void expect_read_error(const std::string& fragment) {
    try {
      (void)read_manifest(dir_);
      FAIL() << "expected InputError containing '" << fragment << "'";
    } catch (const InputError& error) {
      EXPECT_THAT(error.what(), HasSubstr(fragment));
      EXPECT_THAT(error.what(), HasSubstr(dir_.string()));
    }
  }

  rfrecon::testing::TempDir temp_{"manifest"};
  const fs::path dir_ = temp_.path();
};

TEST_F(ManifestTest, RoundTrips) {
  const auto written = write_capture(4);
  const auto read = read_manifest(dir_);
  EXPECT_EQ(read.projector_size, written.projector_size);
  EXPECT_EQ(read.camera_size, written.camera_size);
  EXPECT_EQ(read.dot_spacing, 4);
  EXPECT_EQ(read.black_level, 5);
  ASSERT_EQ(read.frames.size(), written.frames.size());
  for (std::size_t i = 0; i < read.frames.size(); ++i) {
    EXPECT_EQ(read.frames[i].file, written.frames[i].file);
    EXPECT_EQ(read.frames[i].pattern.kind, written.frames[i].pattern.kind);
    EXPECT_EQ(read.frames[i].pattern.bit, written.frames[i].pattern.bit);
    EXPECT_EQ(read.frames[i].pattern.inverse, written.frames[i].pattern.inverse);
    EXPECT_EQ(read.frames[i].pattern.dot_offset_x, written.frames[i].pattern.dot_offset_x);
  }
}

TEST_F(ManifestTest, MissingFrameIsNamed) {
  const auto manifest = write_capture(0);
  fs::remove(dir_ / manifest.frames[3].file);
  expect_read_error("missing frame: " + (dir_ / manifest.frames[3].file).string());
}

TEST_F(ManifestTest, ProjectorSizeInconsistentWithGrayCode) {
  auto manifest = write_capture(0);
  manifest.projector_size = {64, 16};  // 6 column bits expected, 5 present
  write_manifest(manifest, dir_);
  expect_read_error("incomplete Gray code");
  manifest.projector_size = {16, 16};  // bit 4 does not exist for 16 columns
  write_manifest(manifest, dir_);
  expect_read_error("does not exist for a projector width of 16");
}

TEST_F(ManifestTest, MalformedJsonAndFields) {
  write_capture(0);
  std::ofstream(dir_ / kManifestFileName) << "{ not json";
  expect_read_error("not valid JSON");
  std::ofstream(dir_ / kManifestFileName) << R"({"version": 1, "projector_size": [32, 16], "frames": 3})";
  expect_read_error("'frames' must be an array");
  std::ofstream(dir_ / kManifestFileName) << R"({"version": 1, "frames": []})";
  expect_read_error("missing field 'projector_size'");
}

TEST_F(ManifestTest, FifoManifestIsRefusedWithoutBlocking) {
  ASSERT_EQ(::mkfifo((dir_ / kManifestFileName).c_str(), 0600), 0);
  const std::string message = rfrecon::testing::refusal_in_child([&] { (void)read_manifest(dir_); });
  EXPECT_THAT(message, HasSubstr((dir_ / kManifestFileName).string() + ": is a FIFO"));
}

TEST_F(ManifestTest, DeepOrLongInputIsRefusedQuotedCut) {
  std::ofstream(dir_ / kManifestFileName) << std::string(100000, '[') << std::string(100000, ']');
  expect_read_error("deeper than 64 levels");
  const std::string name(10000, 'n');
  std::ofstream(dir_ / kManifestFileName)
      << R"({"version": 1, "projector_size": [32, 16], "frames": [{"file": ")" << name << R"(", "pattern": "white"}]})";
  try {
    (void)read_manifest(dir_);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("10000 bytes"));
    EXPECT_LT(std::string(error.what()).size(), (dir_ / kManifestFileName).string().size() + 250) << error.what();
  }
}

TEST_F(ManifestTest, LinearizeUndoesBlackLevelAndGamma) {
  CaptureManifest manifest;
  manifest.bit_depth = 12;
  manifest.black_level = 95;
  manifest.camera_size = {2, 1};
  manifest.camera_response = "gamma:2.2";
  // reading = black + (full - black) * linear^(1/2.2) for linear = 0.25 and 1.
  const double full = 4095;
  cv::Mat raw(1, 2, CV_16UC1);
  raw.at<uint16_t>(0, 0) = static_cast<uint16_t>(std::lround(95 + (full - 95) * std::pow(0.25, 1 / 2.2)));
  raw.at<uint16_t>(0, 1) = 4095;
  const cv::Mat linear = linearize_frame(raw, manifest, "x.png");
  // One digital number of rounding at 12 bits moves linear by at most ~2.2 / 4000 * 0.25^(1-1/2.2) < 3e-4.
  EXPECT_NEAR(linear.at<float>(0, 0), 0.25, 3e-4);
  EXPECT_NEAR(linear.at<float>(0, 1), 1.0, 1e-6);
}

// The map the kernels apply to raw samples: the black level to 0 exactly, every sample within one rounding of the
// exact (sample - black) / (full - black); only a linear response needs nothing more.
TEST_F(ManifestTest, SampleMapPutsBlackAtZeroAndFullScaleAtOne) {
  CaptureManifest manifest;
  manifest.bit_depth = 12;
  manifest.black_level = 95;
  const SampleMap map = sample_map(manifest);
  cv::Mat raw(1, 4096, CV_16UC1);
  for (int i = 0; i < raw.cols; ++i) raw.at<uint16_t>(0, i) = static_cast<uint16_t>(i);
  const cv::Mat linear = linearize_samples(raw, map);
  EXPECT_EQ(linear.at<float>(0, 95), 0.0f);
  EXPECT_NEAR(linear.at<float>(0, 4095), 1.0, 1e-6);
  for (int i = 0; i < raw.cols; ++i) {
    // The scale's and the product's roundings, values up to about 1: well under 1e-6.
    ASSERT_NEAR(linear.at<float>(0, i), (i - 95.0) / 4000.0, 1e-6) << i;
  }
  EXPECT_TRUE(linear_response(manifest));
  manifest.camera_response = "gamma:2.2";
  EXPECT_FALSE(linear_response(manifest));
}

TEST_F(ManifestTest, LinearizeRejectsWrongDepthAndSize) {
  CaptureManifest manifest;
  manifest.bit_depth = 16;
  manifest.camera_size = {4, 4};
  EXPECT_THROW((void)linearize_frame(cv::Mat(4, 4, CV_8UC1), manifest, "a.png"), InputError);
  EXPECT_THROW((void)linearize_frame(cv::Mat(3, 4, CV_16UC1), manifest, "b.png"), InputError);
  manifest.camera_response = "sRGB";
  EXPECT_THROW((void)linearize_frame(cv::Mat(4, 4, CV_16UC1), manifest, "c.png"), InputError);
}

TEST_F(ManifestTest, OpenCvLayoutNeedsTheRightCount) {
  const cv::Size projector(32, 16);
  const auto sequence = opencv_graycode_protocol(projector);
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    cv::imwrite((dir_ / ("img" + std::to_string(100 + i) + ".png")).string(), cv::Mat(10, 20, CV_8UC1, 7));
  }
  const auto manifest = manifest_from_opencv_layout(dir_, projector);
  EXPECT_EQ(manifest.frames.front().file, "img100.png");
  EXPECT_EQ(manifest.frames.front().pattern.kind, pattern_kind::kGrayColumn);
  EXPECT_EQ(manifest.frames.back().pattern.kind, pattern_kind::kBlack);
  EXPECT_EQ(manifest.camera_size, cv::Size(20, 10));
  try {
    (void)manifest_from_opencv_layout(dir_, {64, 16});
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("needs 22 images"));
  }
}

}  // namespace
}  // namespace rfrecon::capture
