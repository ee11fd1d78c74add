// The parametric bootstrap of the frames' noise through a depth method.
#include "host/depth/sampled_sigma.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <nlohmann/json.hpp>

#include "host/core/parallel_rows.h"
#include "host/core/stage_clock.h"
#include "host/transport/dot_rows.h"

namespace rfrecon::depth {

namespace {
// T with each camera row's entries redrawn (rows of every core, each row's generator seeded by the sample and the row).
transport::CompressedTransport noisy_copy(const transport::CompressedTransport& t, unsigned sample) {
  transport::CompressedTransport copy = t;
  const capture::CameraNoise& noise = t.camera_noise;
  const cv::Size size = t.setup.camera_size;
  const auto k_max = static_cast<std::size_t>(t.k());
  for_each_row(size.height, [&](int y) {
    std::mt19937 random(sample * 1000003u + static_cast<unsigned>(y));
    std::normal_distribution<float> normal;
    for (int x = 0; x < size.width; ++x) {
      const std::size_t first = (static_cast<std::size_t>(y) * size.width + x) * k_max;
      const auto black = static_cast<float>(std::sqrt(noise.variance(0.0))) * normal(random);
      for (std::size_t e = first; e < first + k_max; ++e) {
        if (copy.indices[e] < 0) continue;
        copy.weights[e] += static_cast<float>(std::sqrt(noise.variance(copy.weights[e]))) * normal(random) - black;
      }
    }
  });
  transport::finish_rows(copy, true);
  return copy;
}
}  // namespace

cv::Mat sampled_observation_sigma(const DepthMethod& method, const MethodScan& scan, const calib::StereoRig& rig,
                                  int samples) {
  const transport::CompressedTransport& t = scan.transport;
  if (samples < 2 || !t.camera_noise.known() || !transport::correspondences_are_centroids(t.setup)) return {};
  const cv::Size size = t.setup.camera_size;
  cv::Mat sum = cv::Mat::zeros(size, CV_64F), sum_squares = sum.clone(), count = cv::Mat::zeros(size, CV_32S);
  for (int sample = 0; sample < samples; ++sample) {
    const transport::CompressedTransport copy = noisy_copy(t, static_cast<unsigned>(sample) + 1u);
    const CameraGridTriangulation triangulation =
        triangulate_camera_grid(copy, rig, scan.rectification, scan.options.rectification);
    StageClock clock;
    nlohmann::json summary;
    MethodScan again{copy,         scan.rectification, triangulation, scan.options, scan.rig_name,
                     scan.devices, scan.programs,      clock,         summary};
    const cv::Mat z = method.solve(again);
    for_each_row(size.height, [&](int y) {
      for (int x = 0; x < size.width; ++x) {
        const double value = z.at<float>(y, x);
        if (!std::isfinite(value)) continue;
        sum.at<double>(y, x) += value;
        sum_squares.at<double>(y, x) += value * value;
        ++count.at<int>(y, x);
      }
    });
  }
  cv::Mat sigma(size, CV_32F);
  for_each_row(size.height, [&](int y) {
    for (int x = 0; x < size.width; ++x) {
      const double n = count.at<int>(y, x), mean = sum.at<double>(y, x) / n;
      sigma.at<float>(y, x) =
          count.at<int>(y, x) == samples
              ? static_cast<float>(std::sqrt(std::max(0.0, (sum_squares.at<double>(y, x) - n * mean * mean) / (n - 1))))
              : std::numeric_limits<float>::quiet_NaN();
    }
  });
  return sigma;
}

}  // namespace rfrecon::depth
