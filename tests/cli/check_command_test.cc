// `rfrecon check` on rendered captures: exit 0 on a clean one, 9 with the cause on a gamma 2.2 capture declared
// linear (in the output and in --json), and the usage and input errors of docs/cli.md; the warnings of `transport` and
// `calibrate`.
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "host/cli/exit_codes.h"
#include "host/core/json_file.h"
#include "tests/capture/rendered_capture.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::cli {
namespace {

using rfrecon::testing::run_cli;
using ::testing::HasSubstr;

// A capture rendered with the camera's gamma 2.2 on, its manifest declaring a linear camera.
void render_gamma_declared_linear(const std::filesystem::path& dir) {
  auto manifest = rfrecon::testing::render_capture(dir, [](sim::Scene& scene) { scene.capture.response_gamma = 2.2; });
  manifest.camera_response = "linear";
  capture::write_manifest(manifest, dir);
}

TEST(CheckCommandTest, CleanCapturePassesAndGammaDeclaredLinearFails) {
  const rfrecon::testing::TempDir clean("check_cli_clean");
  (void)rfrecon::testing::render_capture(clean.path(), [](sim::Scene&) {});
  const auto passed = run_cli("check " + clean.path().string());
  EXPECT_EQ(passed.exit_code, kExitOk) << passed.output;
  EXPECT_THAT(passed.output, HasSubstr("no problem found"));

  const rfrecon::testing::TempDir gamma("check_cli_gamma");
  render_gamma_declared_linear(gamma.path());
  const rfrecon::testing::TempDir out("check_cli_out");
  const auto json_file = out.path() / "checks.json";
  const auto failed = run_cli("check " + gamma.path().string() + " --json " + json_file.string());
  EXPECT_EQ(failed.exit_code, kExitCheck) << failed.output;
  EXPECT_THAT(failed.output, HasSubstr("camera_response"));
  const auto json = read_json_file(json_file);
  ASSERT_EQ(json.at("findings").size(), 1u) << json.dump(2);
  EXPECT_EQ(json.at("findings")[0].at("check"), "response");
  EXPECT_NEAR(json.at("response_gamma").get<double>(), 2.2, 0.11);
  // An existing --json needs --force.
  EXPECT_EQ(run_cli("check " + gamma.path().string() + " --json " + json_file.string()).exit_code, kExitUsage);
}

// `transport` runs the same checks: a warning naming the cause, and the findings in --summary; T.h5 is still written.
TEST(CheckCommandTest, TransportWarnsAndRecordsTheFindings) {
  const rfrecon::testing::TempDir capture("check_cli_transport");
  render_gamma_declared_linear(capture.path());
  const rfrecon::testing::TempDir out("check_cli_transport_out");
  const auto summary = out.path() / "summary.json";
  const auto result = run_cli("transport " + capture.path().string() + " -o " + (out.path() / "T.h5").string() +
                              " --summary " + summary.string() + " --devices cpu");
  ASSERT_EQ(result.exit_code, kExitOk) << result.output;
  EXPECT_THAT(result.output, HasSubstr("warning: " + capture.path().string() + ": the camera's response looks like"));
  const auto json = read_json_file(summary).at("capture_checks");
  ASSERT_EQ(json.at("findings").size(), 1u) << json.dump(2);
  EXPECT_EQ(json.at("findings")[0].at("check"), "response");
  EXPECT_NEAR(json.at("response_gamma").get<double>(), 2.2, 0.11);
}

// `calibrate` runs them on each pose's frames and warns naming the pose (this one shows no board, so the
// calibration itself then fails for want of poses).
TEST(CheckCommandTest, CalibrateWarnsNamingThePose) {
  const rfrecon::testing::TempDir capture("check_cli_calibrate");
  render_gamma_declared_linear(capture.path());
  const rfrecon::testing::TempDir out("check_cli_calibrate_out");
  const auto result = run_cli("calibrate " + capture.path().string() + " --board 14x9 --square 20 -o " +
                              (out.path() / "rig.yaml").string() + " --devices cpu");
  EXPECT_THAT(result.output, HasSubstr("warning: " + capture.path().string() + ": the camera's response looks like"));
}

TEST(CheckCommandTest, UsageAndInputErrors) {
  const rfrecon::testing::TempDir empty("check_cli_empty");
  EXPECT_EQ(run_cli("check " + empty.path().string()).exit_code, kExitInput);
  EXPECT_EQ(run_cli("check " + empty.path().string() + " --bit-depth 12").exit_code, kExitUsage)
      << "--bit-depth is for the opencv-graycode layout";
  EXPECT_EQ(run_cli("check " + empty.path().string() + " --layout opencv-graycode --projector 64x32 --bit-depth 11")
                .exit_code,
            kExitUsage);

  // A frame of the wrong size: exit 3 naming it.
  const rfrecon::testing::TempDir capture("check_cli_bad_frame");
  const auto manifest = rfrecon::testing::render_capture(capture.path(), [](sim::Scene&) {});
  const auto frame = capture.path() / manifest.frames.back().file;
  cv::imwrite(frame.string(), cv::Mat(8, 8, CV_16UC1, cv::Scalar(100)));
  const auto bad = run_cli("check " + capture.path().string());
  EXPECT_EQ(bad.exit_code, kExitInput) << bad.output;
  EXPECT_THAT(bad.output, HasSubstr(frame.string()));
}

}  // namespace
}  // namespace rfrecon::cli
