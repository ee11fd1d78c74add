// The rig file (calib/rig.h): exact round trip, rectification that puts corresponding points on one row, and
// errors naming the file and key.
#include <algorithm>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "calib/rig.h"
#include "host/core/errors.h"
#include "sim/builtin_scenes.h"
#include "sim/truth_io.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;

class RigFileTest : public ::testing::Test {
 protected:
  rfrecon::testing::TempDir temp_{"rig_file"};
  const fs::path file_ = temp_.path() / "rig.yaml";
};

double max_difference(const cv::Mat& a, const cv::Mat& b) { return cv::norm(a, b, cv::NORM_INF); }

TEST_F(RigFileTest, RoundTripIsExact) {
  // FileStorage writes doubles with 17 significant digits, so every value must come back bit-exact.
  calib::StereoRig rig = sim::true_rig(sim::builtin_scene("checkerboard-poses"));
  rig.rms = 0.123;
  rig.per_view_errors = {0.1, 0.2, 0.15};
  calib::write_rig(rig, file_);
  const calib::StereoRig back = calib::read_rig(file_);
  EXPECT_EQ(back.camera_size, rig.camera_size);
  EXPECT_EQ(back.projector_size, rig.projector_size);
  for (const auto& [a, b] : {std::pair{back.camera_matrix, rig.camera_matrix},
                             {back.dist_coeffs, rig.dist_coeffs},
                             {back.projector_matrix, rig.projector_matrix},
                             {back.projector_dist_coeffs, rig.projector_dist_coeffs},
                             {back.proj_from_cam_rotation, rig.proj_from_cam_rotation},
                             {back.proj_from_cam_translation_mm, rig.proj_from_cam_translation_mm},
                             {back.essential, rig.essential},
                             {back.fundamental, rig.fundamental},
                             {back.rect_from_cam, rig.rect_from_cam},
                             {back.rect_from_proj, rig.rect_from_proj},
                             {back.rect_cam_image_from_rect, rig.rect_cam_image_from_rect},
                             {back.rect_proj_image_from_rect, rig.rect_proj_image_from_rect},
                             {back.rect_from_disparity, rig.rect_from_disparity}}) {
    EXPECT_EQ(max_difference(a, b), 0.0);
  }
  EXPECT_EQ(back.rms, 0.123);
  EXPECT_EQ(back.per_view_errors, rig.per_view_errors);
  EXPECT_EQ(back.board.cols, 14);
  EXPECT_EQ(back.board.rows, 9);
  EXPECT_EQ(back.board.square_size, 20.0);
}

TEST_F(RigFileTest, RectificationAlignsRowsAndEpipolarGeometryHolds) {
  // A 3D point seen by both devices lands on the same rectified row (to 1e-6 px: exact geometry, no noise), and
  // its two (distorted-then-undistorted) normalised images satisfy x_p^T E x_c = 0.
  const sim::Scene scene = sim::builtin_scene("cube-anisotropic");
  const calib::StereoRig rig = sim::true_rig(scene);
  const cv::Mat rvec_p = [&] {
    cv::Mat v;
    cv::Rodrigues(rig.proj_from_cam_rotation, v);
    return v;
  }();
  for (const cv::Point3d X : {cv::Point3d(0, 0, 600), cv::Point3d(-40, 30, 580), cv::Point3d(50, -35, 650)}) {
    std::vector<cv::Point2d> cam, proj, cam_rect, proj_rect;
    cv::projectPoints(std::vector<cv::Point3d>{X}, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), rig.camera_matrix,
                      rig.dist_coeffs, cam);
    cv::projectPoints(std::vector<cv::Point3d>{X}, rvec_p, rig.proj_from_cam_translation_mm, rig.projector_matrix,
                      rig.projector_dist_coeffs, proj);
    cv::undistortPoints(cam, cam_rect, rig.camera_matrix, rig.dist_coeffs, rig.rect_from_cam,
                        rig.rect_cam_image_from_rect);
    cv::undistortPoints(proj, proj_rect, rig.projector_matrix, rig.projector_dist_coeffs, rig.rect_from_proj,
                        rig.rect_proj_image_from_rect);
    EXPECT_NEAR(cam_rect[0].y, proj_rect[0].y, 1e-6);
    const cv::Mat xc = (cv::Mat_<double>(3, 1) << X.x / X.z, X.y / X.z, 1.0);
    const cv::Mat Xp =
        rig.proj_from_cam_rotation * cv::Mat(cv::Vec3d(X.x, X.y, X.z)) + rig.proj_from_cam_translation_mm;
    const cv::Mat xp = Xp / Xp.at<double>(2);
    EXPECT_NEAR(cv::Mat(xp.t() * rig.essential * xc).at<double>(0), 0.0, 1e-9);
  }
}

TEST_F(RigFileTest, MissingOrMisSizedKeyIsNamed) {
  calib::write_rig(sim::true_rig(sim::builtin_scene("cube-anisotropic")), file_);
  std::string text;
  {
    std::ifstream in(file_);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto expect_error = [&](const std::string& content, const std::string& needle) {
    std::ofstream(file_) << content;
    try {
      calib::read_rig(file_);
      ADD_FAILURE() << "no error for " << needle;
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(needle), std::string::npos) << message;
      EXPECT_NE(message.find(file_.filename().string()), std::string::npos) << message;
    }
  };
  // The file without the block of `key` (its line and the indented lines that follow).
  const auto without = [&](const std::string& key) {
    const auto start = text.find("\n" + key + ":") + 1;
    auto end = text.find("\n", start);
    while (end != std::string::npos && end + 1 < text.size() && text[end + 1] == ' ') end = text.find("\n", end + 1);
    std::string out = text;
    out.erase(start, end + 1 - start);
    return out;
  };
  expect_error(without("R"), "'R'");  // E, F and the rectification are derived from R and T: not required
  expect_error(without("projector_matrix"), "'projector_matrix'");
  std::string bad_t = text;
  const std::string column = "T: !!opencv-matrix\n   rows: 3\n   cols: 1";
  bad_t.replace(bad_t.find(column), column.size(), "T: !!opencv-matrix\n   rows: 1\n   cols: 3");
  expect_error(bad_t, "'T' must be a 3x1");
  EXPECT_THROW(calib::read_rig(file_.string() + ".missing"), InputError);
}

// Sizes and shapes a hostile file could use to make the reader allocate or loop without end are refused first, and
// OpenCV's own parser errors come back as InputError naming the file.
TEST_F(RigFileTest, HostileSizesAndSyntaxAreInputErrors) {
  calib::write_rig(sim::true_rig(sim::builtin_scene("cube-anisotropic")), file_);
  std::string text;
  {
    std::ifstream in(file_);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string out = text;
    const auto at = out.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? out : out.replace(at, from.size(), to);
  };
  const auto camera_size =
      text.substr(text.find("camera_size:"), text.find('\n', text.find("camera_size:")) - text.find("camera_size:"));
  for (const auto& [content, needle] : std::vector<std::pair<std::string, std::string>>{
           {replaced(camera_size, "camera_size: [ 200000000, 2 ]"), "over the limit"},
           {replaced(camera_size, "camera_size: [ 2.0e9, 2 ]"), "integers"},
           {replaced("T: !!opencv-matrix\n   rows: 3\n   cols: 1",
                     "T: !!opencv-matrix\n   rows: 30000\n   cols: 30000"),
            "at most 16 elements"},
           {"%YAML:1.0\n---\n- 1\n- 2\n", "rig.yaml"},
           {"%YAML:1.0\n---\nrms: [\n", "rig.yaml"},
           // OpenCV 4.6's parser never returns on these two (a second document that does not open with "---").
           {"%YAML:1.0\n   ow: 0\nc-a- :\np.\n", "line 2: the first key is indented"},
           {text + "---\n0\n", "line " + std::to_string(std::count(text.begin(), text.end(), '\n') + 1) + ":"},
           {replaced("rms: ", "rms:\t"), "a tab"}}) {
    std::ofstream(file_, std::ios::trunc) << content;
    try {
      calib::read_rig(file_);
      ADD_FAILURE() << "no error for " << needle;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
    }
  }
}

// A distortion model that sends the image border to no finite point (found by fuzzing: the rectified size was NaN
// cast to int) names the key.
TEST_F(RigFileTest, DistortionWithoutFiniteBorderIsNamed) {
  calib::StereoRig rig = sim::true_rig(sim::builtin_scene("cube-anisotropic"));
  rig.projector_dist_coeffs = (cv::Mat_<double>(1, 5) << 0.0, 0.0, 0.0, 2.0, 0.0);
  calib::write_rig(rig, file_);
  try {
    calib::read_rig(file_);
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("'projector_dist_coeffs': the distortion model sends"), std::string::npos)
        << error.what();
  }
}

// The layout check refuses only what cv::FileStorage never writes: the same rig with CRLF line ends, comments (one
// in UTF-8) and blank lines reads back equal (OpenCV itself requires %YAML on the first line).
TEST_F(RigFileTest, LayoutCheckKeepsWhatOpenCvWritesOrReads) {
  const calib::StereoRig rig = sim::true_rig(sim::builtin_scene("cube-anisotropic"));
  calib::write_rig(rig, file_);
  std::string text;
  {
    std::ifstream in(file_);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::string edited;
  for (const char c : text) edited += c == '\n' ? std::string("\r\n") : std::string(1, c);
  edited.insert(edited.find("---"), "# a comment by J\xc3\xb6rg\r\n\r\n");
  edited += "\r\n# the end\r\n";
  std::ofstream(file_, std::ios::trunc | std::ios::binary) << edited;
  const calib::StereoRig back = calib::read_rig(file_);
  EXPECT_EQ(max_difference(back.camera_matrix, rig.camera_matrix), 0.0);
  EXPECT_EQ(max_difference(back.proj_from_cam_translation_mm, rig.proj_from_cam_translation_mm), 0.0);
  EXPECT_EQ(back.camera_size, rig.camera_size);
}

}  // namespace
}  // namespace rfrecon
