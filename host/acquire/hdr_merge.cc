// Exposure merging for HDR capture: exposure-weighted mean of the unsaturated linear readings.
#include "host/acquire/hdr_merge.h"

#include <algorithm>
#include <cmath>

namespace rfrecon::acquire {

void set_merged_format(capture::CaptureManifest& manifest) {
  manifest.bit_depth = kMergedBitDepth;
  manifest.black_level = 0.0;
  manifest.camera_response = "linear";
}

cv::Mat merge_exposures(const std::vector<cv::Mat>& raw, const std::vector<double>& exposures_us,
                        const capture::CaptureManifest& camera) {
  CV_Assert(!raw.empty() && raw.size() == exposures_us.size());
  const double shortest = *std::min_element(exposures_us.begin(), exposures_us.end());
  const double top_code = std::ldexp(1.0, camera.bit_depth) - 1.0;
  cv::Mat linear_sum(raw[0].size(), CV_32F, cv::Scalar(0));
  cv::Mat exposure_sum(raw[0].size(), CV_32F, cv::Scalar(0));
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const cv::Mat linear = capture::linearize_frame(raw[i], camera, "exposure " + std::to_string(i));
    cv::Mat unsaturated;
    cv::compare(raw[i], top_code, unsaturated, cv::CMP_LT);
    cv::add(linear_sum, linear, linear_sum, unsaturated);
    cv::add(exposure_sum, cv::Scalar(exposures_us[i]), exposure_sum, unsaturated);
  }
  cv::Mat merged(raw[0].size(), CV_16U);
  const double full = std::ldexp(1.0, kMergedBitDepth) - 1.0;
  for (int y = 0; y < merged.rows; ++y) {
    const float* sum = linear_sum.ptr<float>(y);
    const float* time = exposure_sum.ptr<float>(y);
    auto* out = merged.ptr<std::uint16_t>(y);
    for (int x = 0; x < merged.cols; ++x) {
      const double value = time[x] > 0.0f ? shortest * sum[x] / time[x] : 1.0;
      out[x] = static_cast<std::uint16_t>(std::lround(std::clamp(value, 0.0, 1.0) * full));
    }
  }
  return merged;
}

}  // namespace rfrecon::acquire
