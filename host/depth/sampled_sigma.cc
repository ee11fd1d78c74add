// The method rerun on noisy copies of T and on moved rigs.
#include "host/depth/sampled_sigma.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/core/parallel_rows.h"
#include "host/core/stage_clock.h"
#include "host/depth/camera_grid.h"
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

// The camera frame's z of each pixel by `method` on `t` with `rig` (rectified as `rectification`), as
// reconstruct_depth computes it; its counts and timings go to a summary of its own.
cv::Mat rerun_depth_mm(const DepthMethod& method, const MethodScan& scan, const transport::CompressedTransport& t,
                       const calib::StereoRig& rig, const Rectification& rectification) {
  const CameraGridTriangulation triangulation =
      triangulate_camera_grid(t, rig, rectification, scan.options.rectification);
  StageClock clock;
  nlohmann::json summary;
  MethodScan again{t,     rectification, triangulation, scan.options, scan.rig_name, scan.devices, scan.programs,
                   clock, summary};
  return camera_frame_maps(method.solve(again), triangulation.rect_cam, rectification.rig, rectification.rect_from_cam)
      .depth_mm;
}
}  // namespace

cv::Mat sampled_observation_sigma(const DepthMethod& method, const MethodScan& scan, const calib::StereoRig& rig,
                                  int samples) {
  const transport::CompressedTransport& t = scan.transport;
  if (samples < 2 || !t.camera_noise.known() || !transport::correspondences_are_centroids(t.setup)) return {};
  const cv::Size size = t.setup.camera_size;
  cv::Mat sum = cv::Mat::zeros(size, CV_64F), sum_squares = sum.clone(), count = cv::Mat::zeros(size, CV_32S);
  for (int sample = 0; sample < samples; ++sample) {
    const cv::Mat z =
        rerun_depth_mm(method, scan, noisy_copy(t, static_cast<unsigned>(sample) + 1u), rig, scan.rectification);
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

cv::Mat rerun_calibration_sigma(const DepthMethod& method, const MethodScan& scan, const calib::StereoRig& rig,
                                const std::vector<std::vector<double>>& steps, const cv::Mat& depth_mm,
                                const cv::Mat& first_order) {
  const int dist_size = static_cast<int>(rig.dist_coeffs.total());
  const std::vector<double> nominal = calib::rig_parameters(rig, dist_size);
  cv::Mat variance = cv::Mat::zeros(depth_mm.size(), CV_64F), lost = cv::Mat::zeros(depth_mm.size(), CV_8U);
  for (const std::vector<double>& step : steps) {
    std::vector<double> moved = nominal;
    for (std::size_t i = 0; i < moved.size(); ++i) moved[i] += step[i];
    calib::StereoRig moved_rig = rig;
    calib::set_rig_parameters(moved_rig, moved, dist_size);
    const Rectification rectification = depth_rectification(moved_rig, scan.rig_name, method.needs_rows());
    const cv::Mat z = rerun_depth_mm(method, scan, scan.transport, moved_rig, rectification);
    for_each_row(depth_mm.rows, [&](int y) {
      for (int x = 0; x < depth_mm.cols; ++x) {
        const double change = static_cast<double>(z.at<float>(y, x)) - depth_mm.at<float>(y, x);
        if (std::isfinite(change)) {
          variance.at<double>(y, x) += change * change;
        } else {
          lost.at<std::uint8_t>(y, x) = 1;
        }
      }
    });
  }
  cv::Mat sigma(depth_mm.size(), CV_32F);
  for_each_row(depth_mm.rows, [&](int y) {
    for (int x = 0; x < depth_mm.cols; ++x) {
      sigma.at<float>(y, x) = !(depth_mm.at<float>(y, x) > 0.0f) ? std::numeric_limits<float>::quiet_NaN()
                              : lost.at<std::uint8_t>(y, x) != 0
                                  ? first_order.at<float>(y, x)
                                  : static_cast<float>(std::sqrt(variance.at<double>(y, x)));
    }
  });
  return sigma;
}

}  // namespace rfrecon::depth
