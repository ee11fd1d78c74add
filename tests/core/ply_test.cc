// The PLY writer against the format: header lines, vertex count, property order and the exact float bytes back.
#include "host/core/ply.h"

#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/common/ply_reader.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;

class PlyTest : public ::testing::Test {
 protected:
  rfrecon::testing::TempDir temp_{"ply_test"};
  const fs::path dir_ = temp_.path();
};

// A 3x2 grid with distinct values everywhere and no point at pixel (1, 0).
struct Maps {
  cv::Mat points = cv::Mat(2, 3, CV_32FC3), normals = cv::Mat(2, 3, CV_32FC3), quality = cv::Mat(2, 3, CV_32F);
  Maps() {
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 3; ++x) {
        const float i = static_cast<float>(y * 3 + x);
        points.at<cv::Vec3f>(y, x) = {i + 0.5f, -i, 500.0f + i / 3.0f};
        normals.at<cv::Vec3f>(y, x) = {0.6f, i / 10.0f, -0.8f};
        quality.at<float>(y, x) = i / 7.0f;
      }
    }
    points.at<cv::Vec3f>(0, 1)[2] = NAN;
  }
};

TEST_F(PlyTest, HeaderAndBodyReadBackExactly) {
  const Maps maps;
  write_point_cloud_ply(dir_ / "cloud.ply", "test cloud, mm", maps.points, maps.normals, {{"quality", maps.quality}});
  const auto ply = testing::read_ply_vertices(dir_ / "cloud.ply");
  EXPECT_EQ(ply.header_lines.front(), "format binary_little_endian 1.0");
  EXPECT_EQ(ply.header_lines[1], "comment test cloud, mm");
  EXPECT_THAT(ply.properties, ElementsAre("x", "y", "z", "nx", "ny", "nz", "u", "v", "quality"));
  ASSERT_EQ(ply.count, 5u);  // six pixels, one without a point
  EXPECT_EQ(ply.trailing_bytes, 0u);
  // Row-major pixel order skipping (1, 0); float values are stored bit for bit, so the comparison is exact.
  const int pixels[5][2] = {{0, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}};
  for (std::size_t v = 0; v < 5; ++v) {
    const int x = pixels[v][0], y = pixels[v][1];
    const cv::Vec3f p = maps.points.at<cv::Vec3f>(y, x), n = maps.normals.at<cv::Vec3f>(y, x);
    const float expected[9] = {
        p[0], p[1], p[2], n[0], n[1], n[2], static_cast<float>(x), static_cast<float>(y), maps.quality.at<float>(y, x)};
    for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(ply.at(v, k), expected[k]) << "vertex " << v << " property " << k;
  }
}

// A point without a normal (or a NaN scalar) keeps its place with 0 0 0 (or 0): no value in the file is NaN.
TEST_F(PlyTest, NoNanReachesTheFile) {
  Maps maps;
  maps.normals.at<cv::Vec3f>(1, 1) = {NAN, NAN, NAN};
  maps.quality.at<float>(1, 2) = INFINITY;
  write_point_cloud_ply(dir_ / "cloud.ply", "", maps.points, maps.normals, {{"quality", maps.quality}});
  const auto ply = testing::read_ply_vertices(dir_ / "cloud.ply");
  ASSERT_EQ(ply.count, 5u);
  for (std::size_t v = 0; v < ply.count; ++v) {
    for (std::size_t k = 0; k < ply.properties.size(); ++k) EXPECT_TRUE(std::isfinite(ply.at(v, k))) << v << " " << k;
  }
  EXPECT_EQ(ply.at(3, 3), 0.0f);  // pixel (1, 1): its point, no normal
  EXPECT_EQ(ply.at(3, 0), maps.points.at<cv::Vec3f>(1, 1)[0]);
  EXPECT_EQ(ply.at(4, 8), 0.0f);  // pixel (2, 1): quality was infinite
}

TEST_F(PlyTest, EmptyCloudIsAValidFile) {
  const cv::Mat none(4, 4, CV_32FC3, cv::Scalar::all(NAN));
  write_point_cloud_ply(dir_ / "empty.ply", "", none, none);
  const auto ply = testing::read_ply_vertices(dir_ / "empty.ply");
  EXPECT_EQ(ply.count, 0u);
  EXPECT_EQ(ply.properties.size(), 8u);
  EXPECT_EQ(ply.trailing_bytes, 0u);
}

TEST_F(PlyTest, BadArgumentsAreRejectedAndNothingIsWritten) {
  const Maps maps;
  EXPECT_THROW(write_point_cloud_ply(dir_ / "a.ply", "", maps.points, cv::Mat(3, 3, CV_32FC3)), std::invalid_argument);
  EXPECT_THROW(write_point_cloud_ply(dir_ / "a.ply", "", maps.points, maps.normals, {{"x", maps.quality}}),
               std::invalid_argument);
  EXPECT_THROW(write_point_cloud_ply(dir_ / "a.ply", "", maps.points, maps.normals, {{"bad name", maps.quality}}),
               std::invalid_argument);
  EXPECT_THROW(write_point_cloud_ply(dir_ / "a.ply", "", maps.points, maps.normals, {{"q", cv::Mat(2, 3, CV_64F)}}),
               std::invalid_argument);
  EXPECT_THROW(write_point_cloud_ply(dir_ / "a.ply", "two\nlines", maps.points, maps.normals), std::invalid_argument);
  EXPECT_THROW(write_point_cloud_ply(dir_ / "a.ply", "", maps.points, maps.normals, {{"red", maps.quality}}),
               std::invalid_argument);
  EXPECT_THROW(
      write_point_cloud_ply(dir_ / "a.ply", "", maps.points, maps.normals, {}, cv::Mat(maps.points.size(), CV_32FC3)),
      std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace rfrecon
