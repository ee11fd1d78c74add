// Calibration building blocks on exactly known synthetic inputs: corner detection on a projected board, dual-image
// hole filling, corner-order alignment, a board larger than the one given, and the degenerate-pose and undetermined-
// intrinsics checks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "calib/board_detection.h"
#include "calib/board_overhang.h"
#include "calib/camera_calibration.h"
#include "calib/pose_observation.h"
#include "host/core/errors.h"

namespace rfrecon::calib {
namespace {

const BoardSpec kBoard{9, 6, 20.0};
const cv::Matx33d kCamera(800, 0, 320, 0, 800, 240, 0, 0, 1);

// A 640x480 image of the board seen by kCamera at pose (rvec, tvec), drawn exactly by warping the board's texture
// with its plane-to-image homography, area-averaged (supersampled 4x).
cv::Mat render_board(const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
  constexpr int kScale = 4;
  constexpr double kPxPerMm = 4.0;
  const int squares_x = kBoard.cols + 1;
  const int squares_y = kBoard.rows + 1;
  // Texture: board plane coordinates (mm) -> texture pixels, origin at the first inner corner; a white margin.
  const double margin = 20.0;
  const cv::Size texture_size(static_cast<int>((squares_x * 20.0 + 2 * margin) * kPxPerMm),
                              static_cast<int>((squares_y * 20.0 + 2 * margin) * kPxPerMm));
  cv::Mat texture(texture_size, CV_8U, cv::Scalar(230));
  for (int sy = 0; sy < squares_y; ++sy) {
    for (int sx = 0; sx < squares_x; ++sx) {
      if ((sx + sy) % 2 != 0) continue;
      const cv::Point2d top_left((margin + sx * 20.0) * kPxPerMm, (margin + sy * 20.0) * kPxPerMm);
      cv::rectangle(texture, cv::Rect(cv::Point(top_left), cv::Size(80, 80)), cv::Scalar(15), cv::FILLED);
    }
  }
  cv::Matx33d rotation;
  cv::Rodrigues(rvec, rotation);
  // Board point (X, Y, 0) in mm, with the first inner corner at (0, 0) = texture ((margin + 20) * kPxPerMm).
  const cv::Matx33d board_to_image =
      kCamera * cv::Matx33d(rotation(0, 0), rotation(0, 1), tvec[0], rotation(1, 0), rotation(1, 1), tvec[1],
                            rotation(2, 0), rotation(2, 1), tvec[2]);
  // Texel t covers [t - 0.5, t + 0.5]: square edges drawn from texel index i lie at i - 0.5.
  const double offset = (margin + 20.0) * kPxPerMm - 0.5;
  const cv::Matx33d texture_to_board(1 / kPxPerMm, 0, -offset / kPxPerMm, 0, 1 / kPxPerMm, -offset / kPxPerMm, 0, 0, 1);
  const cv::Matx33d upscale(kScale, 0, (kScale - 1) / 2.0, 0, kScale, (kScale - 1) / 2.0, 0, 0, 1);
  cv::Mat big;
  cv::warpPerspective(texture, big, cv::Mat(upscale * board_to_image * texture_to_board),
                      cv::Size(640 * kScale, 480 * kScale), cv::INTER_AREA, cv::BORDER_CONSTANT, cv::Scalar(128));
  cv::Mat image;
  cv::resize(big, image, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
  return image;
}

std::vector<cv::Point2f> true_corners(const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
  std::vector<cv::Point2f> projected;
  cv::projectPoints(board_object_points(kBoard), rvec, tvec, cv::Mat(kCamera), cv::noArray(), projected);
  return projected;
}

TEST(BoardDetectionTest, CornersWithinATenthOfAPixelOfTheProjection) {
  const cv::Vec3d rvec(0.3, -0.2, 0.05);
  const cv::Vec3d tvec(-80, -50, 600);
  const auto found = find_board_corners(render_board(rvec, tvec), kBoard);
  const auto expected = true_corners(rvec, tvec);
  ASSERT_EQ(found.size(), expected.size());
  // A board may be numbered from either end (a 180 degree turn looks the same); compare in the better order.
  double worst_forward = 0.0;
  double worst_reversed = 0.0;
  double sq_forward = 0.0;
  double sq_reversed = 0.0;
  for (std::size_t i = 0; i < found.size(); ++i) {
    const double forward = cv::norm(found[i] - expected[i]);
    const double reversed = cv::norm(found[found.size() - 1 - i] - expected[i]);
    worst_forward = std::max(worst_forward, forward);
    worst_reversed = std::max(worst_reversed, reversed);
    sq_forward += forward * forward;
    sq_reversed += reversed * reversed;
  }
  const double worst = std::min(worst_forward, worst_reversed);
  const double rms = std::sqrt(std::min(sq_forward, sq_reversed) / static_cast<double>(found.size()));
  // Area-sampled edges at 8 bits: OpenCV's sector detector is accurate to a few hundredths of a pixel; 0.05 px RMS
  // and 0.1 px worst is the accuracy calibration needs (it averages over 54 corners and several views).
  EXPECT_LT(rms, 0.05);
  EXPECT_LT(worst, 0.1);
}

TEST(BoardDetectionTest, NoBoardGivesNoCorners) {
  EXPECT_TRUE(find_board_corners(cv::Mat(480, 640, CV_8U, cv::Scalar(100)), kBoard).empty());
}

// The corners of the rendered 9x6 board (exact projections) without some of its outer lines, as a detector finds a
// smaller board inside the printed one: the squares beyond show each line left out, and the check names the view,
// the evidence and the board it is. The whole grid's border squares end at the white margin: no overhang.
TEST(BoardOverhangTest, EachLineOfCornersLeftOutIsCounted) {
  const cv::Vec3d rvec(0.3, -0.2, 0.05);
  const cv::Vec3d tvec(-80, -50, 600);
  const cv::Mat image = render_board(rvec, tvec);
  const auto all = true_corners(rvec, tvec);
  EXPECT_FALSE(board_overhang(image, kBoard, all).any());
  const auto sub_grid = [&](int first_col, int first_row, const BoardSpec& board) {
    std::vector<cv::Point2f> corners;
    for (int row = first_row; row < first_row + board.rows; ++row) {
      for (int col = first_col; col < first_col + board.cols; ++col) corners.push_back(all[row * kBoard.cols + col]);
    }
    return corners;
  };
  const BoardSpec inner{7, 5, 20.0};
  const auto overhang = board_overhang(image, inner, sub_grid(1, 0, inner));
  EXPECT_EQ(overhang.before_first_column, 1) << overhang.describe();
  EXPECT_EQ(overhang.after_last_column, 1) << overhang.describe();
  EXPECT_EQ(overhang.before_first_row, 0) << overhang.describe();
  EXPECT_EQ(overhang.after_last_row, 1) << overhang.describe();
  try {
    check_board_fits({{"view.png", overhang}}, inner, 1);
    ADD_FAILURE() << "no error";
  } catch (const ProcessingError& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("--board 7x5: the printed board continues beyond"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("view.png: 1 more column of corners before the first"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("is it 9x6?"));
  }
  // Corners two lines short on one side: both lines are counted.
  const BoardSpec narrower{7, 6, 20.0};
  EXPECT_EQ(board_overhang(image, narrower, sub_grid(0, 0, narrower)).after_last_column, 2);
}

// Intrinsics with a deviation over a tenth of the focal length, or an RMS over 2 px, are refused with the evidence.
TEST(IntrinsicsCheckTest, UndeterminedIntrinsicsAreRefusedWithTheEvidence) {
  const cv::Mat camera_matrix(cv::Matx33d(800, 0, 320, 0, 800, 240, 0, 0, 1));
  const cv::Mat good_std = (cv::Mat_<double>(1, 4) << 0.5, 0.5, 0.6, 0.6);
  EXPECT_NO_THROW(check_intrinsics_determined("camera", camera_matrix, good_std, 0.2, {640, 480}, kBoard, 10));
  const cv::Mat wide_std = (cv::Mat_<double>(1, 4) << 120.0, 0.5, 0.6, 0.6);
  try {
    check_intrinsics_determined("camera", camera_matrix, wide_std, 11.4, {640, 480}, kBoard, 10);
    ADD_FAILURE() << "no error";
  } catch (const ProcessingError& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("--board 9x6 --square 20"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("10 views"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("fx 800.00 +- 120.00 px (15 %"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("reprojection RMS 11.40 px"));
    EXPECT_THAT(error.what(), ::testing::Not(::testing::HasSubstr("fy")));
  }
  EXPECT_THROW(check_intrinsics_determined("camera", -camera_matrix, good_std, 0.2, {640, 480}, kBoard, 10),
               ProcessingError);
}

TEST(DualImageTest, HolesAreFilledWithoutMovingEdges) {
  // A vertical step edge at x = 20 with every third column unreached (moire-like gaps).
  cv::Mat dual(40, 40, CV_32F);
  cv::Mat reached(40, 40, CV_8U, cv::Scalar(255));
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) {
      dual.at<float>(y, x) = x < 20 ? 0.05f : 0.8f;
      if (x % 3 == 1) {
        reached.at<uint8_t>(y, x) = 0;
        dual.at<float>(y, x) = 0.0f;
      }
    }
  }
  // A wide unreached block (a dark square whose transport fell below the noise threshold) is not a gap.
  reached(cv::Rect(2, 25, 12, 12)).setTo(0);
  dual(cv::Rect(2, 25, 12, 12)).setTo(0.0f);
  const cv::Mat filled = fill_dual_image_holes(dual, reached);
  EXPECT_EQ(filled.at<float>(31, 8), 0.0f);
  // Far from the edge the holes take the level of their side (within 1%); reached pixels keep their values.
  EXPECT_NEAR(filled.at<float>(10, 4), 0.05f, 0.0005f);
  EXPECT_NEAR(filled.at<float>(10, 34), 0.8f, 0.008f);
  EXPECT_EQ(filled.at<float>(10, 18), 0.05f);
  // The edge stays where it was (x = 19.5): a gap pixel on the edge takes the mean of its two neighbours, which
  // moves the half-level crossing by at most half a pixel, and filling adds no ringing (values stay in range).
  const float half = (0.05f + 0.8f) / 2;
  double crossing = -1.0;
  for (int x = 0; x + 1 < 40; ++x) {
    const float a = filled.at<float>(10, x);
    const float b = filled.at<float>(10, x + 1);
    EXPECT_GE(a, 0.05f - 1e-6f);
    EXPECT_LE(a, 0.8f + 1e-6f);
    if (a < half && b >= half) crossing = x + (half - a) / (b - a);
  }
  EXPECT_NEAR(crossing, 19.5, 0.5 + 1e-6);
}

TEST(CornerOrderTest, ReversedProjectorCornersAreReordered) {
  // Correspondence: projector = camera + (100, 50).
  cv::Mat correspondence(100, 100, CV_32FC2);
  correspondence.forEach<cv::Vec2f>([](cv::Vec2f& value, const int* at) {
    value = cv::Vec2f(static_cast<float>(at[1] + 100), static_cast<float>(at[0] + 50));
  });
  const std::vector<cv::Point2f> camera{{10, 10}, {20, 10}, {30, 10}, {10, 20}, {20, 20}, {30, 20}};
  std::vector<cv::Point2f> projector;
  for (auto it = camera.rbegin(); it != camera.rend(); ++it) projector.push_back(*it + cv::Point2f(100, 50));
  ASSERT_EQ(calib::align_corner_order(camera, correspondence, projector), "");
  for (std::size_t i = 0; i < camera.size(); ++i) EXPECT_EQ(projector[i], camera[i] + cv::Point2f(100, 50));
  // Dual-image corners a square (10 px) off in either order: the two detections found different parts of the board.
  std::vector<cv::Point2f> shifted;
  for (const auto& corner : camera) shifted.push_back(corner + cv::Point2f(110, 50));
  EXPECT_THAT(calib::align_corner_order(camera, correspondence, shifted), ::testing::HasSubstr("cannot be put in"));
  // Without correspondences near the corners there is nothing to align with.
  correspondence.setTo(cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_THAT(calib::align_corner_order(camera, correspondence, projector),
              ::testing::HasSubstr("no projector correspondence"));
}

TEST(CameraCalibrationTest, RecoversIntrinsicsFromExactCorners) {
  std::vector<BoardView> views;
  const cv::Vec3d rotations[] = {{0.3, -0.2, 0}, {-0.35, 0.1, 0.1}, {0.1, 0.4, -0.1}, {-0.2, -0.35, 0.2}};
  for (const auto& rvec : rotations) views.push_back({"v", true_corners(rvec, {-80, -50, 600})});
  const auto result = calibrate_camera(views, kBoard, {640, 480});
  // Noise-free corners: the fit is exact to the optimiser's tolerance.
  EXPECT_LT(result.rms, 1e-3);
  EXPECT_NEAR(result.camera_matrix.at<double>(0, 0), 800.0, 0.01);
  EXPECT_NEAR(result.camera_matrix.at<double>(1, 2), 240.0, 0.01);
}

TEST(CameraCalibrationTest, ParallelPosesAndTooFewViewsAreRejected) {
  std::vector<BoardView> parallel;
  for (const double x : {-100.0, -60.0, -20.0, 0.0}) parallel.push_back({"p", true_corners({0, 0, 0}, {x, -50, 600})});
  EXPECT_THROW((void)calibrate_camera(parallel, kBoard, {640, 480}), ProcessingError);
  const std::vector<BoardView> two(parallel.begin(), parallel.begin() + 2);
  EXPECT_THROW((void)calibrate_camera(two, kBoard, {640, 480}), ProcessingError);
}

}  // namespace
}  // namespace rfrecon::calib
