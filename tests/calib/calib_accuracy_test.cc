// Calibration from the synthetic checkerboard poses (estimated through dual photography, not copied from the truth)
// against the true rig: intrinsics, stereo pose, and row alignment after rectification.
#include <filesystem>
#include <fstream>
#include <tuple>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "calib/corner_comparison.h"
#include "calib/rig.h"
#include "calib/rig_comparison.h"
#include "host/core/json_file.h"

namespace rfrecon::calib {
namespace {

namespace fs = std::filesystem;
const fs::path kPoses = fs::path(RFRECON_FIXTURES_DIR) / "checkerboard-poses";

class CalibrationAccuracyTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    truth_ = read_rig(kPoses / "truth" / "rig.yaml");
    estimated_ = read_rig(kPoses / "estimated" / "rig.yaml");
  }
  static StereoRig truth_;
  static StereoRig estimated_;
};
StereoRig CalibrationAccuracyTest::truth_;
StereoRig CalibrationAccuracyTest::estimated_;

double relative_error(double estimated, double truth) { return std::abs(estimated - truth) / std::abs(truth); }

// Focal lengths within `focal_relative` of the truth and the principal point within `principal_px` pixels.
void expect_intrinsics_near(const cv::Mat& estimated, const cv::Mat& truth, double focal_relative,
                            double principal_px) {
  EXPECT_LT(relative_error(estimated.at<double>(0, 0), truth.at<double>(0, 0)), focal_relative) << "fx";
  EXPECT_LT(relative_error(estimated.at<double>(1, 1), truth.at<double>(1, 1)), focal_relative) << "fy";
  EXPECT_NEAR(estimated.at<double>(0, 2), truth.at<double>(0, 2), principal_px) << "cx";
  EXPECT_NEAR(estimated.at<double>(1, 2), truth.at<double>(1, 2), principal_px) << "cy";
}

// Tolerances: the targets (focal 0.5%, principal point 2 px, baseline 0.5%, rotation 0.1 degree, rows
// 0.2 px) tightened to about five to ten times what this rig achieves (docs/calibration.md has the measured values
// on 16 poses: focal within 0.005%, principal points within 0.3 px, baseline 0.005%, rotation 0.006 degree, stereo
// RMS 0.037 px), so a regression in corner detection or dual-image quality fails them. The rendering is
// deterministic.
TEST_F(CalibrationAccuracyTest, CameraIntrinsics) {
  expect_intrinsics_near(estimated_.camera_matrix, truth_.camera_matrix, 0.0005, 1.0);
}

TEST_F(CalibrationAccuracyTest, ProjectorIntrinsics) {
  expect_intrinsics_near(estimated_.projector_matrix, truth_.projector_matrix, 0.0005, 1.0);
}

TEST_F(CalibrationAccuracyTest, StereoPose) {
  EXPECT_LT(
      relative_error(cv::norm(estimated_.proj_from_cam_translation_mm), cv::norm(truth_.proj_from_cam_translation_mm)),
      0.0003)
      << "baseline";
  const cv::Mat difference = estimated_.proj_from_cam_rotation * truth_.proj_from_cam_rotation.t();
  cv::Mat rvec;
  cv::Rodrigues(difference, rvec);
  const double rotation_error_deg = cv::norm(rvec) * 180.0 / CV_PI;
  RecordProperty("rotation_error_deg", std::to_string(rotation_error_deg));
  RecordProperty("baseline_mm", std::to_string(cv::norm(estimated_.proj_from_cam_translation_mm)));
  EXPECT_LT(rotation_error_deg, 0.03);
  EXPECT_GT(estimated_.rms, 0.0);
  EXPECT_LT(estimated_.rms, 0.08) << "stereo reprojection RMS, px";
}

// The true board corners of every pose in `poses_dir`, projected by the true camera and projector, then rectified
// with the estimated rig: {RMS, worst} difference of their rectified rows, in px.
std::pair<double, double> rectified_row_error(const fs::path& poses_dir, const StereoRig& truth,
                                              const StereoRig& estimated) {
  std::ifstream in(poses_dir / "truth" / "board_poses.json");
  if (!in) throw std::runtime_error("missing " + (poses_dir / "truth" / "board_poses.json").string());
  std::vector<cv::Point3d> corners_cam_mm;
  for (const auto& pose : nlohmann::json::parse(in)) {
    for (const auto& corner : pose.at("inner_corners_cam_mm")) {
      corners_cam_mm.emplace_back(corner[0].get<double>(), corner[1].get<double>(), corner[2].get<double>());
    }
  }
  std::vector<cv::Point2d> camera_px;
  std::vector<cv::Point2d> projector_px;
  cv::Mat rvec_proj;
  cv::Rodrigues(truth.proj_from_cam_rotation, rvec_proj);
  cv::projectPoints(corners_cam_mm, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), truth.camera_matrix, truth.dist_coeffs,
                    camera_px);
  cv::projectPoints(corners_cam_mm, rvec_proj, truth.proj_from_cam_translation_mm, truth.projector_matrix,
                    truth.projector_dist_coeffs, projector_px);
  std::vector<cv::Point2d> camera_rect;
  std::vector<cv::Point2d> projector_rect;
  cv::undistortPoints(camera_px, camera_rect, estimated.camera_matrix, estimated.dist_coeffs, estimated.rect_from_cam,
                      estimated.rect_cam_image_from_rect);
  cv::undistortPoints(projector_px, projector_rect, estimated.projector_matrix, estimated.projector_dist_coeffs,
                      estimated.rect_from_proj, estimated.rect_proj_image_from_rect);
  double worst = 0.0;
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < camera_rect.size(); ++i) {
    const double dy = camera_rect[i].y - projector_rect[i].y;
    worst = std::max(worst, std::abs(dy));
    sum_sq += dy * dy;
  }
  return {std::sqrt(sum_sq / static_cast<double>(std::max<std::size_t>(camera_rect.size(), 1))), worst};
}

// The standard deviations the adjustment reports cover the actual errors: every intrinsic of both devices and every
// component of T within 3 sigma of the truth (on one rendering; scripts/calibration_seeds.sh checks the spread over
// seeds), and the report holds them with the per-view errors and the pose-set checks.
TEST_F(CalibrationAccuracyTest, ReportedUncertaintyCoversTheError) {
  const auto& u = estimated_.uncertainty;
  ASSERT_FALSE(u.empty());
  for (const auto& [estimated, truth, sigma, device] :
       {std::tuple{&estimated_.camera_matrix, &truth_.camera_matrix, &u.camera_intrinsics, "camera"},
        {&estimated_.projector_matrix, &truth_.projector_matrix, &u.projector_intrinsics, "projector"}}) {
    const double values[4][2] = {{estimated->at<double>(0, 0), truth->at<double>(0, 0)},
                                 {estimated->at<double>(1, 1), truth->at<double>(1, 1)},
                                 {estimated->at<double>(0, 2), truth->at<double>(0, 2)},
                                 {estimated->at<double>(1, 2), truth->at<double>(1, 2)}};
    for (int k = 0; k < 4; ++k) {
      EXPECT_GT(sigma->at<double>(k), 0.0) << device << " " << k;
      EXPECT_LT(std::abs(values[k][0] - values[k][1]), 3.0 * sigma->at<double>(k)) << device << " " << k;
    }
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(std::abs(estimated_.proj_from_cam_translation_mm.at<double>(k) -
                       truth_.proj_from_cam_translation_mm.at<double>(k)),
              3.0 * u.proj_from_cam_translation_mm.at<double>(k))
        << "T " << k;
  }
  const auto report = read_json_file(kPoses / "estimated" / "rig_report" / "report.json");
  EXPECT_EQ(report.at("views").size(), estimated_.per_view_errors.size());
  EXPECT_TRUE(report.at("warnings").empty()) << report.at("warnings").dump();
  EXPECT_GE(report.at("tilt_spread_deg").get<double>(), 30.0);
  for (const char* file : {"residuals_camera.png", "residuals_projector.png", "coverage_camera.png",
                           "coverage_projector.png", "errors.png"}) {
    EXPECT_TRUE(fs::exists(kPoses / "estimated" / "rig_report" / file)) << file;
  }
  // The residual fields are drawn over each device's image, at its size; the rendered poses need no gating.
  for (const auto& [file, size] : {std::pair{"residual_field_camera.png", estimated_.camera_size},
                                   std::pair{"residual_field_projector.png", estimated_.projector_size}}) {
    const cv::Mat field = cv::imread((kPoses / "estimated" / "rig_report" / file).string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(field.empty()) << file;
    EXPECT_EQ(field.size(), size) << file;
  }
  EXPECT_TRUE(report.at("gating").at("decisions").empty()) << report.at("gating").dump();
}

// The corners `calibrate` found (its report's corners.json) against the rendered board's true corners projected with
// the true rig, over all 16 poses: the targets, RMS <= 0.02 px per axis and |mean| <= 0.005 px per axis, for
// both devices (measured 0.014 px and 0.013 px RMS, means within 0.0013 px; docs/calibration.md has the spread over
// seeds).
TEST_F(CalibrationAccuracyTest, CornersMatchTheTruth) {
  const auto views =
      read_view_corners(kPoses / "estimated" / "rig_report" / "corners.json", kPoses / "truth" / "board_poses.json");
  ASSERT_EQ(views.size(), 16u);
  const auto comparison = compare_corners(views, truth_);
  for (const auto& [errors, device] : {std::pair{comparison.camera, "camera"}, {comparison.projector, "projector"}}) {
    RecordProperty(std::string(device) + "_corner_rms_px", std::to_string(errors.rms_px));
    EXPECT_EQ(errors.corners, 16 * 126) << device;
    EXPECT_LE(errors.rms_px, 0.02) << device;
    EXPECT_LE(std::abs(errors.mean_px.x), 0.005) << device;
    EXPECT_LE(std::abs(errors.mean_px.y), 0.005) << device;
  }
}

// The corner comparison itself: the true corners with a known offset (camera +0.1 px in x, the projector's numbered
// from the other end and -0.2 px in y) give exactly that mean and RMS.
TEST_F(CalibrationAccuracyTest, CornerComparisonMeasuresAKnownOffset) {
  const auto views =
      read_view_corners(kPoses / "estimated" / "rig_report" / "corners.json", kPoses / "truth" / "board_poses.json");
  ViewCorners view{views.at(0).true_corners_cam_mm, {}, {}};
  std::vector<cv::Point2d> camera_px, projector_px;
  cv::projectPoints(view.true_corners_cam_mm, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), truth_.camera_matrix,
                    truth_.dist_coeffs, camera_px);
  cv::Mat om;
  cv::Rodrigues(truth_.proj_from_cam_rotation, om);
  cv::projectPoints(view.true_corners_cam_mm, om, truth_.proj_from_cam_translation_mm, truth_.projector_matrix,
                    truth_.projector_dist_coeffs, projector_px);
  for (const auto& p : camera_px) view.camera_px.emplace_back(p.x + 0.1, p.y);
  for (auto p = projector_px.rbegin(); p != projector_px.rend(); ++p) view.projector_px.emplace_back(p->x, p->y - 0.2);
  const auto comparison = compare_corners({view}, truth_);
  EXPECT_NEAR(comparison.camera.mean_px.x, 0.1, 1e-4);
  EXPECT_NEAR(comparison.camera.mean_px.y, 0.0, 1e-4);
  EXPECT_NEAR(comparison.camera.rms_px, 0.1 / std::sqrt(2.0), 1e-4);
  EXPECT_NEAR(comparison.projector.mean_px.y, -0.2, 1e-4);
  EXPECT_NEAR(comparison.projector.max_px, 0.2, 1e-4);
}

// Exact correspondences of the working volume (500 to 700 mm) triangulated with the estimated rig: the depth scale
// within 6e-5 (three times the target for the RMS over seeds, docs/calibration.md has the spread over 10 seeds) and
// the depth error RMS within 3e-4 (it includes the principal points' and distortion's errors).
TEST_F(CalibrationAccuracyTest, DepthScaleOfTheEstimatedRig) {
  const auto comparison = compare_rigs(estimated_, truth_);
  RecordProperty("depth_scale_error", std::to_string(comparison.depth_scale_error));
  EXPECT_GT(comparison.points, 300);
  EXPECT_LT(std::abs(comparison.depth_scale_error), 6e-5);
  EXPECT_LT(comparison.depth_rms_error, 3e-4);
}

// The comparison itself, on a rig whose error is known: the true rig with its baseline lengthened by 1e-4. Rays keep
// their directions and the projector's centre moves out by the factor, so every triangulated point moves out by it:
// depth scale error and depth RMS both exactly 1e-4, baseline error 1e-4, no focal, principal-point or rotation error.
TEST_F(CalibrationAccuracyTest, RigComparisonMeasuresAKnownBaselineError) {
  StereoRig longer = truth_;
  longer.proj_from_cam_translation_mm = cv::Mat(
      truth_.proj_from_cam_translation_mm *
      (1.0 + 1e-4));  // a new matrix: assigning the expression would write into truth_.proj_from_cam_translation_mm
  const auto comparison = compare_rigs(longer, truth_);
  EXPECT_GT(comparison.points, 300);
  EXPECT_NEAR(comparison.depth_scale_error, 1e-4, 1e-9);
  EXPECT_NEAR(comparison.depth_rms_error, 1e-4, 1e-9);
  EXPECT_NEAR(comparison.baseline_error, 1e-4, 1e-12);
  EXPECT_LT(comparison.rotation_error_deg, 1e-9);
  EXPECT_LT(comparison.camera_focal_error + comparison.projector_focal_error, 1e-15);
}

TEST_F(CalibrationAccuracyTest, RectifiedCorrespondencesShareRows) {
  const auto [rms, worst] = rectified_row_error(kPoses, truth_, estimated_);
  RecordProperty("rectified_row_rms_px", std::to_string(rms));
  EXPECT_LT(rms, 0.05);
  EXPECT_LT(worst, 0.2);
}

// The projector 2.1 times finer than the camera on the board (camera 320x256, projector 640x480): the dual image
// has gaps between reached projector pixels. The projector's calibration must still meet the targets
// (focal 0.5%, principal point 2 px), and the baseline 0.5%; measured 0.07%, 1.7 px and 0.009%. The rows and the
// rotation are asserted on the full-resolution rig only.
TEST(CalibrationResolutionRatioTest, ProjectorFinerThanCamera) {
  const fs::path poses = fs::path(RFRECON_FIXTURES_DIR) / "checkerboard-poses-small-camera";
  const auto truth = read_rig(poses / "truth" / "rig.yaml");
  const auto estimated = read_rig(poses / "estimated" / "rig.yaml");
  expect_intrinsics_near(estimated.projector_matrix, truth.projector_matrix, 0.005, 2.0);
  EXPECT_LT(
      relative_error(cv::norm(estimated.proj_from_cam_translation_mm), cv::norm(truth.proj_from_cam_translation_mm)),
      0.005)
      << "baseline";
}

TEST(CameraOnlyCalibrationTest, FocalLengthFromWhiteFrames) {
  const auto truth = read_rig(kPoses / "truth" / "rig.yaml");
  cv::FileStorage fs((kPoses / "estimated" / "camera.yaml").string(), cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  cv::Mat camera_matrix;
  fs["camera_matrix"] >> camera_matrix;
  EXPECT_LT(relative_error(camera_matrix.at<double>(0, 0), truth.camera_matrix.at<double>(0, 0)), 0.002);
  EXPECT_NEAR(camera_matrix.at<double>(0, 2), truth.camera_matrix.at<double>(0, 2), 1.5);
}

}  // namespace
}  // namespace rfrecon::calib
