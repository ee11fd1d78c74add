// Row rectification of rigs like real ones: unequal camera and projector sizes, pixel pitch ratios 0.4 to 2.5, the
// projector beside, above, below or diagonal to the camera, principal points far off centre. Each rig is checked on
// points projected through its true lens model: matching rectified rows, depth from disparity, cv::triangulatePoints
// and the Q matrix, no cropped pixel, no undersampling; and the rig file's P1, P2, Q are the same.
#include "calib/rectification.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "calib/rig.h"
#include "host/core/errors.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::calib {
namespace {

struct RigCase {
  const char* name;
  cv::Size camera_size, projector_size;
  double camera_f, pitch_ratio;   // projector pixel / camera pixel at the same distance: f_proj = camera_f / ratio
  cv::Vec3d projector_centre_mm;  // in the camera frame (y down)
  cv::Point2d projector_principal_fraction;
};

const RigCase kCases[] = {
    {"beside_right", {1280, 1024}, {1024, 768}, 2200, 1.0, {150, 0, 0}, {0.5, 0.5}},
    {"beside_left_finer_projector", {1280, 1024}, {1920, 1080}, 2200, 0.4, {-200, 10, 0}, {0.45, 0.6}},
    {"above_lens_offset", {1280, 1024}, {1024, 768}, 2200, 1.4, {20, -170, 0}, {0.5, 0.05}},
    {"below_coarser_projector", {1920, 1200}, {1024, 768}, 3000, 2.5, {-10, 200, 5}, {0.5, 0.95}},
    {"diagonal", {1920, 1200}, {1920, 1080}, 3000, 0.8, {-280, -160, 20}, {0.3, 0.2}},
};

// The projector at `c.projector_centre_mm`, its optical axis toward a point 600 mm ahead of the camera.
StereoRig make_rig(const RigCase& c) {
  StereoRig rig;
  rig.camera_size = c.camera_size;
  rig.projector_size = c.projector_size;
  rig.camera_matrix = (cv::Mat_<double>(3, 3) << c.camera_f, 0, 0.52 * c.camera_size.width, 0, c.camera_f * 1.001,
                       0.47 * c.camera_size.height, 0, 0, 1);
  rig.dist_coeffs = (cv::Mat_<double>(1, 5) << -0.08, 0.05, 0.0005, -0.0003, 0.0);
  const double f_proj = c.camera_f / c.pitch_ratio;
  rig.projector_matrix =
      (cv::Mat_<double>(3, 3) << f_proj, 0, c.projector_principal_fraction.x * c.projector_size.width, 0, f_proj,
       c.projector_principal_fraction.y * c.projector_size.height, 0, 0, 1);
  rig.projector_dist_coeffs = (cv::Mat_<double>(1, 5) << 0.03, 0.0, 0.0, 0.0, 0.0);
  const cv::Vec3d centre = c.projector_centre_mm;
  const cv::Vec3d forward = cv::normalize(cv::Vec3d(0, 0, 600) - centre);
  const cv::Vec3d right = cv::normalize(cv::Vec3d(0, -1, 0).cross(forward) * -1.0);
  const cv::Vec3d down = forward.cross(right);
  const cv::Matx33d proj_from_cam(right[0], right[1], right[2], down[0], down[1], down[2], forward[0], forward[1],
                                  forward[2]);
  rig.proj_from_cam_rotation = cv::Mat(proj_from_cam).clone();
  rig.proj_from_cam_translation_mm = cv::Mat(-(proj_from_cam * centre)).clone();
  compute_stereo_geometry(rig);
  return rig;
}

// Points 450-800 mm ahead that both devices see (inside both images).
void visible_points(const StereoRig& rig, std::vector<cv::Point3d>& points, std::vector<cv::Point2d>& cam_px,
                    std::vector<cv::Point2d>& proj_px) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> lateral(-200.0, 200.0), depth(450.0, 800.0);
  const cv::Vec3d no_rotation(0, 0, 0), no_translation(0, 0, 0);
  cv::Vec3d rvec;
  cv::Rodrigues(rig.proj_from_cam_rotation, rvec);
  for (int tries = 0; points.size() < 400 && tries < 1000000; ++tries) {
    const cv::Point3d X(lateral(random), lateral(random), depth(random));
    std::vector<cv::Point2d> c, p;
    cv::projectPoints(std::vector<cv::Point3d>{X}, no_rotation, no_translation, rig.camera_matrix, rig.dist_coeffs, c);
    cv::projectPoints(std::vector<cv::Point3d>{X}, rvec, cv::Vec3d(rig.proj_from_cam_translation_mm),
                      rig.projector_matrix, rig.projector_dist_coeffs, p);
    const cv::Rect2d camera(0, 0, rig.camera_size.width - 1, rig.camera_size.height - 1);
    const cv::Rect2d projector(0, 0, rig.projector_size.width - 1, rig.projector_size.height - 1);
    if (!camera.contains(c[0]) || !projector.contains(p[0])) continue;
    points.push_back(X);
    cam_px.push_back(c[0]);
    proj_px.push_back(p[0]);
  }
}

cv::TermCriteria tight() { return {cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-14}; }

class RectificationTest : public ::testing::TestWithParam<RigCase> {};

TEST_P(RectificationTest, RowsMatchAndDisparityGivesDepth) {
  const StereoRig rig = make_rig(GetParam());
  const RowRectification rect = rectify_rig(rig);
  std::vector<cv::Point3d> points;
  std::vector<cv::Point2d> cam_px, proj_px, cam_rect, proj_rect;
  visible_points(rig, points, cam_px, proj_px);
  ASSERT_EQ(points.size(), 400u);
  cv::undistortPoints(cam_px, cam_rect, rig.camera_matrix, rig.dist_coeffs, rig.rect_from_cam,
                      rig.rect_cam_image_from_rect, tight());
  cv::undistortPoints(proj_px, proj_rect, rig.projector_matrix, rig.projector_dist_coeffs, rig.rect_from_proj,
                      rig.rect_proj_image_from_rect, tight());
  cv::Mat X_rect;
  cv::triangulatePoints(rig.rect_cam_image_from_rect, rig.rect_proj_image_from_rect, cam_rect, proj_rect, X_rect);
  const cv::Matx44d Q(rig.rect_from_disparity);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const cv::Vec3d expected = rect.rect_from_cam * cv::Vec3d(points[i]);  // rectified camera frame
    // Same row within 1e-6 px: epipolar lines are rows.
    ASSERT_NEAR(cam_rect[i].y, proj_rect[i].y, 1e-6) << i;
    // Depth from disparity (the depth stage's formula) within 1e-6 relative.
    const double disparity = (cam_rect[i].x - rect.cx_cam_px) - (proj_rect[i].x - rect.cx_proj_px);
    ASSERT_NEAR(rect.f_px * rect.baseline_mm / disparity, expected[2], 1e-6 * expected[2]) << i;
    // cv::triangulatePoints with P1, P2 and cv::reprojectImageTo3D's Q give the point within 1e-6 mm.
    const cv::Vec4d h(X_rect.col(static_cast<int>(i)));
    for (int a = 0; a < 3; ++a) ASSERT_NEAR(h[a] / h[3], expected[a], 1e-6 * expected[2]) << i;
    const cv::Vec4d q = Q * cv::Vec4d(cam_rect[i].x, cam_rect[i].y, cam_rect[i].x - proj_rect[i].x, 1.0);
    for (int a = 0; a < 3; ++a) ASSERT_NEAR(q[a] / q[3], expected[a], 1e-6 * expected[2]) << i;
  }
}

TEST_P(RectificationTest, RectifiedImagesHoldEveryPixelAtFullResolution) {
  const StereoRig rig = make_rig(GetParam());
  const RowRectification rect = rectify_rig(rig);
  EXPECT_EQ(rig.rectified_camera_size, rect.camera_size);
  EXPECT_EQ(rig.rectified_projector_size, rect.projector_size);
  const auto check = [&](const cv::Mat& K, const cv::Mat& dist, const cv::Mat& R, const cv::Mat& P, cv::Size size,
                         cv::Size rect_size, bool rows_only, const char* device) {
    std::vector<cv::Point2d> px, out;
    for (int x = 0; x < size.width; x += 7) px.insert(px.end(), {{double(x), 0.0}, {double(x), size.height - 1.0}});
    for (int y = 0; y < size.height; y += 7) px.insert(px.end(), {{0.0, double(y)}, {size.width - 1.0, double(y)}});
    cv::undistortPoints(px, out, K, dist, R, P, tight());
    for (const auto& p : out) {
      EXPECT_GE(p.x, 0.0) << device;
      EXPECT_LE(p.x, rect_size.width - 1.0) << device;
      if (!rows_only) {
        EXPECT_GE(p.y, 0.0) << device;
        EXPECT_LE(p.y, rect_size.height - 1.0) << device;
      }
    }
    // A one-pixel step at the image centre moves at least 0.95 rectified pixels: the image is not undersampled.
    const cv::Point2d c(K.at<double>(0, 2), K.at<double>(1, 2));
    std::vector<cv::Point2d> steps{c, c + cv::Point2d(1, 0), c + cv::Point2d(0, 1)}, rect_steps;
    cv::undistortPoints(steps, rect_steps, K, dist, R, P, tight());
    EXPECT_GE(cv::norm(rect_steps[1] - rect_steps[0]), 0.95) << device;
    EXPECT_GE(cv::norm(rect_steps[2] - rect_steps[0]), 0.95) << device;
  };
  check(rig.camera_matrix, rig.dist_coeffs, rig.rect_from_cam, rig.rect_cam_image_from_rect, rig.camera_size,
        rect.camera_size, false, "camera");
  // The projector's rectified image has the camera's rows: only its columns must all be inside.
  check(rig.projector_matrix, rig.projector_dist_coeffs, rig.rect_from_proj, rig.rect_proj_image_from_rect,
        rig.projector_size, rect.projector_size, true, "projector");
}

TEST_P(RectificationTest, RigFileHoldsTheSameRectification) {
  const StereoRig rig = make_rig(GetParam());
  testing::TempDir dir("rectification_test");
  write_rig(rig, dir.path() / "rig.yaml");
  cv::FileStorage fs((dir.path() / "rig.yaml").string(), cv::FileStorage::READ);
  EXPECT_EQ(static_cast<std::string>(fs["format"]), kRigFormat);
  EXPECT_EQ(static_cast<int>(fs["version"]), kRigVersion);
  for (const char* key : {"R1", "R2", "P1", "P2", "Q"}) {
    cv::Mat from_file;
    fs[key] >> from_file;
    const cv::Mat& expected = std::string(key) == "R1"   ? rig.rect_from_cam
                              : std::string(key) == "R2" ? rig.rect_from_proj
                              : std::string(key) == "P1" ? rig.rect_cam_image_from_rect
                              : std::string(key) == "P2" ? rig.rect_proj_image_from_rect
                                                         : rig.rect_from_disparity;
    EXPECT_LE(cv::norm(from_file, expected, cv::NORM_INF), 1e-9 * (1.0 + cv::norm(expected, cv::NORM_INF))) << key;
  }
}

INSTANTIATE_TEST_SUITE_P(RealRigs, RectificationTest, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Rectification, OlderRigFilesReadTheSame) {
  const StereoRig rig = make_rig(kCases[2]);
  testing::TempDir dir("rectification_old_file");
  write_rig(rig, dir.path() / "rig.yaml");
  // A version-1 file: no format or version key, and another rectification (stereoRectify's) in R1.
  std::ifstream in(dir.path() / "rig.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const std::string key : {"format: ", "version: "}) {
    const auto at = text.find(key);
    text.erase(at, text.find('\n', at) + 1 - at);
  }
  const auto r1 = text.find("data: [", text.find("R1:")) + 8;
  text.replace(r1, text.find(',', r1) - r1, "0.5");
  std::ofstream(dir.path() / "old.yaml") << text;
  const StereoRig back = read_rig(dir.path() / "old.yaml");
  EXPECT_LE(cv::norm(back.rect_from_cam, rig.rect_from_cam, cv::NORM_INF), 1e-12);
  EXPECT_LE(cv::norm(back.rect_proj_image_from_rect, rig.rect_proj_image_from_rect, cv::NORM_INF),
            1e-9 * cv::norm(rig.rect_proj_image_from_rect, cv::NORM_INF));
}

TEST(Rectification, DegenerateRigsNameTheKey) {
  const auto expect_error = [](StereoRig rig, const std::string& key) {
    try {
      rectify_rig(rig);
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("key '" + key + "'"), std::string::npos) << error.what();
    }
  };
  StereoRig rig = make_rig(kCases[0]);
  rig.proj_from_cam_translation_mm = cv::Mat::zeros(3, 1, CV_64F);
  expect_error(rig, "T");
  rig = make_rig(kCases[0]);
  rig.proj_from_cam_rotation = cv::Mat::eye(3, 3, CV_64F);
  rig.proj_from_cam_translation_mm =
      (cv::Mat_<double>(3, 1) << 0.0, 0.0, -150.0);  // the projector straight ahead of the camera
  expect_error(rig, "T");
  rig = make_rig(kCases[0]);
  rig.projector_matrix.at<double>(0, 0) = -1.0;
  expect_error(rig, "projector_matrix");
}

}  // namespace
}  // namespace rfrecon::calib
