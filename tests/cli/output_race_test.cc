// Output names at the file system's limit through the built tool (docs/cli.md, "Conventions every command follows"):
// a name of 255 bytes is written like any other and leaves no temporary; a longer one is exit 2 before any work.
// (The races themselves are tests/core/atomic_file_test.cc, made with the before-commit hook.)
#include <filesystem>
#include <iterator>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/cli/exit_codes.h"
#include "host/core/temporaries.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::cli {
namespace {

namespace fs = std::filesystem;
using rfrecon::testing::run_cli;
using ::testing::HasSubstr;

std::size_t entry_count(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(OutputRaceTest, ANameAtTheLimitIsWrittenAndALongerOneIsExit2) {
  const rfrecon::testing::TempDir dir("cli_long_names");
  const std::size_t limit = name_max(dir.path());
  const fs::path longest = dir.path() / std::string(limit, 'p');
  const auto written = run_cli("-q patterns --projector 64x48 -o " + longest.string());
  ASSERT_EQ(written.exit_code, kExitOk) << written.output;
  EXPECT_TRUE(fs::exists(longest / "manifest.json"));
  EXPECT_EQ(entry_count(dir.path()), 1u) << "no temporary left beside it";

  const fs::path too_long = dir.path() / std::string(limit + 1, 'p');
  const auto refused = run_cli("-q patterns --projector 64x48 -o " + too_long.string());
  EXPECT_EQ(refused.exit_code, kExitUsage) << refused.output;
  EXPECT_THAT(refused.output, HasSubstr("is " + std::to_string(limit + 1) + " bytes long"));
  EXPECT_EQ(entry_count(dir.path()), 1u);
}

}  // namespace
}  // namespace rfrecon::cli
