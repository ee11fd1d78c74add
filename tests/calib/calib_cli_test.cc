// `rfrecon calibrate` and `calibrate-camera` on bad input: documented exit codes, messages naming the problem, and
// no calibration file left behind.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "host/cli/exit_codes.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kPoses = fs::path(RFRECON_FIXTURES_DIR) / "checkerboard-poses" / "capture";

using rfrecon::testing::run_cli;

class CalibrateCliTest : public ::testing::Test {
 protected:
  std::string pose(int i) const { return (kPoses / ("pose_0" + std::to_string(i))).string(); }
  rfrecon::testing::TempDir temp_{"calib_cli"};
  const fs::path out_ = temp_.path();
};

TEST_F(CalibrateCliTest, TooFewPosesIsExit6WithoutRig) {
  const auto result =
      run_cli("calibrate " + pose(0) + " " + pose(1) + " --board 14x9 --square 20 -o " + (out_ / "rig.yaml").string());
  EXPECT_EQ(result.exit_code, kExitProcessing) << result.output;
  EXPECT_THAT(result.output, HasSubstr("at least 3 views"));
  EXPECT_FALSE(fs::exists(out_ / "rig.yaml"));
}

// A board larger than the printed one (14x9 inner corners) is found in no pose.
TEST_F(CalibrateCliTest, BoardFoundNowhereIsExit6WithoutRig) {
  const auto result = run_cli("calibrate " + pose(0) + " " + pose(1) + " " + pose(2) +
                              " --board 16x11 --square 20 -o " + (out_ / "rig.yaml").string());
  EXPECT_EQ(result.exit_code, kExitProcessing) << result.output;
  EXPECT_THAT(result.output, HasSubstr("board not found"));
  EXPECT_FALSE(fs::exists(out_ / "rig.yaml"));
}

// A pose whose capture shows no board (here the cube scene, captured on the same rig) is named, skipped, and the
// calibration goes on with the poses that remain.
TEST_F(CalibrateCliTest, PoseWithoutTheBoardIsNamedAndSkipped) {
  const fs::path cube = fs::path(RFRECON_FIXTURES_DIR) / "cube-anisotropic" / "capture";
  const auto result = run_cli("calibrate " + pose(0) + " " + pose(1) + " " + cube.string() + " " + pose(2) + " " +
                              pose(3) + " --board 14x9 --square 20 -o " + (out_ / "rig.yaml").string());
  EXPECT_EQ(result.exit_code, kExitOk) << result.output;
  EXPECT_THAT(result.output, HasSubstr(cube.string() + ": board not found"));
  EXPECT_THAT(result.output, HasSubstr("pose skipped"));
  EXPECT_TRUE(fs::exists(out_ / "rig.yaml"));
}

TEST_F(CalibrateCliTest, MixedImageSizesIsExit3) {
  fs::create_directories(out_);
  const fs::path small = out_ / "small.png";
  cv::imwrite(small.string(), cv::Mat(100, 120, CV_8U, cv::Scalar(90)));
  const auto result = run_cli("calibrate-camera " + pose(0) + "/000_white.tiff " + small.string() +
                              " --board 14x9 --square 20 -o " + (out_ / "camera.yaml").string());
  EXPECT_EQ(result.exit_code, kExitInput) << result.output;
  EXPECT_THAT(result.output, HasSubstr(small.string()));
  EXPECT_FALSE(fs::exists(out_ / "camera.yaml"));
}

TEST_F(CalibrateCliTest, UnreadableImageIsExit3) {
  fs::create_directories(out_);
  const fs::path broken = out_ / "broken.png";
  std::ofstream(broken) << "not an image";
  const auto result = run_cli("calibrate-camera " + broken.string() + " --board 14x9 --square 20 -o " +
                              (out_ / "camera.yaml").string());
  EXPECT_EQ(result.exit_code, kExitInput) << result.output;
  EXPECT_THAT(result.output, HasSubstr(broken.string()));
  EXPECT_FALSE(fs::exists(out_ / "camera.yaml"));
}

TEST_F(CalibrateCliTest, SquareBoardIsRejected) {
  const auto result = run_cli("calibrate-camera " + pose(0) + "/000_white.tiff --board 6x6 --square 20 -o " +
                              (out_ / "camera.yaml").string());
  EXPECT_EQ(result.exit_code, kExitUsage) << result.output;
  EXPECT_THAT(result.output, HasSubstr("inner corner counts differ"));
}

TEST_F(CalibrateCliTest, UnknownDistortionModelIsExit2) {
  const auto result =
      run_cli("calibrate-camera " + pose(0) + "/000_white.tiff --board 14x9 --square 20 --distortion k4 -o " +
              (out_ / "camera.yaml").string());
  EXPECT_EQ(result.exit_code, kExitUsage) << result.output;
  EXPECT_THAT(result.output, HasSubstr("k4"));
  EXPECT_FALSE(fs::exists(out_ / "camera.yaml"));
}

// Six white frames with the radial model: the tangential coefficients are held at 0 (deviation 0), the others get a
// positive deviation, and the report warns that six poses are too few.
TEST_F(CalibrateCliTest, RadialModelWithFewPosesWarnsAndHoldsTangentialAtZero) {
  std::string images;
  for (int i = 0; i < 6; ++i) images += pose(i) + "/000_white.tiff ";
  const auto result = run_cli("calibrate-camera " + images + "--board 14x9 --square 20 --distortion radial -o " +
                              (out_ / "camera.yaml").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("only 6 poses"));
  cv::FileStorage fs((out_ / "camera.yaml").string(), cv::FileStorage::READ);
  cv::Mat dist;
  cv::Mat dist_std;
  fs["dist_coeffs"] >> dist;
  fs["dist_coeffs_std"] >> dist_std;
  ASSERT_EQ(dist_std.total(), 5u);
  EXPECT_EQ(dist.at<double>(2), 0.0);
  EXPECT_EQ(dist_std.at<double>(2), 0.0);
  EXPECT_EQ(dist_std.at<double>(3), 0.0);
  EXPECT_GT(dist_std.at<double>(0), 0.0);
  std::ifstream report(out_ / "camera_report" / "report.json");
  std::stringstream text;
  text << report.rdbuf();
  EXPECT_THAT(text.str(), HasSubstr("only 6 poses"));
  EXPECT_TRUE(fs::exists(out_ / "camera_report" / "residuals_camera.png"));
  EXPECT_TRUE(fs::exists(out_ / "camera_report" / "coverage_camera.png"));
}

TEST_F(CalibrateCliTest, EvaluateRigNeverWritesOverAnInput) {
  fs::create_directories(out_);
  const fs::path rig = out_ / "rig.yaml";
  fs::copy_file(kPoses.parent_path() / "truth" / "rig.yaml", rig);
  const auto before = fs::file_size(rig);
  const auto result =
      run_cli("evaluate-rig " + rig.string() + " --truth " + rig.string() + " -o " + rig.string() + " --force");
  EXPECT_EQ(result.exit_code, kExitUsage) << result.output;
  EXPECT_THAT(result.output, HasSubstr("is also an input"));
  EXPECT_EQ(fs::file_size(rig), before);
}

// The corner comparison needs both files; a corners file that is not calibrate's, or a view the truth lacks, is an
// input error naming the file.
TEST_F(CalibrateCliTest, EvaluateRigCornerFilesAreChecked) {
  fs::create_directories(out_);
  const fs::path truth = kPoses.parent_path() / "truth";
  const std::string rigs = (truth / "rig.yaml").string() + " --truth " + (truth / "rig.yaml").string();
  const std::string board_poses = (truth / "board_poses.json").string();
  auto result = run_cli("evaluate-rig " + rigs + " --board-poses " + board_poses);
  EXPECT_EQ(result.exit_code, kExitUsage) << result.output;
  EXPECT_THAT(result.output, HasSubstr("--corners and --board-poses go together"));

  const fs::path corners = out_ / "corners.json";
  std::ofstream(corners) << R"({"views": [{"name": "pose_99", "camera_px": [], "projector_px": []}]})";
  result = run_cli("evaluate-rig " + rigs + " --corners " + corners.string() + " --board-poses " + board_poses);
  EXPECT_EQ(result.exit_code, kExitInput) << result.output;
  EXPECT_THAT(result.output, HasSubstr("view 'pose_99' is not in"));

  std::ofstream(corners) << R"({"views": [{"name": "pose_00", "camera_px": [[1, 2, 3]], "projector_px": []}]})";
  result = run_cli("evaluate-rig " + rigs + " --corners " + corners.string() + " --board-poses " + board_poses);
  EXPECT_EQ(result.exit_code, kExitInput) << result.output;
  EXPECT_THAT(result.output, HasSubstr(corners.string() + ": camera_px must be an array of [x, y] points"));
}

}  // namespace
}  // namespace rfrecon::cli
