// `rfrecon evaluate` end to end: report and error map written where documented, exit codes for bad input.
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/cli/exit_codes.h"
#include "host/outputs/reconstruction_files.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"
#include "tests/evaluation/synthetic_truth.h"

namespace rfrecon::evaluation {
namespace {

namespace fs = std::filesystem;
using rfrecon::testing::run_cli;
using ::testing::HasSubstr;

class EvaluateCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::write_truth(dir_ / "sim");
    write_reconstruction(testing::reconstruction(), {}, dir_ / "out", false);
  }
  rfrecon::testing::TempDir temp_{"evaluate_cli"};
  const fs::path dir_ = temp_.path();
};

TEST_F(EvaluateCliTest, WritesReportAndMapIntoTheReconstructionByDefault) {
  const auto result = run_cli("evaluate " + (dir_ / "out").string() + " --truth " + (dir_ / "sim").string());
  ASSERT_EQ(result.exit_code, cli::kExitOk) << result.output;
  EXPECT_THAT(result.output, HasSubstr("object 'cube' (box, 60 mm = longest edge)"));
  std::ifstream in(dir_ / "out" / "evaluation.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["object_pixels"]["reconstructed_pixels"], 551);  // see synthetic_truth.h
  EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / "error_map.png"));

  const auto other = run_cli("evaluate " + (dir_ / "out").string() + " --truth " + (dir_ / "sim" / "truth").string() +
                             " --object wall -o " + (dir_ / "wall.json").string() + " --force");
  EXPECT_EQ(other.exit_code, cli::kExitInput) << other.output;  // an infinite plane has no size
  EXPECT_THAT(other.output, HasSubstr("infinite plane"));
  EXPECT_FALSE(fs::exists(dir_ / "wall.json"));

  // Evaluating again replaces the report and the map only with --force; nothing is lost without it.
  const auto again = run_cli("evaluate " + (dir_ / "out").string() + " --truth " + (dir_ / "sim").string());
  EXPECT_EQ(again.exit_code, cli::kExitUsage) << again.output;
  EXPECT_THAT(again.output, HasSubstr("--force"));
  EXPECT_EQ(
      run_cli("evaluate " + (dir_ / "out").string() + " --truth " + (dir_ / "sim").string() + " --force").exit_code,
      cli::kExitOk);
}

TEST_F(EvaluateCliTest, BadInputIsExitCode3AndBadUsage2) {
  const std::string out = (dir_ / "out").string(), sim = (dir_ / "sim").string();
  EXPECT_EQ(run_cli("evaluate " + out).exit_code, cli::kExitUsage);  // --truth is required
  const auto no_truth = run_cli("evaluate " + out + " --truth " + (dir_ / "none").string());
  EXPECT_EQ(no_truth.exit_code, cli::kExitInput);
  const auto no_object = run_cli("evaluate " + out + " --truth " + sim + " --object teapot");
  EXPECT_EQ(no_object.exit_code, cli::kExitInput);
  EXPECT_THAT(no_object.output, HasSubstr("teapot"));
  fs::remove(dir_ / "out" / "confidence.tiff");
  const auto missing = run_cli("evaluate " + out + " --truth " + sim);
  EXPECT_EQ(missing.exit_code, cli::kExitInput);
  EXPECT_THAT(missing.output, HasSubstr("confidence.tiff: missing"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "evaluation.json"));
}

}  // namespace
}  // namespace rfrecon::evaluation
