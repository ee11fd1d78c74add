// The stereo adjustment's uncertainty and pose-set checks on exactly known synthetic corners: the standard
// deviations it reports must match the spread of its estimates over noise draws, and poor pose sets get warnings.
#include <random>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "calib/board_detection.h"
#include "calib/pose_diversity.h"
#include "calib/stereo_calibration.h"

namespace rfrecon::calib {
namespace {

const BoardSpec kBoard{9, 6, 30.0};
const cv::Size kCameraSize(640, 512);
const cv::Size kProjectorSize(640, 480);
const cv::Matx33d kCamera(800, 0, 325, 0, 799, 252, 0, 0, 1);
const cv::Matx33d kProjector(860, 0, 330, 0, 860, 96, 0, 0, 1);
const cv::Vec<double, 5> kCameraDist(-0.08, 0.05, 0.0005, -0.0003, 0.0);
const cv::Vec<double, 5> kProjectorDist(0.02, 0.0, 0.0, 0.0, 0.0);
const cv::Vec3d kOm(-0.11, 0.03, 0.0);   // projector from camera
const cv::Vec3d kT(-20.0, 169.0, 19.0);  // mm: the projector 170 mm above the camera

// Board poses (rotation about x, y in degrees, centre offset in mm, distance) tilted by `tilt` at most.
std::vector<std::pair<cv::Vec3d, cv::Vec3d>> board_poses(int count, double tilt_deg) {
  std::vector<std::pair<cv::Vec3d, cv::Vec3d>> poses;
  for (int i = 0; i < count; ++i) {
    const double a = 2.0 * CV_PI * i / count;
    const double t = tilt_deg * CV_PI / 180.0 * (i % 3 == 0 ? 0.5 : 1.0);
    const cv::Vec3d rvec(t * std::cos(a), t * std::sin(a), 0.1 * std::sin(3 * a));
    cv::Matx33d r;
    cv::Rodrigues(rvec, r);
    // Board centre (120, 75 mm from the first corner) near the optical axis, at 560 to 640 mm.
    const cv::Vec3d centre(30.0 * std::cos(a), 20.0 * std::sin(a), 600.0 + 40.0 * std::cos(2 * a));
    poses.emplace_back(rvec, centre - r * cv::Vec3d(120.0, 75.0, 0.0));
  }
  return poses;
}

std::vector<StereoView> observe(const std::vector<std::pair<cv::Vec3d, cv::Vec3d>>& poses, double noise_px,
                                std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, noise_px);
  cv::Matx33d proj_from_cam;
  cv::Rodrigues(kOm, proj_from_cam);
  std::vector<StereoView> views;
  for (const auto& [rvec, tvec] : poses) {
    cv::Matx33d cam_from_board;
    cv::Rodrigues(rvec, cam_from_board);
    cv::Vec3d proj_rvec;
    cv::Rodrigues(proj_from_cam * cam_from_board, proj_rvec);
    StereoView view{"pose_" + std::to_string(views.size()), {}, {}};
    cv::projectPoints(board_object_points(kBoard), rvec, tvec, kCamera, kCameraDist, view.camera_corners);
    cv::projectPoints(board_object_points(kBoard), proj_rvec, proj_from_cam * tvec + kT, kProjector, kProjectorDist,
                      view.projector_corners);
    for (auto* corners : {&view.camera_corners, &view.projector_corners}) {
      for (auto& c : *corners) c += cv::Point2f(static_cast<float>(noise(rng)), static_cast<float>(noise(rng)));
    }
    views.push_back(std::move(view));
  }
  return views;
}

double spread(const std::vector<double>& values) {
  double mean = 0.0;
  for (const double v : values) mean += v / static_cast<double>(values.size());
  double sum_sq = 0.0;
  for (const double v : values) sum_sq += (v - mean) * (v - mean);
  return std::sqrt(sum_sq / static_cast<double>(values.size() - 1));
}

// 40 draws of 0.1 px corner noise: each reported standard deviation (mean over draws) within 35% of the spread of
// the estimates (the spread of 40 draws is itself uncertain by about 11%), and the residual sigma within 5% of the
// noise.
TEST(StereoFitTest, StandardDeviationsMatchTheSpreadOverNoiseDraws) {
  constexpr int kDraws = 40;
  constexpr double kNoisePx = 0.1;
  std::mt19937 rng(7);
  const auto poses = board_poses(12, 40.0);
  std::vector<std::vector<double>> estimates(6);
  std::vector<double> reported(6, 0.0);
  for (int draw = 0; draw < kDraws; ++draw) {
    const auto result = calibrate_stereo(observe(poses, kNoisePx, rng), kBoard, kCameraSize, kProjectorSize);
    const auto& rig = result.rig;
    const auto& u = rig.uncertainty;
    const double values[6] = {rig.camera_matrix.at<double>(0, 0),
                              rig.camera_matrix.at<double>(0, 2),
                              rig.projector_matrix.at<double>(1, 1),
                              rig.projector_matrix.at<double>(1, 2),
                              rig.T.at<double>(1),
                              rig.T.at<double>(2)};
    const double sigmas[6] = {u.camera_intrinsics.at<double>(0),
                              u.camera_intrinsics.at<double>(2),
                              u.projector_intrinsics.at<double>(1),
                              u.projector_intrinsics.at<double>(3),
                              u.T.at<double>(1),
                              u.T.at<double>(2)};
    for (int k = 0; k < 6; ++k) {
      estimates[k].push_back(values[k]);
      reported[k] += sigmas[k] / kDraws;
    }
    EXPECT_NEAR(result.fit.residual_sigma_px, kNoisePx, 0.05 * kNoisePx);
  }
  const char* names[6] = {"camera fx", "camera cx", "projector fy", "projector cy", "Ty", "Tz"};
  for (int k = 0; k < 6; ++k) {
    const double empirical = spread(estimates[k]);
    EXPECT_GT(reported[k], 0.65 * empirical) << names[k];
    EXPECT_LT(reported[k], 1.35 * empirical) << names[k];
  }
}

TEST(StereoFitTest, ExactCornersLeaveNoResidual) {
  std::mt19937 rng(1);
  const auto result = calibrate_stereo(observe(board_poses(10, 40.0), 0.0, rng), kBoard, kCameraSize, kProjectorSize);
  EXPECT_LT(result.fit.residual_sigma_px, 1e-4);
  EXPECT_NEAR(result.rig.camera_matrix.at<double>(0, 0), 800.0, 1e-3);
  EXPECT_NEAR(cv::norm(result.rig.T), cv::norm(kT), 1e-4);
  ASSERT_EQ(result.fit.camera_residuals_px.size(), 10u);
  EXPECT_EQ(result.fit.camera_residuals_px[0].size(), 54u);
}

// Few poses, small tilts and boards bunched in the middle of the image each get their warning; a good set none.
TEST(PoseSetTest, PoorPoseSetsAreWarnedAbout) {
  std::mt19937 rng(3);
  const auto good = calibrate_stereo(observe(board_poses(12, 40.0), 0.05, rng), kBoard, kCameraSize, kProjectorSize);
  const auto contains = [](const std::vector<std::string>& warnings, const std::string& text) {
    for (const auto& w : warnings) {
      if (w.find(text) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_FALSE(contains(good.warnings, "poses:")) << "12 poses";
  EXPECT_FALSE(contains(good.warnings, "tilts span"));
  const auto few = calibrate_stereo(observe(board_poses(5, 40.0), 0.05, rng), kBoard, kCameraSize, kProjectorSize);
  EXPECT_TRUE(contains(few.warnings, "only 5 poses"));
  const auto frontal = calibrate_stereo(observe(board_poses(12, 10.0), 0.05, rng), kBoard, kCameraSize, kProjectorSize);
  EXPECT_TRUE(contains(frontal.warnings, "tilts span"));
  // These boards stay near the optical axes: they cannot cover the image.
  EXPECT_TRUE(contains(good.warnings, "of the camera image"));
  EXPECT_LT(good.camera.coverage, kRecommendedCoverage);
}

// A board whose printed pattern (one square beyond the corners) spans the top-left quarter of a 640x448 image covers
// 4 x 3 of the 8 x 6 coverage cells, and no pixel outside the pattern.
TEST(PoseSetTest, CoverageCountsThePrintedPattern) {
  std::vector<cv::Point2f> corners;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 9; ++c) corners.emplace_back(32.0f * (c + 1), 32.0f * (r + 1));
  }
  const cv::Mat counts = board_coverage_counts({corners}, kBoard, {640, 448});
  EXPECT_DOUBLE_EQ(covered_fraction(counts), 12.0 / 48.0);
  EXPECT_EQ(counts.at<int>(10, 10), 1) << "inside the pattern, outside the corners' hull";
  EXPECT_EQ(counts.at<int>(300, 400), 0);
}

}  // namespace
}  // namespace rfrecon::calib
