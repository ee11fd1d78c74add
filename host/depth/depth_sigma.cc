// The two parts of the depth's standard deviation, on the camera grid, and their summary.
#include "host/depth/depth_sigma.h"

#include <cmath>
#include <limits>

#include "host/core/parallel_rows.h"
#include "host/core/percentile.h"

namespace rfrecon::depth {

namespace {
constexpr float kUnknownSigma = std::numeric_limits<float>::quiet_NaN();

nlohmann::json spread(const cv::Mat& sigma) {
  const float median = finite_percentile(sigma, 0.5), high = finite_percentile(sigma, 0.95);
  if (std::isnan(median)) return nullptr;
  return {{"median", median}, {"p95", high}};
}

// `part` where the depth exists and the part is known, NaN elsewhere.
cv::Mat where_depth(const SigmaPart& part, const cv::Mat& depth_mm) {
  cv::Mat sigma(depth_mm.size(), CV_32F, cv::Scalar(kUnknownSigma));
  if (!part.sigma_mm.empty()) part.sigma_mm.copyTo(sigma, depth_mm > 0.0f);
  return sigma;
}
}  // namespace

cv::Mat camera_z_sigma(const cv::Mat& rect_sigma_mm, const cv::Mat& z_rect_mm, const cv::Mat& depth_mm) {
  if (rect_sigma_mm.empty()) return {};
  cv::Mat sigma(depth_mm.size(), CV_32F);
  for_each_row(depth_mm.rows, [&](int y) {
    for (int x = 0; x < depth_mm.cols; ++x) {
      sigma.at<float>(y, x) = rect_sigma_mm.at<float>(y, x) * depth_mm.at<float>(y, x) / z_rect_mm.at<float>(y, x);
    }
  });
  return sigma;
}

void add_depth_sigma(outputs::Reconstruction& maps, const SigmaPart& calibration, const SigmaPart& observation,
                     nlohmann::json& summary) {
  maps.depth_sigma_calibration_mm = where_depth(calibration, maps.depth_mm);
  maps.depth_sigma_observation_mm = where_depth(observation, maps.depth_mm);
  cv::magnitude(maps.depth_sigma_calibration_mm, maps.depth_sigma_observation_mm, maps.depth_sigma_mm);
  summary["depth_sigma_mm"] = {{"total", spread(maps.depth_sigma_mm)},
                               {"calibration", spread(maps.depth_sigma_calibration_mm)},
                               {"observation", spread(maps.depth_sigma_observation_mm)},
                               {"calibration_source", calibration.source},
                               {"observation_source", observation.source}};
}

}  // namespace rfrecon::depth
