// The commands that run kernels use every selected device and report per-stage, per-device shares in --summary;
// failover through RFRECON_INJECT_FAULT, a hung device dropped after RFRECON_TILE_TIMEOUT; every device failing or
// hanging exits with the OpenCL code (5).
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "host/capture/protocol.h"
#include "host/cl/device_selection.h"
#include "host/cli/exit_codes.h"
#include "host/sched/fault.h"
#include "host/sched/watchdog.h"
#include "tests/common/devices.h"
#include "tests/common/run_cli.h"
#include "tests/sched/test_support.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon::sched {
namespace {

namespace testing = transport::testing;
using rfrecon::testing::run_cli;

class SchedCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ::unsetenv(kInjectFaultEnv);
    ::unsetenv(kTileTimeoutEnv);
    testing::SceneOptions options;
    options.camera_size = {24, 20};
    options.projector_size = {16, 12};
    const auto scene = testing::make_plane_scene(options);
    const auto sequence = capture::make_protocol({options.projector_size, 3});
    testing::write_capture(capture_, scene, sequence, 3, testing::render_frames(scene, sequence, 3, 1.0, 7));
  }
  void TearDown() override {
    ::unsetenv(kInjectFaultEnv);
    ::unsetenv(kTileTimeoutEnv);
  }

  std::string transport_args() const {
    return "transport " + capture_.string() + " -o " + (dir_.path() / "T.h5").string() + " --summary " +
           (dir_.path() / "summary.json").string() + " --force";
  }
  // Runs the transport once, so that the kernel builds of the next run come from PoCL's cache: with a short tile
  // timeout, a slow build would be taken as a hang, and its thread, still building, would outlive the command's
  // objects (docs/scheduler.md, "What it cannot fence").
  void warm_kernel_cache() const { ASSERT_EQ(run_cli(transport_args()).exit_code, cli::kExitOk); }
  static constexpr const char* kShortTimeout = "2";  // seconds: cached builds take 0.2 to 0.5 s, more under load

  nlohmann::json summary() const {
    std::ifstream file(dir_.path() / "summary.json");
    return nlohmann::json::parse(file);
  }

  testing::TempDir dir_{"sched_cli"};
  std::filesystem::path capture_ = dir_.path() / "capture";
  std::size_t devices_ = cl::open_devices("").size();
};

TEST_F(SchedCliTest, TransportSummaryHasPerStageDeviceShares) {
  const auto result = run_cli(transport_args());
  ASSERT_EQ(result.exit_code, cli::kExitOk) << result.output;
  EXPECT_NE(result.output.find("share"), std::string::npos) << result.output;  // the table at the end
  const auto json = summary();
  ASSERT_TRUE(json.contains("schedule"));
  std::vector<std::string> stages;
  for (const auto& stage : json["schedule"]) {
    stages.push_back(stage["stage"]);
    ASSERT_EQ(stage["devices"].size(), devices_);
    double shares = 0.0;
    for (const auto& device : stage["devices"]) shares += device["share"].get<double>();
    EXPECT_NEAR(shares, 1.0, 1e-9);  // shares are fractions of the stage's items
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"decode", "compress", "finalize"}));
  EXPECT_TRUE(json["stage_seconds"].contains("decode"));
}

// single,ndrange,single,... with one word per selected device (or one more).
std::string entry_list(std::size_t words) {
  std::string list;
  for (std::size_t i = 0; i < words; ++i) list += std::string(i == 0 ? "" : ",") + (i % 2 == 0 ? "single" : "ndrange");
  return list;
}

TEST_F(SchedCliTest, EntryListGivesEachDeviceItsEntryAndTheSummaryNamesIt) {
  const auto result = run_cli(transport_args() + " --entry " + entry_list(devices_));
  ASSERT_EQ(result.exit_code, cli::kExitOk) << result.output;
  EXPECT_NE(result.output.find("(entry single)"), std::string::npos) << result.output;  // the start-up log
  const nlohmann::json written = summary();  // named: a range-for over summary()["schedule"] would outlive it
  for (const auto& stage : written.at("schedule")) {
    ASSERT_EQ(stage["devices"].size(), devices_);
    for (std::size_t i = 0; i < devices_; ++i) {
      EXPECT_EQ(stage["devices"][i]["entry"], i % 2 == 0 ? "single" : "ndrange") << stage["stage"] << " device " << i;
    }
  }
}

TEST_F(SchedCliTest, EntryListOfAnotherLengthThanTheDevicesIsExitCode2BeforeAnyWork) {
  const std::string counts = std::to_string(devices_ + 1) + " entries for " + std::to_string(devices_) +
                             " selected device" + (devices_ == 1 ? "" : "s");
  const auto transport = run_cli(transport_args() + " --entry " + entry_list(devices_ + 1));
  EXPECT_EQ(transport.exit_code, cli::kExitUsage) << transport.output;
  EXPECT_NE(transport.output.find(counts), std::string::npos) << transport.output;
  EXPECT_FALSE(std::filesystem::exists(dir_.path() / "T.h5"));
  // Checked before the inputs are read: missing files would be exit 3.
  const auto reconstruct = run_cli("reconstruct " + (dir_.path() / "missing.h5").string() + " --calib " +
                                   (dir_.path() / "missing.yaml").string() + " -o " + (dir_.path() / "out").string() +
                                   " --entry " + entry_list(devices_ + 1));
  EXPECT_EQ(reconstruct.exit_code, cli::kExitUsage) << reconstruct.output;
  EXPECT_NE(reconstruct.output.find(counts), std::string::npos) << reconstruct.output;
}

TEST_F(SchedCliTest, TransportCompletesWhenADeviceFailsAndReportsIt) {
  if (devices_ < 2) GTEST_SKIP() << rfrecon::testing::kNeedTwoDevices;
  ::setenv(kInjectFaultEnv, "0:3", 1);
  const auto result = run_cli(transport_args());
  ASSERT_EQ(result.exit_code, cli::kExitOk) << result.output;
  EXPECT_NE(result.output.find("failed"), std::string::npos) << result.output;  // the warning
  std::size_t failures = 0;
  const auto json = summary();
  for (const auto& stage : json["schedule"]) failures += stage["failures"].size();
  EXPECT_EQ(failures, 1u);
}

TEST_F(SchedCliTest, EveryDeviceFailingExitsWithTheOpenClCodeAndWritesNothing) {
  ::setenv(kInjectFaultEnv, "*:1", 1);
  const auto result = run_cli(transport_args());
  EXPECT_EQ(result.exit_code, cli::kExitOpenCl) << result.output;
  EXPECT_NE(result.output.find("every selected device failed"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(dir_.path() / "T.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir_.path() / "summary.json"));
}

TEST_F(SchedCliTest, TransportCompletesWhenADeviceHangsAndExits) {
  if (devices_ < 2) GTEST_SKIP() << rfrecon::testing::kNeedTwoDevices;
  warm_kernel_cache();
  ::setenv(kInjectFaultEnv, "hang:1:3", 1);
  ::setenv(kTileTimeoutEnv, kShortTimeout, 1);
  const auto result = run_cli(transport_args());  // returns: the hung thread does not keep the process alive
  ASSERT_EQ(result.exit_code, cli::kExitOk) << result.output;
  EXPECT_NE(result.output.find("tile timeout"), std::string::npos) << result.output;  // the warning
  std::vector<nlohmann::json> failures;
  const auto json = summary();
  for (const auto& stage : json["schedule"])
    failures.insert(failures.end(), stage["failures"].begin(), stage["failures"].end());
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_EQ(failures[0]["device"], 1);
  EXPECT_EQ(failures[0]["timed_out"], true);
}

TEST_F(SchedCliTest, EveryDeviceHangingExitsWithTheOpenClCode) {
  if (rfrecon::testing::hangs_untimed(cl::open_devices(""))) GTEST_SKIP() << rfrecon::testing::kHangsUntimed;
  warm_kernel_cache();
  ::setenv(kInjectFaultEnv, "hang:*:2", 1);
  ::setenv(kTileTimeoutEnv, kShortTimeout, 1);
  const auto result = run_cli(transport_args());
  EXPECT_EQ(result.exit_code, cli::kExitOpenCl) << result.output;
  EXPECT_NE(result.output.find("every selected device failed"), std::string::npos) << result.output;
}

TEST_F(SchedCliTest, DualSummaryHasTheDualStage) {
  ASSERT_EQ(run_cli(transport_args()).exit_code, cli::kExitOk);
  const auto result =
      run_cli("dual " + (dir_.path() / "T.h5").string() + " -o " + (dir_.path() / "dual.tiff").string() +
              " --summary " + (dir_.path() / "dual.json").string());
  ASSERT_EQ(result.exit_code, cli::kExitOk) << result.output;
  std::ifstream file(dir_.path() / "dual.json");
  const auto json = nlohmann::json::parse(file);
  ASSERT_EQ(json["schedule"].size(), 1u);
  EXPECT_EQ(json["schedule"][0]["stage"], "dual");
  EXPECT_EQ(json["schedule"][0]["items"], 16 * 12);  // every projector pixel once
}

}  // namespace
}  // namespace rfrecon::sched
