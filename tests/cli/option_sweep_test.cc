// Every documented option range, both ends, runs on PoCL or is refused up front; and every input of every command
// that is not a regular file (a FIFO, a device, a directory) is refused by name without blocking (docs/cli.md).
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include "host/cli/exit_codes.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::cli {
namespace {

namespace fs = std::filesystem;
using rfrecon::testing::CliResult;
using rfrecon::testing::run_cli;
using ::testing::AnyOf;
using ::testing::HasSubstr;

// A command that would wait on a FIFO is stopped by `timeout` (exit 124): the assertions then fail instead of hanging.
CliResult run_bounded(const std::string& arguments) { return run_cli("-q " + arguments, "timeout 120"); }

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

// One small rendered cube (96x80 camera, 96x72 projector), its T at K = 8 and 64, and the truth rig, shared by the
// tests of this file.
class OptionSweepTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new rfrecon::testing::TempDir("option_sweep");
    const auto render =
        run_cli("-q simulate --scene cube-anisotropic --camera 96x80 --projector 96x72 -o " + quoted(scan()));
    ASSERT_EQ(render.exit_code, kExitOk) << render.output;
    for (const int k : {8, 64}) {
      const auto transport = run_cli("-q transport " + quoted(capture()) + " -k " + std::to_string(k) + " -o " +
                                     quoted(transport_file(k)));
      ASSERT_EQ(transport.exit_code, kExitOk) << transport.output;
    }
    const auto reconstruct = run_cli("-q reconstruct " + quoted(transport_file(8)) + " --calib " + quoted(rig()) +
                                     " -o " + quoted(reconstruction()));
    ASSERT_EQ(reconstruct.exit_code, kExitOk) << reconstruct.output;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }

  static fs::path path(const std::string& name) { return dir_->path() / name; }
  static fs::path scan() { return path("scan"); }
  static fs::path capture() { return scan() / "capture"; }
  static fs::path rig() { return scan() / "truth" / "rig.yaml"; }
  static fs::path transport_file(int k) { return path("T" + std::to_string(k) + ".h5"); }
  static fs::path reconstruction() { return path("reconstruction"); }

  // A copy of `directory` whose `file` is a FIFO.
  static fs::path copy_with_fifo(const fs::path& directory, const std::string& file) {
    const fs::path copy = path(directory.filename().string() + "_fifo_" + fs::path(file).stem().string());
    fs::copy(directory, copy, fs::copy_options::recursive);
    fs::remove(copy / file);
    EXPECT_EQ(::mkfifo((copy / file).c_str(), 0600), 0) << copy / file;
    return copy;
  }

  // A fresh output path for one run.
  static std::string output(const std::string& name) { return quoted(path("out_" + name)); }

  // A FIFO with no writer: opening it for reading would wait forever.
  static fs::path fifo(const std::string& name) {
    const fs::path file = path(name);
    EXPECT_EQ(::mkfifo(file.c_str(), 0600), 0) << file;
    return file;
  }

  static rfrecon::testing::TempDir* dir_;
};

rfrecon::testing::TempDir* OptionSweepTest::dir_ = nullptr;

// Kernel-sizing options: K over its whole range on both entries (the compression's private arrays grow with K: the
// work-group must shrink with them on a CPU runtime), and the readers and deflate levels at their ends.
TEST_F(OptionSweepTest, TransportRunsAtEveryEndOfItsRanges) {
  int run = 0;
  for (const std::string options : {"-k 1 --entry ndrange", "-k 64 --entry ndrange", "-k 1 --entry single",
                                    "-k 64 --entry single", "--readers 1 --deflate 0", "--readers 64 --deflate 9",
                                    "--white-threshold 0 --noise-threshold 0 --black-threshold 0"}) {
    const auto result =
        run_bounded("transport " + quoted(capture()) + " " + options + " -o " + output("t" + std::to_string(run++)));
    EXPECT_EQ(result.exit_code, kExitOk) << options << "\n" << result.output;
  }
  // The thresholds' top end (half of full scale) leaves nothing of this scan: refused with the reason, by name.
  for (const std::string option : {"--black-threshold", "--white-threshold", "--noise-threshold"}) {
    const auto result =
        run_bounded("transport " + quoted(capture()) + " " + option + " 0.5 -o " + output("t" + std::to_string(run++)));
    EXPECT_THAT(result.exit_code, AnyOf(kExitOk, kExitInput, kExitProcessing)) << option << "\n" << result.output;
    if (result.exit_code != kExitOk) {
      EXPECT_THAT(result.output, AnyOf(HasSubstr(option), HasSubstr("black threshold"))) << result.output;
    }
  }
}

TEST_F(OptionSweepTest, ProductsAndDepthRunOnTheLargestK) {
  EXPECT_EQ(run_bounded("dual " + quoted(transport_file(64)) + " -o " + output("dual64.png")).exit_code, kExitOk);
  for (const std::string method : {"triangulate", "integrate", "fused"}) {
    for (const std::string entry : {"ndrange", "single"}) {
      const auto result =
          run_bounded("reconstruct " + quoted(transport_file(64)) + " --calib " + quoted(rig()) + " --method " +
                      method + " --entry " + entry + " -o " + output("r64_" + method + entry));
      EXPECT_EQ(result.exit_code, kExitOk) << method << " " << entry << "\n" << result.output;
    }
  }
}

// Each reconstruct option at both ends of the range docs/cli.md gives, one at a time, on the fused method (which
// runs the triangulation, the integration and the fusion).
TEST_F(OptionSweepTest, ReconstructRunsAtBothEndsOfEveryRange) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> ranges = {
      {"--epipolar-tolerance", {"0.01", "1000"}},
      {"--saturation", {"0.1", "1000"}},
      {"--edge-relative", {"0.1", "1000"}},
      {"--edge-footprint", {"0", "10"}},
      {"--jump", {"0.001", "1000"}},
      {"--crease", {"1", "180"}},
      {"--passes", {"1", "20"}},
      {"--iterations", {"1", "20"}},
      {"--sigma-disparity", {"0.0001", "100"}},
      {"--sigma-step", {"0.0001", "100"}},
      {"--sigma-samples", {"0", "64"}},
  };
  int run = 0;
  for (const auto& [option, ends] : ranges) {
    for (const auto& value : ends) {
      const auto result =
          run_bounded("reconstruct " + quoted(transport_file(8)) + " --calib " + quoted(rig()) + " --method fused " +
                      option + " " + value + " -o " + output("r" + std::to_string(run++)));
      EXPECT_EQ(result.exit_code, kExitOk) << option << " " << value << "\n" << result.output;
    }
  }
}

// Just outside each range: exit 2 from the parser, naming the option, before anything runs.
TEST_F(OptionSweepTest, ValuesOutsideTheRangesAreUsageErrors) {
  const std::string reconstruct =
      "reconstruct " + quoted(transport_file(8)) + " --calib " + quoted(rig()) + " -o " + output("refused") + " ";
  const std::string transport = "transport " + quoted(capture()) + " -o " + output("refused.h5") + " ";
  for (const std::string& arguments :
       {reconstruct + "--epipolar-tolerance 0.001", reconstruct + "--saturation 0.05",
        reconstruct + "--edge-relative 2000", reconstruct + "--edge-footprint 11", reconstruct + "--jump 0",
        reconstruct + "--crease 0.5", reconstruct + "--passes 21", reconstruct + "--iterations 0",
        reconstruct + "--sigma-disparity 1e-30", reconstruct + "--sigma-step 1e30", transport + "-k 65",
        transport + "-k 0", transport + "--black-threshold 0.6", transport + "--noise-threshold -1",
        transport + "--white-threshold nan", "patterns --projector 64x48 --dot-spacing 1 -o " + output("patterns"),
        "simulate --scene plane-lambert --dot-spacing 65 -o " + output("sim")}) {
    const auto result = run_bounded(arguments);
    EXPECT_EQ(result.exit_code, kExitUsage) << arguments << "\n" << result.output;
  }
  EXPECT_FALSE(fs::exists(path("out_refused")));
  EXPECT_FALSE(fs::exists(path("out_patterns")));
}

// Every file input of every command given as a FIFO with no writer, a character device or a directory: exit 3 naming
// it, at once. (`timeout` turns a command that would wait into exit 124, which the test reports.)
TEST_F(OptionSweepTest, InputsThatAreNotRegularFilesAreRefusedByName) {
  const fs::path pipe = fifo("pipe");
  const fs::path directory = path("a_directory");
  fs::create_directories(directory);
  const std::string t8 = quoted(transport_file(8));

  for (const fs::path& bad : {pipe, fs::path("/dev/zero"), directory}) {
    const std::string in = quoted(bad);
    const std::vector<std::string> commands = {
        "dual " + in + " -o " + output("dual.png"),
        "reconstruct " + in + " --calib " + quoted(rig()) + " -o " + output("rec"),
        "reconstruct " + t8 + " --calib " + in + " -o " + output("rec"),
        "calibrate-camera " + in + " --board 9x6 --square 30 -o " + output("camera.yaml"),
        "evaluate-rig " + in + " --truth " + quoted(rig()),
        "evaluate-rig " + quoted(rig()) + " --truth " + in,
        "simulate --scene " + in + " -o " + output("sim"),
    };
    for (const auto& arguments : commands) {
      const auto result = run_bounded(arguments);
      EXPECT_EQ(result.exit_code, kExitInput) << arguments << "\n" << result.output;
      EXPECT_THAT(result.output, HasSubstr(bad.string())) << arguments;
    }
  }
  // A capture whose manifest, and one whose white frame, is a FIFO.
  for (const fs::path& bad_capture :
       {copy_with_fifo(capture(), "manifest.json"), copy_with_fifo(capture(), "000_white.tiff")}) {
    for (const std::string command : {"transport", "check"}) {
      const std::string arguments =
          command + " " + quoted(bad_capture) + (command == "transport" ? " -o " + output("bad.h5") : "");
      const auto result = run_bounded(arguments);
      EXPECT_THAT(result.exit_code, AnyOf(kExitInput, kExitCheck)) << arguments << "\n" << result.output;
      EXPECT_THAT(result.output, HasSubstr("FIFO")) << arguments;
    }
  }
  // Files inside the directories `evaluate` reads: the reconstruction's depth map, the truth's depth and objects.
  const fs::path truth = scan() / "truth";
  for (const auto& [reconstruction_dir, truth_dir] :
       {std::pair{copy_with_fifo(reconstruction(), "depth.tiff"), truth},
        std::pair{reconstruction(), copy_with_fifo(truth, "depth.tiff")},
        std::pair{reconstruction(), copy_with_fifo(truth, "objects.json")}}) {
    const std::string arguments =
        "evaluate " + quoted(reconstruction_dir) + " --truth " + quoted(truth_dir) + " -o " + output("report.json");
    const auto result = run_bounded(arguments);
    EXPECT_EQ(result.exit_code, kExitInput) << arguments << "\n" << result.output;
    EXPECT_THAT(result.output, HasSubstr("FIFO")) << arguments;
  }
}

}  // namespace
}  // namespace rfrecon::cli
