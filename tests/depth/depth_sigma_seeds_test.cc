// The observation's depth sigma against the spread it predicts, end to end: the same plane rendered with eight noise
// seeds, each decoded and reconstructed with the true rig by the command-line tool (the triangulation's closed form,
// the fusion's noisy copies of T); over the pixels all of them reconstruct, the RMS of each pixel's standard
// deviation over the seeds matches the RMS of its predicted sigma.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

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

}  // namespace
}  // namespace rfrecon::depth
