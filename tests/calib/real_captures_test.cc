// `rfrecon calibrate` on the four real Gray-code captures of ../shared/data/procam-graycode (not part of the
// product; skipped when absent): the stereo RMS stays under the corners-only calibration's of the same poses before the
// joint adjustment (0.3864 px, docs/calibration.md), every gating decision is in report.json and on the console with
// its numbers, and the residual fields have each device's size.
#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "host/cli/exit_codes.h"
#include "host/core/json_file.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::calib {
namespace {

namespace fs = std::filesystem;

const fs::path kCaptures = fs::path(RFRECON_SOURCE_DIR) / ".." / "shared" / "data" / "procam-graycode";
constexpr double kRmsBeforeJointAdjustmentPx = 0.3864;

std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++count;
  return count;
}

TEST(RealCapturesTest, StereoRmsUnderTheCornersOnlyCalibrationsWithEveryGatingDecisionReported) {
  if (!fs::exists(kCaptures / "capture_3")) GTEST_SKIP() << kCaptures << " is absent (not part of the product)";
  rfrecon::testing::TempDir temp("real_captures");
  std::string poses;
  for (int i = 0; i < 4; ++i) poses += " " + (kCaptures / ("capture_" + std::to_string(i))).string();
  const fs::path rig = temp.path() / "rig.yaml";
  const auto result = rfrecon::testing::run_cli("calibrate" + poses +
                                                " --board 9x7 --square 75 --layout opencv-graycode --projector "
                                                "1024x768 -o " +
                                                rig.string());
  ASSERT_EQ(result.exit_code, cli::kExitOk) << result.output;
  const auto report = read_json_file(temp.path() / "rig_report" / "report.json");
  EXPECT_LT(report.at("rms_px").get<double>(), kRmsBeforeJointAdjustmentPx);

  const auto& gating = report.at("gating");
  const auto& decisions = gating.at("decisions");
  EXPECT_FALSE(decisions.empty()) << "corners at one end of the board stand out in two poses";
  EXPECT_EQ(count_of(result.output, "gating: "), decisions.size()) << result.output;
  for (const auto& decision : decisions) {
    const bool dropped = decision.at("action") == "dropped";
    const double threshold = gating.at(dropped ? "corner_z_max" : "pose_z_max").get<double>();
    EXPECT_GT(decision.at("z").get<double>(), threshold) << decision.dump();
    const auto down_weighted = [&](const nlohmann::json& d) {
      return d.at("action") == "down-weighted" && d.at("view") == decision.at("view") &&
             d.at("series") == decision.at("series");
    };
    if (dropped && std::none_of(decisions.begin(), decisions.end(), down_weighted)) {
      // In a pose at full weight the z-score is the residual's against the series' median and sigma.
      const double z = (decision.at("residual_px").get<double>() - decision.at("median_px").get<double>()) /
                       decision.at("sigma_px").get<double>();
      EXPECT_NEAR(decision.at("z").get<double>(), z, 1e-9) << decision.dump();
    }
  }
  // Dropping corners lowers the RMS over the kept ones only.
  EXPECT_GE(report.at("rms_all_corners_px").get<double>(), report.at("rms_px").get<double>());
  for (const auto& [file, size] : {std::pair{"residual_field_camera.png", cv::Size(1280, 1024)},
                                   std::pair{"residual_field_projector.png", cv::Size(1024, 768)}}) {
    const cv::Mat field = cv::imread((temp.path() / "rig_report" / file).string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(field.empty()) << file;
    EXPECT_EQ(field.size(), size) << file;
  }
}

}  // namespace
}  // namespace rfrecon::calib
