// The stereo adjustment's uncertainty and pose-set checks on exactly known synthetic corners: the standard
// deviations it reports must match the spread of its estimates over noise draws, poor pose sets get warnings, dense
// correspondences shrink the errors the corners leave, misdecoded ones are left out, and gating drops a corrupted
// corner and down-weights a noisy pose.
#include <algorithm>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "calib/board_detection.h"
#include "calib/pose_diversity.h"
#include "calib/report_files.h"
#include "calib/stereo_calibration.h"
#include "host/core/errors.h"

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

// x, then y: drawn in this order whatever the compiler's order of evaluating arguments, so that every compiler sees
// the same noise.
cv::Point2f noise_point(std::normal_distribution<double>& noise, std::mt19937& rng) {
  const auto x = static_cast<float>(noise(rng));
  const auto y = static_cast<float>(noise(rng));
  return {x, y};
}

// Corners with `noise_px` of noise in both devices and, with dense_points > 0, that many dense correspondences per
// pose on a grid over the board (exact camera pixels, projector positions with `dense_noise_px`).
std::vector<StereoView> observe(const std::vector<std::pair<cv::Vec3d, cv::Vec3d>>& poses, double noise_px,
                                std::mt19937& rng, int dense_points = 0, double dense_noise_px = 0.0) {
  std::normal_distribution<double> noise(0.0, noise_px);
  cv::Matx33d proj_from_cam;
  cv::Rodrigues(kOm, proj_from_cam);
  std::vector<StereoView> views;
  for (const auto& [rvec, tvec] : poses) {
    cv::Matx33d cam_from_board;
    cv::Rodrigues(rvec, cam_from_board);
    cv::Vec3d proj_rvec;
    cv::Rodrigues(proj_from_cam * cam_from_board, proj_rvec);
    StereoView view{"pose_" + std::to_string(views.size()), {}, {}, {}};
    cv::projectPoints(board_object_points(kBoard), rvec, tvec, kCamera, kCameraDist, view.camera_corners);
    cv::projectPoints(board_object_points(kBoard), proj_rvec, proj_from_cam * tvec + kT, kProjector, kProjectorDist,
                      view.projector_corners);
    for (auto* corners : {&view.camera_corners, &view.projector_corners}) {
      for (auto& c : *corners) c += noise_point(noise, rng);
    }
    if (dense_points > 0) {
      // A grid over the inner corners' rectangle (240 x 150 mm), as many points as asked for.
      const int columns = static_cast<int>(std::sqrt(dense_points * 1.6)), rows = dense_points / columns;
      std::vector<cv::Point3f> on_board;
      for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < columns; ++c)
          on_board.emplace_back(240.0f * (c + 0.5f) / columns, 150.0f * (r + 0.5f) / rows, 0.0f);
      }
      std::vector<cv::Point2f> camera_px;
      cv::projectPoints(on_board, rvec, tvec, kCamera, kCameraDist, camera_px);
      cv::projectPoints(on_board, proj_rvec, proj_from_cam * tvec + kT, kProjector, kProjectorDist,
                        view.dense.projector);
      // The camera pixel is exact only to float precision; its projector position carries the noise.
      view.dense.camera = camera_px;
      std::normal_distribution<double> dense_noise(0.0, dense_noise_px);
      for (auto& p : view.dense.projector) {
        p += noise_point(dense_noise, rng);
      }
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
                              rig.proj_from_cam_translation_mm.at<double>(1),
                              rig.proj_from_cam_translation_mm.at<double>(2)};
    const double sigmas[6] = {u.camera_intrinsics.at<double>(0),
                              u.camera_intrinsics.at<double>(2),
                              u.projector_intrinsics.at<double>(1),
                              u.projector_intrinsics.at<double>(3),
                              u.proj_from_cam_translation_mm.at<double>(1),
                              u.proj_from_cam_translation_mm.at<double>(2)};
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
  EXPECT_NEAR(cv::norm(result.rig.proj_from_cam_translation_mm), cv::norm(kT), 1e-4);
  ASSERT_EQ(result.fit.camera_residuals_px.size(), 10u);
  EXPECT_EQ(result.fit.camera_residuals_px[0].size(), 54u);
}

// The relative depth scale of a rig: X = b f / d, so to first order the relative errors of the camera's focal length
// (which sets the board's distance) and of the baseline.
double scale_error(const StereoRig& rig) {
  return rig.camera_matrix.at<double>(0, 0) / kCamera(0, 0) - cv::norm(rig.proj_from_cam_translation_mm) / cv::norm(kT);
}

// Dense correspondences (500 per pose, 0.03 px like the rendered boards') pin what the corners leave loose: over 12
// draws on 12 poses with 0.03 px corners, the sum of squared depth scale errors (fx against the baseline) falls by
// more than half and the camera focal length's by more than a quarter (these draws: to 0.25 and 0.49 of the
// corners-only sums; another realisation of the noise gave 0.03 for the scale, so 12 draws tell the ratio only
// roughly). These boards stay near the image centre, which leaves the principal points loose either way.
TEST(StereoFitTest, DenseCorrespondencesShrinkTheIntrinsicsErrors) {
  constexpr int kDraws = 12;
  std::mt19937 rng(11);
  const auto poses = board_poses(12, 40.0);
  double corners_sq[2] = {0, 0}, dense_sq[2] = {0, 0};
  for (int draw = 0; draw < kDraws; ++draw) {
    const unsigned seed = rng();
    for (const bool dense : {false, true}) {
      std::mt19937 draw_rng(seed);  // the same corner noise with and without the dense points
      const auto views = observe(poses, 0.03, draw_rng, dense ? 500 : 0, 0.03);
      const StereoRig rig = calibrate_stereo(views, kBoard, kCameraSize, kProjectorSize).rig;
      const double errors[2] = {rig.camera_matrix.at<double>(0, 0) / kCamera(0, 0) - 1.0, scale_error(rig)};
      for (int k = 0; k < 2; ++k) (dense ? dense_sq : corners_sq)[k] += errors[k] * errors[k];
    }
  }
  EXPECT_LT(dense_sq[0], 0.75 * corners_sq[0]) << "camera fx";
  EXPECT_LT(dense_sq[1], 0.5 * corners_sq[1]) << "depth scale";
}

// Exact observations, but every 50th dense correspondence misdecoded by 3 to 30 px: those are left out (and said so),
// and the rest fit exactly.
TEST(StereoFitTest, ExactDenseCorrespondencesLeaveNoResidualOnceOutliersAreOut) {
  std::mt19937 rng(1);
  auto views = observe(board_poses(10, 40.0), 0.0, rng, 500, 0.0);
  std::size_t misdecoded = 0;
  for (auto& view : views) {
    for (std::size_t i = 0; i < view.dense.projector.size(); i += 50, ++misdecoded) {
      view.dense.projector[i].x += static_cast<float>(3 + i % 28);
    }
  }
  const auto result = calibrate_stereo(views, kBoard, kCameraSize, kProjectorSize);
  const std::string said =
      std::to_string(misdecoded) + " dense correspondences lay over 1 px from the corners' solution and were left out";
  EXPECT_NE(std::find(result.warnings.begin(), result.warnings.end(), said), result.warnings.end());
  EXPECT_LT(result.fit.residual_sigma_px, 1e-4);
  EXPECT_NEAR(result.rig.camera_matrix.at<double>(0, 0), 800.0, 1e-3);
  EXPECT_NEAR(cv::norm(result.rig.proj_from_cam_translation_mm), cv::norm(kT), 1e-4);
  ASSERT_EQ(result.fit.dense_view_rms_px.size(), 10u);
  EXPECT_LT(result.fit.dense_view_rms_px[0], 1e-4);
}

// One camera corner moved by 5 px (pose 3, corner 20) among 0.05 px of noise: gating drops it, names it in the
// report with its residual and z-score, and the rig is as good as without the bad corner (fx within 3 reported
// deviations of the truth and 0.02 px of the clean observations'); clean observations lose no corner and no pose is
// down-weighted.
TEST(GatingTest, CorruptedCornerIsDroppedAndNamed) {
  std::mt19937 rng(5);
  auto views = observe(board_poses(12, 40.0), 0.05, rng);
  const auto clean = calibrate_stereo(views, kBoard, kCameraSize, kProjectorSize);
  EXPECT_TRUE(clean.gating.empty()) << gating_json(clean.gating_thresholds, clean.gating).dump();
  views[3].camera_corners[20] += cv::Point2f(4.0f, -3.0f);
  const auto result = calibrate_stereo(views, kBoard, kCameraSize, kProjectorSize);
  ASSERT_EQ(result.gating.size(), 1u) << gating_json(result.gating_thresholds, result.gating).dump();
  const GatingDecision& decision = result.gating[0];
  EXPECT_EQ(decision.view, "pose_3");
  EXPECT_EQ(decision.series, "camera");
  EXPECT_EQ(decision.corner, 20);
  EXPECT_NEAR(decision.residual_px, 5.0, 0.3);
  EXPECT_GT(decision.z, result.gating_thresholds.corner_z);
  EXPECT_EQ(decision.weight, 0.0);
  ASSERT_EQ(result.camera_dropped.size(), 12u);
  EXPECT_EQ(result.camera_dropped[3].at(20), 1);
  // The stereo RMS over the kept corners is the noise's (0.05 px per axis: 0.071 px per point); over all, more.
  EXPECT_NEAR(result.rig.rms, 0.05 * std::sqrt(2.0), 0.01);
  EXPECT_GT(result.rms_all_px, result.rig.rms + 0.05);
  EXPECT_NEAR(result.rig.camera_matrix.at<double>(0, 0), 800.0,
              3.0 * result.rig.uncertainty.camera_intrinsics.at<double>(0));
  EXPECT_NEAR(result.rig.camera_matrix.at<double>(0, 0), clean.rig.camera_matrix.at<double>(0, 0), 0.02);
  const auto report = stereo_report_json(result).at("gating").at("decisions");
  ASSERT_EQ(report.size(), 1u);
  EXPECT_EQ(report[0].at("view"), "pose_3");
  EXPECT_EQ(report[0].at("corner"), 20);
  EXPECT_EQ(report[0].at("action"), "dropped");
  EXPECT_NEAR(report[0].at("residual_px").get<double>(), 5.0, 0.3);
}

// A pose whose projector corners carry 0.5 px of noise among poses of 0.05 px is down-weighted by about the ratio of
// the noise variances (0.01; accepted 0.003 to 0.03), and named; its corners are judged as weighted, so at most a
// few of them are dropped.
TEST(GatingTest, NoisyPoseIsDownWeighted) {
  std::mt19937 rng(9);
  auto views = observe(board_poses(12, 40.0), 0.05, rng);
  std::normal_distribution<double> noise(0.0, 0.5);
  for (auto& c : views[7].projector_corners) c += noise_point(noise, rng);
  const auto result = calibrate_stereo(views, kBoard, kCameraSize, kProjectorSize);
  const auto pose =
      std::find_if(result.gating.begin(), result.gating.end(), [](const GatingDecision& d) { return d.corner < 0; });
  ASSERT_NE(pose, result.gating.end()) << gating_json(result.gating_thresholds, result.gating).dump();
  EXPECT_EQ(pose->view, "pose_7");
  EXPECT_EQ(pose->series, "projector");
  EXPECT_GT(pose->z, result.gating_thresholds.pose_z);
  EXPECT_GT(pose->weight, 0.003);
  EXPECT_LT(pose->weight, 0.03);
  EXPECT_LE(
      std::count_if(result.gating.begin(), result.gating.end(), [](const GatingDecision& d) { return d.corner >= 0; }),
      3);
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
  // Near-frontal boards leave focal length and distance entangled: warned about when the intrinsics still come out
  // determined, refused (ProcessingError, exit 6) when they do not; which depends on the rounding of the build.
  const auto frontal_views = observe(board_poses(12, 10.0), 0.05, rng);
  try {
    const auto frontal = calibrate_stereo(frontal_views, kBoard, kCameraSize, kProjectorSize);
    EXPECT_TRUE(contains(frontal.warnings, "tilts span"));
  } catch (const ProcessingError& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("not determined"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("tilted differently"));
  }
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
