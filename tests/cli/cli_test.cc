// The command-line tool's documented exit codes and messages (docs/cli.md), checked by running the built binary.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "host/cli/exit_codes.h"
#include "tests/common/run_cli.h"
#include "tests/common/scoped_env.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::cli {
namespace {

using ::testing::HasSubstr;

using rfrecon::testing::run_cli;

TEST(CliTest, UnknownDeviceNameIsExitCode4WithTheDeviceList) {
  const auto result = run_cli("devices --devices no-such-device");
  EXPECT_EQ(result.exit_code, kExitNoDevice);
  EXPECT_THAT(result.output, HasSubstr("no OpenCL device matches 'no-such-device'"));
  EXPECT_THAT(result.output, HasSubstr("available devices:"));
}

TEST(CliTest, EnvironmentSelectionIsHonoured) {
  const auto result = run_cli("selfcheck --size 64 2>&1; RFRECON_DEVICES=nothing-here " RFRECON_CLI_PATH " selfcheck");
  EXPECT_EQ(result.exit_code, kExitNoDevice);
  EXPECT_THAT(result.output, HasSubstr("OK"));
  EXPECT_THAT(result.output, HasSubstr("'nothing-here'"));
}

TEST(CliTest, BadUsageIsExitCode2) {
  EXPECT_EQ(run_cli("").exit_code, kExitUsage);
  EXPECT_EQ(run_cli("no-such-command").exit_code, kExitUsage);
  EXPECT_EQ(run_cli("selfcheck --size 0").exit_code, kExitUsage);
}

TEST(CliTest, DevicesJsonListsTheFields) {
  const auto result = run_cli("devices --json");
  ASSERT_EQ(result.exit_code, kExitOk) << result.output;
  for (const char* key : {"\"platform\"", "\"compute_units\"", "\"global_mem_bytes\"", "\"opencl_c_version\"",
                          "\"fp64\"", "\"fp16\"", "\"programs\": \"source\"", "\"entry\": \""}) {
    EXPECT_THAT(result.output, HasSubstr(key));
  }
}

// The program cache's stored binaries go; anything else in the directory stays.
TEST(CliTest, DevicesClearCacheRemovesTheStoredPrograms) {
  const rfrecon::testing::TempDir dir("clear_cache");
  std::ofstream(dir.path() / "0123456789abcdef.clbin") << "binary";
  std::ofstream(dir.path() / "notes.txt") << "kept";
  const rfrecon::testing::ScopedEnv store("RFRECON_PROGRAM_CACHE", dir.path().c_str());
  const auto result = run_cli("devices --clear-cache");
  ASSERT_EQ(result.exit_code, kExitOk) << result.output;
  EXPECT_THAT(result.output, HasSubstr(dir.path().string() + ", 1 stored program removed"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "0123456789abcdef.clbin"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "notes.txt"));
}

TEST(CliTest, CommandLineMistakesAreExitCode2) {
  for (const char* arguments :
       {"selfcheck --devices ''", "selfcheck --size 100000000000", "simulate --scene cube-anisotropic",
        "simulate -o /tmp/rfrecon-cli-no-scene", "calibrate-camera x.png --board 9x6 --square nan -o c.yaml",
        "patterns --projector 100000x100000 -o /tmp/rfrecon-cli-patterns", "patterns --projector 64x48 -o /dev/null",
        "patterns --projector 64x48 --dot-spacing 100000 -o /tmp/rfrecon-cli-patterns",
        "reconstruct T.h5 --calib rig.yaml --epipolar-tolerance inf -o /tmp/rfrecon-cli-out",
        "transport /tmp -o /tmp/rfrecon-cli-T.h5 --tile-timeout 1",
        "transport /tmp -o /tmp/rfrecon-cli-T.h5 --devices ,", "transport /tmp -o /tmp/rfrecon-cli-T.h5 --entry fast",
        "transport /tmp -o /tmp/rfrecon-cli-T.h5 --readers 0", "transport /tmp -o /tmp/rfrecon-cli-T.h5 --deflate 10",
        "reconstruct T.h5 --calib rig.yaml --entry single,,ndrange -o /tmp/rfrecon-cli-out"}) {
    const auto result = run_cli(arguments);
    EXPECT_EQ(result.exit_code, kExitUsage) << arguments << "\n" << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists("/tmp/rfrecon-cli-patterns"));
}

TEST(CliTest, MissingInputsAreExitCode3AndUnwritableOutputsExitCode8) {
  const auto missing = run_cli("transport /nonexistent/capture -o /tmp/rfrecon-cli-T.h5");
  EXPECT_EQ(missing.exit_code, kExitInput) << missing.output;
  EXPECT_THAT(missing.output, HasSubstr("/nonexistent/capture"));
  const auto unwritable = run_cli("patterns --projector 64x48 -o /proc/rfrecon-patterns");
  EXPECT_EQ(unwritable.exit_code, kExitOutput) << unwritable.output;
  EXPECT_THAT(unwritable.output, HasSubstr("/proc/rfrecon-patterns"));
}

// SIGTERM during a long run: exit 128 + 15, and the staging directory it was writing is gone.
TEST(CliTest, ASignalRemovesTheRunsTemporaries) {
  const rfrecon::testing::TempDir dir("cli_signal");
  const std::filesystem::path out = dir.path() / "render";
  const pid_t child = ::fork();
  if (child == 0) {
    ::execl(RFRECON_CLI_PATH, RFRECON_CLI_PATH, "-q", "simulate", "--scene", "cube-anisotropic", "--camera",
            "1280x1024", "-o", out.c_str(), nullptr);
    ::_exit(127);
  }
  bool staging_seen = false;
  for (int wait_ms = 0; wait_ms < 20000 && !staging_seen; wait_ms += 20) {
    ::usleep(20000);
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
      staging_seen = staging_seen || entry.path().filename().string().find(".staging-") != std::string::npos;
    }
  }
  ::kill(child, SIGTERM);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(staging_seen);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace rfrecon::cli
