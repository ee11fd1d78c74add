// Output rules against the file system: devices, FIFOs and directories are never written as files, no input is
// replaced (by path, link or hard link), a directory holding an input is never replaced, and --force is needed to
// replace anything that exists.
#include "host/core/output_path.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;

void touch(const fs::path& file, const std::string& text = "input") { std::ofstream(file) << text; }

std::string text_of(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The UsageError message of `check`, or "" when it passes.
template <typename Check>
std::string refusal(Check check) {
  try {
    check();
  } catch (const UsageError& error) {
    return error.what();
  }
  return "";
}

class OutputPathTest : public ::testing::Test {
 protected:
  testing::TempDir temp_{"output_path"};
  const fs::path dir_ = temp_.path();
};

TEST_F(OutputPathTest, OnlyRegularFilesAreWritten) {
  ASSERT_EQ(::mkfifo((dir_ / "fifo").c_str(), 0600), 0);
  fs::create_directory(dir_ / "sub");
  for (const auto& [path, kind] :
       {std::pair{fs::path("/dev/null"), "character device"}, {dir_ / "fifo", "FIFO"}, {dir_ / "sub", "directory"}}) {
    const fs::path output = path;  // structured bindings cannot be captured in C++17
    EXPECT_NE(refusal([&] { check_output_file({output, "-o", true}, {}); }).find(kind), std::string::npos) << output;
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_NE(refusal([&] { check_output_file({"", "-o", true}, {}); }).find("empty"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_file({dir_ / "new/", "-o", true}, {}); }).find("directory"), std::string::npos);
  EXPECT_EQ(refusal([&] { check_output_file({dir_ / "new.h5", "-o", false}, {}); }), "");
}

TEST_F(OutputPathTest, AnExistingFileNeedsForce) {
  touch(dir_ / "out.json");
  EXPECT_NE(refusal([&] {
              check_output_file({dir_ / "out.json", "-o", false}, {});
            }).find("--force"),
            std::string::npos);
  EXPECT_EQ(refusal([&] { check_output_file({dir_ / "out.json", "-o", true}, {}); }), "");
}

TEST_F(OutputPathTest, NoInputIsReplacedEvenWithForceThroughLinksOrAsPartOfADirectory) {
  fs::create_directories(dir_ / "capture");
  touch(dir_ / "capture" / "manifest.json");
  fs::create_hard_link(dir_ / "capture" / "manifest.json", dir_ / "hard");
  fs::create_symlink(dir_ / "capture" / "manifest.json", dir_ / "soft");
  for (const auto& output : {dir_ / "capture" / "manifest.json", dir_ / "capture" / ".." / "capture" / "manifest.json",
                             dir_ / "hard", dir_ / "soft"}) {
    EXPECT_NE(refusal([&] {
                check_output_file({output, "-o", true}, {dir_ / "capture" / "manifest.json"});
              }).find("is also an input"),
              std::string::npos)
        << output;
    EXPECT_NE(refusal([&] {
                check_output_file({output, "-o", true}, {dir_ / "capture"});
              }).find("is also an input"),
              std::string::npos)
        << output << " (input given as its directory)";
  }
  EXPECT_EQ(text_of(dir_ / "capture" / "manifest.json"), "input");
  // A new file beside the inputs is fine.
  EXPECT_EQ(refusal([&] { check_output_file({dir_ / "capture" / "T.h5", "-o", true}, {dir_ / "capture"}); }), "");
}

TEST_F(OutputPathTest, ADirectoryHoldingAnInputIsNeverReplaced) {
  fs::create_directories(dir_ / "scan");
  touch(dir_ / "scan" / "T.h5");
  for (const auto& output : {dir_ / "scan", dir_}) {
    EXPECT_NE(refusal([&] {
                check_output_directory({output, "-o", true}, {dir_ / "scan" / "T.h5"});
              }).find("holds the input"),
              std::string::npos)
        << output;
  }
  EXPECT_NE(refusal([&] {
              check_output_directory({dir_ / "scan", "-o", false}, {});
            }).find("--force"),
            std::string::npos);
  EXPECT_NE(refusal([&] {
              check_output_directory({dir_ / "scan" / "T.h5", "-o", true}, {});
            }).find("not a directory"),
            std::string::npos);
  EXPECT_EQ(refusal([&] {
              check_output_directory({dir_ / "scan" / "out", "-o", false}, {dir_ / "scan" / "T.h5"});
            }),
            "");
}

TEST_F(OutputPathTest, TwoOutputsMayNotOverlap) {
  const OutputPath main{dir_ / "T.h5", "-o"};
  EXPECT_NE(refusal([&] {
              check_distinct_outputs({main, {dir_ / "." / "T.h5", "--summary"}});
            }).find("each other"),
            std::string::npos);
  EXPECT_NE(refusal([&] {
              check_distinct_outputs({{dir_ / "r" / "rig.yaml", "-o"}, {dir_ / "r", "--report"}});
            }).find("each other"),
            std::string::npos);
  EXPECT_EQ(refusal([&] { check_distinct_outputs({main, {dir_ / "summary.json", "--summary"}, {"", "--x"}}); }), "");
}

TEST_F(OutputPathTest, AStagingDirectoryNeverReplacesAFile) {
  touch(dir_ / "file");
  EXPECT_THROW(StagingDirectory(dir_ / "file", true), UsageError);
  EXPECT_EQ(text_of(dir_ / "file"), "input");
}

}  // namespace
}  // namespace rfrecon
