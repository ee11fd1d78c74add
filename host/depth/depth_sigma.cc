// The two parts of the depth's standard deviation, on the camera grid, and their summary.
#include "host/depth/depth_sigma.h"

#include <cmath>
#include <limits>

#include "host/core/parallel_rows.h"
#include "host/core/percentile.h"
#include "host/depth/calibration_sigma.h"

namespace rfrecon::depth {

namespace {
constexpr float kUnknownSigma = std::numeric_limits<float>::quiet_NaN();

nlohmann::json spread(const cv::Mat& sigma) {
  const float median = finite_percentile(sigma, 0.5), high = finite_percentile(sigma, 0.95);
  if (std::isnan(median)) return nullptr;
  return {{"median", median}, {"p95", high}};
}
}  // namespace

void add_depth_sigma(outputs::Reconstruction& maps, const cv::Mat& z_rect_mm, const cv::Mat& observation_rect_sigma_mm,
                     const std::string& observation_source, const calib::StereoRig& rig, nlohmann::json& summary) {
  const cv::Mat& depth = maps.depth_mm;
  const cv::Mat covariance = rig_parameter_covariance(rig);
  maps.depth_sigma_calibration_mm = covariance.empty() ? cv::Mat(depth.size(), CV_32F, cv::Scalar(0.0f))
                                                       : calibration_depth_sigma(rig, covariance, depth);
  maps.depth_sigma_observation_mm = cv::Mat(depth.size(), CV_32F);
  maps.depth_sigma_mm = cv::Mat(depth.size(), CV_32F);
  for_each_row(depth.rows, [&](int y) {
    for (int x = 0; x < depth.cols; ++x) {
      const float z = depth.at<float>(y, x), z_rect = z_rect_mm.at<float>(y, x);
      float& calibration = maps.depth_sigma_calibration_mm.at<float>(y, x);
      float& observation = maps.depth_sigma_observation_mm.at<float>(y, x);
      if (!(z > 0.0f)) calibration = kUnknownSigma;
      observation = observation_rect_sigma_mm.empty() || !(z > 0.0f)
                        ? kUnknownSigma
                        : observation_rect_sigma_mm.at<float>(y, x) * z / z_rect;
      maps.depth_sigma_mm.at<float>(y, x) = std::sqrt(calibration * calibration + observation * observation);
    }
  });
  const bool full = !rig.uncertainty.parameter_covariance.empty();
  summary["depth_sigma_mm"] = {
      {"total", spread(maps.depth_sigma_mm)},
      {"calibration", spread(maps.depth_sigma_calibration_mm)},
      {"observation", spread(maps.depth_sigma_observation_mm)},
      {"calibration_source", covariance.empty() ? "none: the rig has no uncertainty (0)"
                             : full             ? "the rig's parameter covariance"
                                                : "the rig's standard deviations (no covariance in the file)"},
      {"observation_source", observation_source}};
}

}  // namespace rfrecon::depth
