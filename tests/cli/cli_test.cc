// The command-line tool's documented exit codes and messages (docs/cli.md), checked by running the built binary.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/cli/exit_codes.h"
#include "tests/common/run_cli.h"

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
                          "\"fp64\"", "\"fp16\"", "\"programs\": \"source\""}) {
    EXPECT_THAT(result.output, HasSubstr(key));
  }
}

}  // namespace
}  // namespace rfrecon::cli
