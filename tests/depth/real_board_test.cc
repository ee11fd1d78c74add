// The whole pipeline on real Gray-code captures (../shared/data/procam-graycode: four poses of a printed 9x7-corner
// board with 75 mm squares, 3.1 to 3.6 m away): the rig calibrated from three poses, the fourth reconstructed by
// triangulation comes out flat. Skipped when the captures are absent: they are not part of the product.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "calib/board_detection.h"
#include "host/cli/exit_codes.h"
#include "host/outputs/reconstruction_files.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::depth {
namespace {

namespace fs = std::filesystem;

const fs::path kCaptures = fs::path(RFRECON_SOURCE_DIR) / ".." / "shared" / "data" / "procam-graycode";
const std::string kLayout = " --layout opencv-graycode --projector 1024x768";

// RMS distance (mm) of the points inside the board's inner corners' convex hull from their least-squares plane, and
// how many points there are.
std::pair<double, std::size_t> plane_rms_mm(const cv::Mat& points_mm, const std::vector<cv::Point2f>& corners) {
  std::vector<cv::Point> hull;
  std::vector<cv::Point> corner_pixels(corners.begin(), corners.end());
  cv::convexHull(corner_pixels, hull);
  cv::Mat inside(points_mm.size(), CV_8U, cv::Scalar(0));
  cv::fillConvexPoly(inside, hull, cv::Scalar(1));
  std::vector<cv::Vec3d> points;
  for (int y = 0; y < points_mm.rows; ++y) {
    for (int x = 0; x < points_mm.cols; ++x) {
      const cv::Vec3f p = points_mm.at<cv::Vec3f>(y, x);
      if (inside.at<unsigned char>(y, x) != 0 && std::isfinite(p[2])) points.emplace_back(p[0], p[1], p[2]);
    }
  }
  const cv::Mat data(static_cast<int>(points.size()), 3, CV_64F, points.data());
  const cv::PCA pca(data, cv::Mat(), cv::PCA::DATA_AS_ROW);
  const cv::Mat normal = pca.eigenvectors.row(2);
  double sum = 0.0;
  for (int i = 0; i < data.rows; ++i) {
    const double distance = (data.row(i) - pca.mean).dot(normal);
    sum += distance * distance;
  }
  return {std::sqrt(sum / data.rows), points.size()};
}

// Measured with the committed code (docs/accuracy.md): pose 0 flat to 0.05 % of the board's diagonal (600 x 450 mm
// between the outer inner corners, 750 mm), where the fixed-threshold decoding without edge rejection gave 0.10 %.
// Bound: 0.06 %, the target.
TEST(RealBoard, ATriangulatedPoseIsFlatWithARigCalibratedFromTheOthers) {
  if (!fs::exists(kCaptures / "capture_3")) GTEST_SKIP() << kCaptures << " is absent (not part of the product)";
  rfrecon::testing::TempDir temp("real_board");
  const fs::path pose = kCaptures / "capture_0";
  std::string others;
  for (int i = 1; i < 4; ++i) others += " " + (kCaptures / ("capture_" + std::to_string(i))).string();
  const fs::path rig = temp.path() / "rig.yaml", t = temp.path() / "T.h5", out = temp.path() / "out";
  for (const std::string& command :
       {"calibrate" + others + kLayout + " --board 9x7 --square 75 -o " + rig.string(),
        "transport " + pose.string() + kLayout + " -o " + t.string(),
        "reconstruct " + t.string() + " --calib " + rig.string() + " --method triangulate -o " + out.string()}) {
    const auto result = rfrecon::testing::run_cli(command);
    ASSERT_EQ(result.exit_code, cli::kExitOk) << command << "\n" << result.output;
  }
  const auto corners =
      calib::find_board_corners(cv::imread((pose / "graycode_40.png").string(), cv::IMREAD_GRAYSCALE), {9, 7, 75.0});
  ASSERT_EQ(corners.size(), 63u);
  const auto [rms_mm, count] = plane_rms_mm(outputs::read_reconstruction(out).points_mm, corners);
  const double diagonal_mm = 75.0 * std::hypot(8.0, 6.0);
  std::printf("pose 0: %zu points on the board, plane RMS %.4f mm = %.4f %% of its diagonal\n", count, rms_mm,
              100.0 * rms_mm / diagonal_mm);
  EXPECT_GT(count, 100000u) << "the white squares' pixels, most of them";
  EXPECT_LT(100.0 * rms_mm / diagonal_mm, 0.06);
}

}  // namespace
}  // namespace rfrecon::depth
