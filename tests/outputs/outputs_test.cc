// The reconstruction directory: float maps round-trip bit for bit, 3-channel TIFFs hold x first for any TIFF reader,
// the PLY holds the valid pixels and the white frame's colours, previews follow their documented colour rules and
// carry a legend, and a refused or failed write leaves nothing behind.
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/core/errors.h"
#include "host/outputs/legend.h"
#include "host/outputs/reconstruction_files.h"
#include "tests/common/ply_reader.h"
#include "tests/common/temp_dir.h"
#include "tests/common/tiff_reader.h"

namespace rfrecon::outputs {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class OutputsTest : public ::testing::Test {
 protected:
  std::set<std::string> entries(const fs::path& dir) const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
  }

  rfrecon::testing::TempDir temp_{"outputs_test"};
  const fs::path dir_ = temp_.path();
};

// A 40x30 tilted plane z = 400 + 2 x + y mm seen by a pinhole camera (f = 100 px, centre (20, 15)); the first four
// columns have no reconstruction. Normal (0.6, 0, -0.8), confidence x / 40.
Reconstruction plane() {
  Reconstruction r;
  r.depth_mm.create(30, 40, CV_32F);
  r.points_mm.create(30, 40, CV_32FC3);
  r.normals.create(30, 40, CV_32FC3);
  r.confidence.create(30, 40, CV_32F);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      const float z = x < 4 ? NAN : 400.0f + 2.0f * x + y;
      r.depth_mm.at<float>(y, x) = z;
      r.points_mm.at<cv::Vec3f>(y, x) = {(x - 20.0f) * z / 100.0f, (y - 15.0f) * z / 100.0f, z};
      r.normals.at<cv::Vec3f>(y, x) = x < 4 ? cv::Vec3f(NAN, NAN, NAN) : cv::Vec3f(0.6f, 0.0f, -0.8f);
      r.confidence.at<float>(y, x) = x < 4 ? 0.0f : x / 40.0f;
    }
  }
  return r;
}

// Equal element by element, NaN equal to NaN.
void expect_same(const cv::Mat& a, const cv::Mat& b, const char* what) {
  ASSERT_EQ(a.type(), b.type()) << what;
  ASSERT_EQ(a.size(), b.size()) << what;
  const auto* pa = a.ptr<float>();
  const auto* pb = b.ptr<float>();
  for (std::size_t i = 0; i < a.total() * a.channels(); ++i) {
    if (std::isnan(pa[i])) {
      EXPECT_TRUE(std::isnan(pb[i])) << what << " element " << i;
    } else {
      EXPECT_EQ(pa[i], pb[i]) << what << " element " << i;
    }
  }
}

TEST_F(OutputsTest, MapsRoundTripBitForBitAndEveryFileIsThere) {
  const Reconstruction written = plane();
  const nlohmann::json summary{{"stage", "test"}, {"pixels", 1200}};
  write_reconstruction(written, summary, dir_ / "out", false);
  EXPECT_EQ(entries(dir_ / "out"),
            (std::set<std::string>{"depth.tiff", "points.tiff", "normals.tiff", "confidence.tiff", "points.ply",
                                   "depth.png", "normals.png", "confidence.png", "summary.json"}));
  EXPECT_EQ(entries(dir_), std::set<std::string>{"out"});  // no staging leftovers

  const Reconstruction read = read_reconstruction(dir_ / "out");
  expect_same(read.depth_mm, written.depth_mm, "depth");
  expect_same(read.points_mm, written.points_mm, "points");
  expect_same(read.normals, written.normals, "normals");
  expect_same(read.confidence, written.confidence, "confidence");
  EXPECT_TRUE(read.white.empty());

  std::ifstream in(dir_ / "out" / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(in), summary);
}

TEST_F(OutputsTest, PointCloudHoldsTheValidPixelsWithConfidenceAsQuality) {
  const Reconstruction r = plane();
  write_reconstruction(r, {}, dir_ / "out", false);
  const auto ply = testing::read_ply_vertices(dir_ / "out" / "points.ply");
  ASSERT_THAT(ply.properties, ::testing::ElementsAre("x", "y", "z", "nx", "ny", "nz", "u", "v", "quality"));
  ASSERT_EQ(ply.count, 36u * 30u);  // columns 4..39 of 30 rows
  // First vertex: pixel (4, 0); last: pixel (39, 29). Floats are stored bit for bit.
  EXPECT_EQ(ply.at(0, 0), r.points_mm.at<cv::Vec3f>(0, 4)[0]);
  EXPECT_EQ(ply.at(0, 2), 408.0f);
  EXPECT_EQ(ply.at(0, 6), 4.0f);  // u, v of pixel (4, 0)
  EXPECT_EQ(ply.at(0, 7), 0.0f);
  EXPECT_EQ(ply.at(0, 8), 0.1f);
  EXPECT_EQ(ply.at(ply.count - 1, 2), 400.0f + 78.0f + 29.0f);
  EXPECT_EQ(ply.at(ply.count - 1, 3), 0.6f);
  EXPECT_EQ(ply.at(ply.count - 1, 6), 39.0f);
  EXPECT_EQ(ply.at(ply.count - 1, 7), 29.0f);
  EXPECT_EQ(ply.at(ply.count - 1, 8), 39.0f / 40.0f);
}

// As libtiff reads them (any reader but OpenCV): points.tiff and normals.tiff hold x, y, z in samples 0, 1, 2.
TEST_F(OutputsTest, ThreeChannelTiffsHoldXFirstForAnyTiffReader) {
  const Reconstruction r = plane();
  write_reconstruction(r, {}, dir_ / "out", false);
  const auto points = testing::read_float_tiff(dir_ / "out" / "points.tiff");
  const auto normals = testing::read_float_tiff(dir_ / "out" / "normals.tiff");
  for (const auto* image : {&points, &normals}) {
    ASSERT_EQ(image->samples, 3);
    ASSERT_EQ(image->width, 40u);
    ASSERT_EQ(image->height, 30u);
  }
  for (int sample = 0; sample < 3; ++sample) {
    EXPECT_EQ(points.at(30, 7, sample), r.points_mm.at<cv::Vec3f>(7, 30)[sample]) << sample;
    EXPECT_TRUE(std::isnan(points.at(2, 7, sample))) << "no point: NaN";
  }
  // Normal (0.6, 0, -0.8).
  EXPECT_EQ(normals.at(30, 7, 0), 0.6f);
  EXPECT_EQ(normals.at(30, 7, 1), 0.0f);
  EXPECT_EQ(normals.at(30, 7, 2), -0.8f);
}

// The white frame colours the PLY: grey, brighter where the white frame is brighter, linear 0.5 at sRGB's 0.7354
// (IEC 61966-2-1) = 187.5 of 255; without a white frame the PLY has no colour properties.
TEST_F(OutputsTest, PlyColoursFollowTheWhiteFrame) {
  Reconstruction r = plane();
  r.white.create(30, 40, CV_32F);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) r.white.at<float>(y, x) = x / 40.0f;
  }
  write_reconstruction(r, {}, dir_ / "out", false);
  const auto ply = testing::read_ply_vertices(dir_ / "out" / "points.ply");
  ASSERT_THAT(ply.properties,
              ::testing::ElementsAre("x", "y", "z", "nx", "ny", "nz", "u", "v", "quality", "red", "green", "blue"));
  EXPECT_THAT(ply.types, ::testing::ElementsAre("float", "float", "float", "float", "float", "float", "float", "float",
                                                "float", "uchar", "uchar", "uchar"));
  float previous = -1.0f;
  for (std::size_t v = 0; v < 36; ++v) {  // row 0: u = 4 .. 39, white 0.1 .. 0.975
    EXPECT_EQ(ply.at(v, 9), ply.at(v, 10));
    EXPECT_EQ(ply.at(v, 9), ply.at(v, 11));
    EXPECT_GT(ply.at(v, 9), previous) << "u " << ply.at(v, 6);
    previous = ply.at(v, 9);
    if (ply.at(v, 6) == 20.0f) {
      EXPECT_NEAR(ply.at(v, 9), 187.5, 1.0);
    }
  }
  write_reconstruction(plane(), {}, dir_ / "plain", false);
  EXPECT_EQ(testing::read_ply_vertices(dir_ / "plain" / "points.ply").properties.size(), 9u);
}

TEST_F(OutputsTest, PreviewsFollowTheirColourRules) {
  const Reconstruction r = plane();
  write_reconstruction(r, {}, dir_ / "out", false);
  const cv::Mat depth = cv::imread((dir_ / "out" / "depth.png").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat normals = cv::imread((dir_ / "out" / "normals.png").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat confidence = cv::imread((dir_ / "out" / "confidence.png").string(), cv::IMREAD_UNCHANGED);
  for (const cv::Mat* image : {&depth, &normals, &confidence}) {
    ASSERT_EQ(image->type(), CV_8UC3);
    // The camera grid at the top left, the legend to its right.
    ASSERT_EQ(image->size(), cv::Size(40 + kLegendWidth, kLegendMinHeight));
    EXPECT_EQ(image->at<cv::Vec3b>(10, 2), cv::Vec3b(0, 0, 0));  // no reconstruction: black
  }
  // The nearest depth (408 mm, below the 1st percentile) and farthest (507 mm, above the 99th) saturate to the two
  // ends of the turbo map.
  cv::Mat ends(1, 2, CV_8U), turbo;
  ends.at<uchar>(0, 0) = 0;
  ends.at<uchar>(0, 1) = 255;
  cv::applyColorMap(ends, turbo, cv::COLORMAP_TURBO);
  EXPECT_EQ(depth.at<cv::Vec3b>(0, 4), turbo.at<cv::Vec3b>(0, 0));
  EXPECT_EQ(depth.at<cv::Vec3b>(29, 39), turbo.at<cv::Vec3b>(0, 1));
  // The legend's colour bar shows both ends of the scale.
  const cv::Mat legend = depth.colRange(40, depth.cols);
  for (const cv::Vec3b& end : {turbo.at<cv::Vec3b>(0, 0), turbo.at<cv::Vec3b>(0, 1)}) {
    cv::Mat matches;
    cv::inRange(legend, cv::Scalar(end[0], end[1], end[2]), cv::Scalar(end[0], end[1], end[2]), matches);
    EXPECT_GT(cv::countNonZero(matches), 0);
  }
  // Normal (0.6, 0, -0.8): RGB = 255 (n + 1) / 2 = (204, 127.5, 25.5); +-1 for rounding the halves. Stored BGR.
  const cv::Vec3b n = normals.at<cv::Vec3b>(5, 20);
  EXPECT_NEAR(n[2], 204, 1);
  EXPECT_NEAR(n[1], 127.5, 1);
  EXPECT_NEAR(n[0], 25.5, 1);
  // Confidence 20 / 40 = 0.5: grey 127.5 +- 1 for rounding.
  EXPECT_NEAR(confidence.at<cv::Vec3b>(5, 20)[0], 127.5, 1);
  EXPECT_EQ(confidence.at<cv::Vec3b>(5, 20)[0], confidence.at<cv::Vec3b>(5, 20)[2]);
}

TEST_F(OutputsTest, ExistingNonEmptyDirectoryIsRefusedUntouchedUnlessForced) {
  fs::create_directories(dir_ / "out");
  std::ofstream(dir_ / "out" / "mine.txt") << "keep me";
  try {
    write_reconstruction(plane(), {}, dir_ / "out", false);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr((dir_ / "out").string()));
    EXPECT_THAT(error.what(), HasSubstr("--force"));
  }
  EXPECT_EQ(entries(dir_), std::set<std::string>{"out"});
  EXPECT_EQ(entries(dir_ / "out"), std::set<std::string>{"mine.txt"});

  write_reconstruction(plane(), {}, dir_ / "out", true);
  EXPECT_EQ(entries(dir_ / "out").count("mine.txt"), 0u);
  EXPECT_EQ(entries(dir_ / "out").count("depth.tiff"), 1u);
  EXPECT_EQ(entries(dir_), std::set<std::string>{"out"});
}

TEST_F(OutputsTest, InconsistentMapsAreRejectedBeforeAnythingIsWritten) {
  Reconstruction r = plane();
  r.confidence = cv::Mat(10, 10, CV_32F, 0.0f);
  EXPECT_THROW(write_reconstruction(r, {}, dir_ / "out", false), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(OutputsTest, ReadingNamesTheMissingOrMisSizedFile) {
  write_reconstruction(plane(), {}, dir_ / "out", false);
  fs::remove(dir_ / "out" / "normals.tiff");
  try {
    read_reconstruction(dir_ / "out");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("normals.tiff"));
  }
  write_reconstruction(plane(), {}, dir_ / "out", true);
  const std::vector<int> uncompressed{cv::IMWRITE_TIFF_COMPRESSION, 1};
  cv::imwrite((dir_ / "out" / "confidence.tiff").string(), cv::Mat(20, 40, CV_32F, 0.5f), uncompressed);
  try {
    read_reconstruction(dir_ / "out");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("confidence.tiff: 40x20, expected 40x30"));
  }
  EXPECT_THROW(read_reconstruction(dir_ / "nothing-here"), InputError);
}

}  // namespace
}  // namespace rfrecon::outputs
