// Calibration on real photographs against the reference toolbox: Bouguet's stereo example (../shared/data/
// bouguet-stereo, 14 pairs of 640x480 images of a 9x6-corner board with 30 mm squares), whose published values
// (Calib_Results_left/right/stereo.mat) are the targets. Skipped when the images are absent: they are not part of
// the product. $RFRECON_BOUGUET_DIR overrides the folder.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "calib/board_detection.h"
#include "calib/camera_calibration.h"
#include "calib/stereo_calibration.h"

namespace rfrecon::calib {
namespace {

namespace fs = std::filesystem;
const BoardSpec kBoard{9, 6, 30.0};

fs::path data_dir() {
  if (const char* dir = std::getenv("RFRECON_BOUGUET_DIR")) return dir;
  return fs::path(RFRECON_SOURCE_DIR) / ".." / "shared" / "data" / "bouguet-stereo";
}

// The toolbox's published value and one standard deviation.
struct Published {
  double value;
  double sigma;
};

struct Camera {
  Published fx, fy, cx, cy;
};

// Calib_Results_left.mat and Calib_Results_right.mat (README.md of the data folder). The toolbox's principal point
// is compared as published: its values match OpenCV's pixel-centre convention on these images (checked: shifting
// them by one pixel puts every recipe 0.7 to 0.9 sigma away).
const Camera kLeft{{533.0037, 1.076}, {533.1526, 1.109}, {341.5861, 1.240}, {234.2594, 1.331}};
const Camera kRight{{536.9826, 1.198}, {536.5694, 1.157}, {326.4721, 1.366}, {249.3326, 1.343}};

// Corners of every image of one camera that shows the whole board.
std::vector<BoardView> views_of(const std::string& camera) {
  std::vector<BoardView> views;
  for (int i = 1; i <= 14; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%s%02d.jpg", camera.c_str(), i);
    const cv::Mat image = cv::imread((data_dir() / name).string(), cv::IMREAD_GRAYSCALE);
    if (image.empty()) continue;
    auto corners = find_board_corners(image, kBoard);
    if (!corners.empty()) views.push_back({name, std::move(corners)});
  }
  return views;
}

void expect_within_one_sigma(const cv::Mat& camera_matrix, const Camera& published) {
  EXPECT_NEAR(camera_matrix.at<double>(0, 0), published.fx.value, published.fx.sigma) << "fx";
  EXPECT_NEAR(camera_matrix.at<double>(1, 1), published.fy.value, published.fy.sigma) << "fy";
  EXPECT_NEAR(camera_matrix.at<double>(0, 2), published.cx.value, published.cx.sigma) << "cx";
  EXPECT_NEAR(camera_matrix.at<double>(1, 2), published.cy.value, published.cy.sigma) << "cy";
}

class BouguetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(data_dir() / "left01.jpg")) GTEST_SKIP() << "no Bouguet images in " << data_dir();
  }
};

// Each camera alone, as the toolbox calibrated them (k1 k2 p1 p2, k3 = 0, no skew): intrinsics within one published
// standard deviation, and residuals no larger than the toolbox's (0.13-0.14 px per axis, about 0.19 px as OpenCV's
// RMS over both axes).
TEST_F(BouguetTest, EachCameraMatchesTheToolbox) {
  for (const auto& [name, published] : {std::pair{"left", kLeft}, {"right", kRight}}) {
    SCOPED_TRACE(name);
    const auto views = views_of(name);
    EXPECT_GE(views.size(), 13u) << "boards found";
    const auto result = calibrate_camera(views, kBoard, {640, 480});
    RecordProperty(std::string(name) + "_fx", std::to_string(result.camera_matrix.at<double>(0, 0)));
    RecordProperty(std::string(name) + "_rms_px", std::to_string(result.rms));
    expect_within_one_sigma(result.camera_matrix, published);
    EXPECT_LE(result.rms, 0.20);
  }
}

// The pair through the stereo adjustment (the right camera in the projector's role): the baseline within the
// toolbox's standard deviations of T = (-99.80198, 1.12443, 0.05041) mm +- (0.14200, 0.11352, 0.49773), and the
// adjustment's own standard deviations of T no larger than the toolbox's.
TEST_F(BouguetTest, StereoPoseMatchesTheToolbox) {
  const auto left = views_of("left");
  const auto right = views_of("right");
  std::vector<StereoView> pairs;
  for (const auto& l : left) {
    const std::string partner = "right" + l.name.substr(4);
    for (const auto& r : right) {
      if (r.name != partner) continue;
      // Both detectors number the board from the same end on these images when the first corners are close.
      StereoView view{l.name, l.corners, r.corners, {}};
      if (cv::norm(view.camera_corners.front() - view.projector_corners.front()) >
          cv::norm(view.camera_corners.front() - view.projector_corners.back())) {
        std::reverse(view.projector_corners.begin(), view.projector_corners.end());
      }
      pairs.push_back(std::move(view));
    }
  }
  ASSERT_GE(pairs.size(), 12u);
  const auto result = calibrate_stereo(pairs, kBoard, {640, 480}, {640, 480});
  RecordProperty("stereo_rms_px", std::to_string(result.rig.rms));
  RecordProperty("left_fx_joint", std::to_string(result.rig.camera_matrix.at<double>(0, 0)));
  RecordProperty("right_fx_joint", std::to_string(result.rig.projector_matrix.at<double>(0, 0)));
  RecordProperty("stereo_rms_all_corners_px", std::to_string(result.rms_all_px));
  std::string gating;
  for (const auto& decision : result.gating) gating += decision.describe() + "; ";
  RecordProperty("gating", gating);
  const cv::Vec3d published(-99.80198, 1.12443, 0.05041);
  const cv::Vec3d sigma(0.14200, 0.11352, 0.49773);
  for (int i = 0; i < 3; ++i) {
    RecordProperty("T" + std::to_string(i), std::to_string(result.rig.proj_from_cam_translation_mm.at<double>(i)));
    RecordProperty("T" + std::to_string(i) + "_std",
                   std::to_string(result.rig.uncertainty.proj_from_cam_translation_mm.at<double>(i)));
    EXPECT_NEAR(result.rig.proj_from_cam_translation_mm.at<double>(i), published[i], sigma[i]) << "T[" << i << "]";
    EXPECT_LE(result.rig.uncertainty.proj_from_cam_translation_mm.at<double>(i), sigma[i]) << "sigma of T[" << i << "]";
  }
}

}  // namespace
}  // namespace rfrecon::calib
