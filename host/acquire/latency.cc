// Latency of a projector-camera pair, by flashing white after black.
#include "host/acquire/latency.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "host/core/errors.h"

namespace rfrecon::acquire {

namespace {
double mean_reading(Camera& camera, std::chrono::milliseconds timeout) { return cv::mean(camera.grab(timeout))[0]; }
}  // namespace

int measure_latency_frames(Projector& projector, Camera& camera, const LatencyOptions& options) {
  const cv::Mat black(projector.size(), CV_8UC1, cv::Scalar(0));
  const cv::Mat white(projector.size(), CV_8UC1, cv::Scalar(255));
  const double full_scale = std::ldexp(1.0, camera.format().bit_depth) - 1.0;
  int latency = 0;
  for (int trial = 0; trial < options.trials; ++trial) {
    projector.show(black);
    double black_mean = 0.0;
    for (int i = 0; i <= options.max_frames; ++i) black_mean = mean_reading(camera, options.timeout);
    projector.show(white);
    std::vector<double> means;
    for (int i = 0; i <= options.max_frames; ++i) means.push_back(mean_reading(camera, options.timeout));
    const double white_mean = means.back();
    if (white_mean - black_mean < 0.02 * full_scale) {
      throw HardwareError(camera.name() + " does not see " + projector.name() + ": its mean reading under white (" +
                          std::to_string(white_mean) + " DN) is not 2 % of full scale above black's (" +
                          std::to_string(black_mean) +
                          " DN); point the camera at the projected area, open the aperture or lengthen the exposure");
    }
    const double midpoint = 0.5 * (black_mean + white_mean);
    const auto seen = std::find_if(means.begin(), means.end(), [&](double m) { return m > midpoint; });
    const int frames = static_cast<int>(seen - means.begin());
    if (frames >= options.max_frames) {
      throw HardwareError(camera.name() + " did not see the white flash of " + projector.name() + " within " +
                          std::to_string(options.max_frames) + " frames");
    }
    spdlog::debug("latency trial {}: {} frames (black {:.1f} DN, white {:.1f} DN)", trial + 1, frames, black_mean,
                  white_mean);
    latency = std::max(latency, frames);
  }
  return latency;
}

}  // namespace rfrecon::acquire
