// Evaluation against a synthetic truth whose errors are known exactly, the object-size rule, the error map's fixed
// scale, the report, compatibility with a real `simulate` output, and bad input named in the error.
#include "host/evaluation/evaluation.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/core/errors.h"
#include "host/outputs/legend.h"
#include "sim/simulate.h"
#include "tests/common/temp_dir.h"
#include "tests/evaluation/synthetic_truth.h"
#include "tests/sim/test_scenes.h"

namespace rfrecon::evaluation {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
namespace synthetic = testing;

// Errors are sums of exact float32 values (multiples of 1/8 mm) accumulated in double: only the final division and
// square root round, so 1e-12 mm is ample.
constexpr double kExact = 1e-12;

class EvaluationTest : public ::testing::Test {
 protected:
  void SetUp() override { synthetic::write_truth(root_); }

  // Runs `call` and returns the InputError's message (empty, with a failure, when nothing is thrown).
  template <typename Call>
  static std::string input_error(Call call) {
    try {
      call();
    } catch (const InputError& error) {
      return error.what();
    }
    ADD_FAILURE() << "expected InputError";
    return {};
  }

  rfrecon::testing::TempDir temp_{"evaluation_test"};
  const fs::path root_ = temp_.path();
};

TEST_F(EvaluationTest, KnownErrorsOfTheObjectAndOfAllPixels) {
  const auto truth = read_evaluation_truth(root_);
  const auto e = evaluate(synthetic::reconstruction(), truth);
  // Cube: 20 columns x 29 rows; column 0 missing; columns 2, 4, .., 18 (9 x 29 = 261 pixels) off by 1/8 mm.
  EXPECT_EQ(e.object.truth_pixels, 580u);
  EXPECT_EQ(e.object.reconstructed_pixels, 551u);
  EXPECT_NEAR(e.object.coverage_percent, 100.0 * 551 / 580, kExact);
  EXPECT_NEAR(e.object.rms_mm, 0.125 * std::sqrt(261.0 / 551.0), kExact);
  EXPECT_NEAR(e.object.mean_abs_mm, 0.125 * 261.0 / 551.0, kExact);
  EXPECT_NEAR(e.object.bias_mm, 0.125 * 261.0 / 551.0, kExact);
  EXPECT_EQ(e.object.max_abs_mm, 0.125);
  // Normals tilted by 3 degrees, stored as float32 components: the angle is good to ~1e-5 degrees.
  EXPECT_EQ(e.object.normal_pixels, 551u);
  EXPECT_NEAR(e.object.normal_rms_deg, synthetic::kCubeNormalErrorDeg, 1e-4);

  // All pixels with truth: the cube plus the wall (20 x 29, column 39 missing, the rest -1/4 mm, normals exact).
  // Row 0 has no truth: its reconstruction must not count.
  EXPECT_EQ(e.all.truth_pixels, 1160u);
  EXPECT_EQ(e.all.reconstructed_pixels, 1102u);
  EXPECT_NEAR(e.all.coverage_percent, 100.0 * 1102 / 1160, kExact);
  EXPECT_NEAR(e.all.rms_mm, std::sqrt((261 * 0.125 * 0.125 + 551 * 0.25 * 0.25) / 1102), kExact);
  EXPECT_NEAR(e.all.mean_abs_mm, (261 * 0.125 + 551 * 0.25) / 1102, kExact);
  EXPECT_NEAR(e.all.bias_mm, (261 * 0.125 - 551 * 0.25) / 1102, kExact);
  EXPECT_EQ(e.all.max_abs_mm, 0.25);
  EXPECT_EQ(e.all.normal_pixels, 1102u);
  EXPECT_NEAR(e.all.normal_rms_deg, synthetic::kCubeNormalErrorDeg / std::sqrt(2.0), 1e-4);
}

TEST_F(EvaluationTest, ReportGivesPercentOfTheObjectSize) {
  const auto e = evaluate(synthetic::reconstruction(), read_evaluation_truth(root_));
  const auto report = evaluation_report(e, "error_map.png");
  EXPECT_EQ(report["format"], "rfrecon-evaluation");
  EXPECT_EQ(report["object"]["name"], "cube");
  EXPECT_EQ(report["object"]["size_mm"], synthetic::kBoxSizeMm);
  const auto& object = report["object_pixels"];
  EXPECT_NEAR(object["depth_error_percent_of_size"]["rms"].get<double>(),
              100.0 * 0.125 * std::sqrt(261.0 / 551.0) / synthetic::kBoxSizeMm, kExact);
  EXPECT_NEAR(object["depth_error_percent_of_size"]["max_abs"].get<double>(), 100.0 * 0.125 / 60.0, kExact);
  EXPECT_EQ(object["reconstructed_pixels"], 551);
  EXPECT_NEAR(report["all_pixels"]["depth_error_percent_of_size"]["max_abs"].get<double>(), 100.0 * 0.25 / 60.0,
              kExact);
  EXPECT_EQ(report["error_map"]["full_scale_mm"], 0.6);
}

TEST_F(EvaluationTest, WritesReportAndMapWithTheMapNamedRelativeToTheReport) {
  const auto e = evaluate(synthetic::reconstruction(), read_evaluation_truth(root_));
  write_evaluation(e, root_ / "eval" / "evaluation.json", root_ / "eval" / "error_map.png");
  std::ifstream in(root_ / "eval" / "evaluation.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["error_map"]["file"], "error_map.png");
  EXPECT_EQ(report["object_pixels"]["truth_pixels"], 580);
  // The map at the top left, unchanged, and its legend to the right.
  const cv::Mat file = cv::imread((root_ / "eval" / "error_map.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(file.size(), cv::Size(synthetic::kWidth + outputs::kLegendWidth,
                                  std::max(synthetic::kHeight, outputs::kLegendMinHeight)));
  const cv::Mat map = error_map(e);
  EXPECT_EQ(cv::norm(file(cv::Rect(0, 0, map.cols, map.rows)), map, cv::NORM_INF), 0.0);
}

TEST_F(EvaluationTest, ErrorMapHasAFixedScaleOfOnePercentOfTheSize) {
  auto r = synthetic::reconstruction();
  // Full scale 0.6 mm (1 % of 60 mm): +0.75 mm saturates; +0.3 mm is half scale.
  r.depth_mm.at<float>(5, 3) = synthetic::truth_depth(3, 5) + 0.75f;
  r.depth_mm.at<float>(6, 3) = synthetic::truth_depth(3, 6) + 0.3f;
  const cv::Mat map = error_map(evaluate(r, read_evaluation_truth(root_)));
  cv::Mat levels(1, 256, CV_8U), turbo;
  for (int i = 0; i < 256; ++i) levels.at<uchar>(0, i) = static_cast<uchar>(i);
  cv::applyColorMap(levels, turbo, cv::COLORMAP_TURBO);
  EXPECT_EQ(map.at<cv::Vec3b>(5, 3), turbo.at<cv::Vec3b>(0, 255));
  const cv::Vec3b half = map.at<cv::Vec3b>(6, 3);  // 127.5 before rounding; float32 depth moves it by < 0.1
  EXPECT_TRUE(half == turbo.at<cv::Vec3b>(0, 127) || half == turbo.at<cv::Vec3b>(0, 128));
  EXPECT_EQ(map.at<cv::Vec3b>(6, 5), turbo.at<cv::Vec3b>(0, 0));  // odd column: exact
  EXPECT_EQ(map.at<cv::Vec3b>(6, 0), cv::Vec3b(0, 0, 0));         // on the cube, not reconstructed
  EXPECT_EQ(map.at<cv::Vec3b>(6, 30), cv::Vec3b(128, 128, 128));  // the wall: outside the object
  EXPECT_EQ(map.at<cv::Vec3b>(0, 5), cv::Vec3b(128, 128, 128));   // no truth
}

TEST_F(EvaluationTest, ObjectSelectionByName) {
  const auto cube = read_evaluation_truth(root_);
  EXPECT_EQ(cube.object.name, "cube");
  EXPECT_EQ(cube.object.label, 1);
  EXPECT_EQ(cube.object.size_mm, 60.0);
  EXPECT_EQ(cube.object.size_rule, "longest edge");
  const auto ball = read_evaluation_truth(root_, "ball");
  EXPECT_EQ(ball.object.label, 3);
  EXPECT_EQ(ball.object.size_mm, 20.0);                                        // diameter of r = 10
  EXPECT_THROW(evaluate(synthetic::reconstruction(), ball), ProcessingError);  // not in view
  EXPECT_THAT(input_error([&] { read_evaluation_truth(root_, "wall"); }), HasSubstr("infinite plane"));
  EXPECT_THAT(input_error([&] { read_evaluation_truth(root_, "teapot"); }),
              HasSubstr("no object named 'teapot' (objects: cube, wall, ball)"));
}

TEST_F(EvaluationTest, TruthFolderItselfIsAccepted) {
  const auto truth = read_evaluation_truth(root_ / "truth");
  EXPECT_EQ(truth.object.name, "cube");
  EXPECT_EQ(evaluate(synthetic::reconstruction(), truth).object.truth_pixels, 580u);
}

TEST_F(EvaluationTest, BadInputIsNamed) {
  auto small = synthetic::reconstruction();
  small.depth_mm = small.depth_mm(cv::Rect(0, 0, 20, 30)).clone();
  small.normals = small.normals(cv::Rect(0, 0, 20, 30)).clone();
  EXPECT_THAT(
      input_error([&] { evaluate(small, read_evaluation_truth(root_), "OUT/depth.tiff"); }),
      HasSubstr("OUT/depth.tiff is 20x30 but the truth " + (root_ / "truth" / "depth.tiff").string() + " is 40x30"));

  cv::imwrite((root_ / "truth" / "object_id.png").string(), cv::Mat(10, 10, CV_16U, cv::Scalar(1)));
  EXPECT_THAT(input_error([&] { read_evaluation_truth(root_); }), HasSubstr("object_id.png: 10x10, expected 40x30"));
  fs::remove(root_ / "truth" / "object_id.png");
  EXPECT_THAT(input_error([&] { read_evaluation_truth(root_); }), HasSubstr("object_id.png: missing"));
  EXPECT_THAT(input_error([&] { read_evaluation_truth(root_ / "nowhere"); }), HasSubstr("neither a truth folder"));

  synthetic::write_truth(root_);
  fs::remove(root_ / "truth" / "objects.json");
  EXPECT_THAT(input_error([&] { read_evaluation_truth(root_); }), HasSubstr("objects.json"));

  fs::remove_all(root_ / "truth");
  fs::create_directories(root_ / "truth" / "pose_00");
  EXPECT_THAT(input_error([&] { read_evaluation_truth(root_); }), HasSubstr("a multi-view rendering"));
}

// A real `simulate` output evaluated against itself: compatibility with its layout, object ids and objects.json, and
// zero error with full coverage (the maps are the same float32 files).
TEST(EvaluationOfASimulation, TruthAgainstItselfHasNoErrorAndFullCoverage) {
  const rfrecon::testing::TempDir temp("evaluation_sim");
  const fs::path dir = temp.path() / "sim";
  auto json =
      sim::testing::small_rig({{{"name", "box"},
                                {"shape", "box"},
                                {"size", {80.0, 60.0, 40.0}},
                                {"pose", {{"position", {0.0, 0.0, 550.0}}, {"rotation_deg", {20.0, 30.0, 0.0}}}},
                                {"material", {{"brdf", "lambert"}, {"diffuse", 0.5}}}},
                               {{"name", "wall"},
                                {"shape", "plane"},
                                {"pose", {{"position", {0.0, 0.0, 700.0}}}},
                                {"material", {{"brdf", "lambert"}, {"diffuse", 0.5}}}}});
  json["capture"] = {{"dot_spacing", 0}};
  json["render"] = {{"supersample", 1}};
  sim::simulate(sim::testing::make_scene(json), dir, {});
  const auto truth = read_evaluation_truth(dir);
  outputs::Reconstruction same;
  same.depth_mm = truth.depth_mm;
  same.normals = truth.normals;
  const auto e = evaluate(same, truth);
  EXPECT_EQ(truth.object.size_mm, 80.0);
  // f = 100 px at 550 mm: the silhouette covers at least the smallest face (40 x 60 mm: 79 px) and at most the disc
  // of the bounding sphere (radius 54 mm at >= 496 mm: 373 px).
  EXPECT_GE(e.object.truth_pixels, 79u);
  EXPECT_LE(e.object.truth_pixels, 373u);
  EXPECT_EQ(e.object.coverage_percent, 100.0);
  EXPECT_EQ(e.object.max_abs_mm, 0.0);
  EXPECT_EQ(e.all.truth_pixels, 80u * 60u);  // the wall fills the rest
  EXPECT_EQ(e.all.max_abs_mm, 0.0);
  EXPECT_EQ(e.object.normal_rms_deg, 0.0);
}

}  // namespace
}  // namespace rfrecon::evaluation
