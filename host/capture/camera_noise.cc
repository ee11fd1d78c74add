// The photon transfer line fitted to binned robust variances.
#include "host/capture/camera_noise.h"

#include <algorithm>
#include <cmath>

namespace rfrecon::capture {

namespace {
constexpr std::size_t kMinSamples = 64;
constexpr std::size_t kBins = 16;

double median_of(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}
}  // namespace

CameraNoise fit_camera_noise(std::vector<NoiseSample> samples, int frames, double floor_variance) {
  CameraNoise noise;
  if (samples.size() < kMinSamples || frames < 1) return noise;
  std::sort(samples.begin(), samples.end(),
            [](const NoiseSample& a, const NoiseSample& b) { return a.level < b.level; });
  const std::size_t bins = std::min(kBins, samples.size() / (kMinSamples / 2));
  // Weighted least squares of variance on level; a variance estimate from n samples has variance 2 v^2 / n.
  double sw = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t first = b * samples.size() / bins, last = (b + 1) * samples.size() / bins;
    std::vector<double> residuals;
    double level = 0.0;
    for (std::size_t i = first; i < last; ++i) {
      residuals.push_back(samples[i].residual);
      level += samples[i].level;
    }
    level /= static_cast<double>(last - first);
    const double centre = median_of(residuals);
    for (double& r : residuals) r = std::abs(r - centre);
    const double sigma = 1.4826 * median_of(std::move(residuals));
    const double variance = std::max(sigma * sigma, frames * floor_variance);
    const double weight = static_cast<double>(last - first) / (variance * variance);
    sw += weight;
    sx += weight * level;
    sy += weight * variance;
    sxx += weight * level * level;
    sxy += weight * level * variance;
  }
  const double spread = sw * sxx - sx * sx;
  double slope = spread > 0.0 ? (sw * sxy - sx * sy) / spread : 0.0;
  slope = std::max(slope, 0.0);
  const double intercept = (sy - slope * sx) / sw;
  noise.variance_per_signal = slope;
  noise.read_variance = std::max(intercept / frames, floor_variance);
  return noise;
}

}  // namespace rfrecon::capture
