// The camera's noise as a function of its signal (a photon transfer line): variance = read + per_signal * signal in
// linear units (1 = full scale), fitted from differences of frames that should sum to the same value.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

namespace rfrecon::capture {

struct CameraNoise {
  double read_variance = std::numeric_limits<double>::quiet_NaN();        // at zero signal (read noise, quantisation)
  double variance_per_signal = std::numeric_limits<double>::quiet_NaN();  // shot noise: 1 / electrons at full scale
  bool known() const { return read_variance >= 0.0 && variance_per_signal >= 0.0; }
  // One frame's noise variance at linear signal `signal`.
  double variance(double signal) const { return read_variance + variance_per_signal * std::max(signal, 0.0); }
};

// One sample of a frame combination whose expectation is 0 and whose variance is the sum of `frames` frames' noise:
// `level` is the sum of those frames' signals, `residual` the combination's value.
struct NoiseSample {
  double level;
  double residual;
};

// The line variance(residual) = frames read_variance + variance_per_signal level, fitted robustly (1.4826 MAD per
// bin of equal count in level, weighted least squares over the bins), both coefficients at least 0 and the read
// variance at least `floor_variance` (quantisation). Unknown (NaN) with fewer than 64 samples.
CameraNoise fit_camera_noise(std::vector<NoiseSample> samples, int frames, double floor_variance);

}  // namespace rfrecon::capture
