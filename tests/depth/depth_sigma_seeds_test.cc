// The observation's depth sigma against the spread it predicts, end to end: the same plane rendered with eight noise
// seeds, each decoded and reconstructed with the true rig by the command-line tool (the triangulation's closed form,
// the fusion's noisy copies of T); over the pixels all of them reconstruct, the RMS of each pixel's standard
// deviation over the seeds matches the RMS of its predicted sigma.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "host/outputs/reconstruction_files.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::depth {
namespace {

class DepthSigmaSeedsTest : public ::testing::TestWithParam<const char*> {};

TEST_P(DepthSigmaSeedsTest, ObservationSigmaPredictsTheSpreadOverNoiseSeeds) {
  const std::string method = GetParam();
  const testing::TempDir dir("depth_sigma_seeds_" + method);
  constexpr int kSeeds = 8;
  std::vector<outputs::Reconstruction> runs;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const std::string out = (dir.path() / ("s" + std::to_string(seed))).string();
    for (const std::string& command : {"-q simulate --scene plane-lambert --camera 160x128 --projector 128x80 --seed " +
                                           std::to_string(seed) + " -o " + out,
                                       "-q transport " + out + "/capture -o " + out + "/T.h5",
                                       "-q reconstruct " + out + "/T.h5 --calib " + out + "/truth/rig.yaml --method " +
                                           method + " --sigma-samples 8 -o " + out + "/depth"}) {
      const auto run = testing::run_cli(command);
      ASSERT_EQ(run.exit_code, 0) << command << "\n" << run.output;
    }
    runs.push_back(outputs::read_reconstruction(out + "/depth"));
    ASSERT_FALSE(runs.back().depth_sigma_observation_mm.empty());
  }
  const cv::Size size = runs.front().depth_mm.size();
  double observed_sum = 0.0, predicted_sum = 0.0;
  int pixels = 0;
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      double sum = 0.0, sum_sq = 0.0, predicted_sq = 0.0;
      bool everywhere = true;
      for (const auto& run : runs) {
        const double z = run.depth_mm.at<float>(y, x), sigma = run.depth_sigma_observation_mm.at<float>(y, x);
        everywhere = everywhere && std::isfinite(z) && std::isfinite(sigma);
        sum += z;
        sum_sq += z * z;
        predicted_sq += sigma * sigma;
      }
      if (!everywhere) continue;
      // The true rig: no calibration part, so the total is the observation's.
      EXPECT_EQ(runs.front().depth_sigma_calibration_mm.at<float>(y, x), 0.0f);
      EXPECT_FLOAT_EQ(runs.front().depth_sigma_mm.at<float>(y, x),
                      runs.front().depth_sigma_observation_mm.at<float>(y, x));
      const double mean = sum / kSeeds;
      observed_sum += (sum_sq - kSeeds * mean * mean) / (kSeeds - 1);
      predicted_sum += predicted_sq / kSeeds;
      ++pixels;
    }
  }
  ASSERT_GT(pixels, 4000);
  const double ratio = std::sqrt(observed_sum / predicted_sum);
  // The bound; the ratio's own sampling error over thousands of pixels of 7 degrees of freedom is about 1 %.
  EXPECT_GT(ratio, 0.8);
  EXPECT_LT(ratio, 1.25);
  ::testing::Test::RecordProperty("observed_over_predicted", std::to_string(ratio));
  std::printf("%s: observed / predicted depth sigma RMS over %d pixels and %d seeds: %.3f\n", method.c_str(), pixels,
              kSeeds, ratio);
}

INSTANTIATE_TEST_SUITE_P(Methods, DepthSigmaSeedsTest, ::testing::Values("triangulate", "fused"));

// The calibration's part of a method rerun on moved rigs (--sigma-samples): a rig whose only uncertainty is its
// baseline's length (the covariance sigma_b^2 t t^T along the translation's direction t) scales the whole geometry,
// so every method's depth moves by z sigma_b / b.
class CalibrationRerunTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CalibrationRerunTest, BaselineLengthAloneScalesTheDepth) {
  const std::string method = GetParam();
  const testing::TempDir dir("calibration_rerun_" + method);
  const std::string out = dir.path().string();
  for (const std::string& command :
       {"-q simulate --scene plane-lambert --camera 160x128 --projector 128x80 --seed 1 -o " + out,
        "-q transport " + out + "/capture -o " + out + "/T.h5"}) {
    const auto run = testing::run_cli(command);
    ASSERT_EQ(run.exit_code, 0) << command << "\n" << run.output;
  }
  calib::StereoRig rig = calib::read_rig(out + "/truth/rig.yaml");
  const cv::Mat t = rig.proj_from_cam_translation_mm.reshape(1, 3);
  const double baseline_mm = cv::norm(t), sigma_b_mm = 0.01 * baseline_mm;
  const int g = calib::rig_parameter_count(rig), dist_size = static_cast<int>(rig.dist_coeffs.total());
  calib::RigUncertainty& u = rig.uncertainty;
  u.camera_intrinsics = u.projector_intrinsics = cv::Mat::zeros(1, 4, CV_64F);
  u.camera_dist_coeffs = u.projector_dist_coeffs = cv::Mat::zeros(1, dist_size, CV_64F);
  u.proj_from_cam_rotation_vector = cv::Mat::zeros(1, 3, CV_64F);
  u.proj_from_cam_translation_mm = cv::abs(t.t()) * (sigma_b_mm / baseline_mm);
  u.parameter_covariance = cv::Mat::zeros(g, g, CV_64F);
  const cv::Mat direction = t / baseline_mm;
  cv::Mat block = u.parameter_covariance(cv::Rect(g - 3, g - 3, 3, 3));
  block += direction * direction.t() * (sigma_b_mm * sigma_b_mm);
  calib::write_rig(rig, out + "/rig.yaml");
  const std::string command = "-q reconstruct " + out + "/T.h5 --calib " + out + "/rig.yaml --method " + method +
                              " --sigma-samples 2 -o " + out + "/depth";
  const auto run = testing::run_cli(command);
  ASSERT_EQ(run.exit_code, 0) << command << "\n" << run.output;
  const outputs::Reconstruction maps = outputs::read_reconstruction(out + "/depth");
  std::vector<double> relative_errors;
  for (int y = 0; y < maps.depth_mm.rows; ++y) {
    for (int x = 0; x < maps.depth_mm.cols; ++x) {
      const double z = maps.depth_mm.at<float>(y, x), sigma = maps.depth_sigma_calibration_mm.at<float>(y, x);
      if (!(z > 0.0)) continue;
      relative_errors.push_back(std::abs(sigma / (z * sigma_b_mm / baseline_mm) - 1.0));
    }
  }
  ASSERT_GT(relative_errors.size(), 4000u);
  std::sort(relative_errors.begin(), relative_errors.end());
  // A 1 % scale moves the depth by 1 % to within the forward difference's second order (1e-4) and the row solvers'
  // convergence.
  EXPECT_LT(relative_errors[relative_errors.size() / 2], 0.01);
  EXPECT_LT(relative_errors[relative_errors.size() * 95 / 100], 0.05);
  std::printf("%s: calibration sigma / (z sigma_b / b) - 1, median %.4f, 95th percentile %.4f over %zu pixels\n",
              method.c_str(), relative_errors[relative_errors.size() / 2],
              relative_errors[relative_errors.size() * 95 / 100], relative_errors.size());
}

INSTANTIATE_TEST_SUITE_P(Methods, CalibrationRerunTest, ::testing::Values("integrate", "fused"));

}  // namespace
}  // namespace rfrecon::depth
