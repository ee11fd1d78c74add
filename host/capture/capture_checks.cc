// Capture checks on a grid of sampled pixels: the frames' sums against white and black, the response gamma that
// makes them add up, black level, saturation, exposure, bit depth and the pattern / inverse pairs' order.
#include "host/capture/capture_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <utility>

#include "host/capture/frame_read_ahead.h"
#include "host/capture/graycode_patterns.h"
#include "host/capture/phase_patterns.h"
#include "host/core/errors.h"
#include "host/core/percentile.h"

namespace rfrecon::capture {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Thresholds, justified in docs/method.md ("Capture checks").
constexpr double kSaturatedShareLimit = 0.001;  // of sampled pixels
constexpr double kGammaTolerance = 0.1;         // |ln(estimated / declared)| above ln(1.1)
constexpr std::size_t kMinResponseSamples = 50;
constexpr std::size_t kMaxResponseSamples = 2000;
constexpr double kDotSumTolerance = 0.1;         // |dot sum ratio - 1|
constexpr double kPairSumTolerance = 0.05;       // |pair sum ratio - 1|
constexpr double kPairMismatch = 0.5;            // a pixel's pair sum ratio outside [1 - this, 1 + this]
constexpr double kPairMismatchShareLimit = 0.2;  // of a pair's lit pixels
constexpr double kSwappedShareLimit = 0.5;       // of lit-looking pixels where black is brighter than white
constexpr double kAmbientLimit = 0.1;            // black frame's 1st percentile, linear (of full scale)
constexpr double kUnderexposedLevel = 0.25;      // white frame's 99th percentile, of full scale

std::string number(double value, const char* format = "%.3g") {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string percent(double share) { return number(100.0 * share, "%.3g") + "%"; }

double median(std::vector<double> values) { return percentile_of(std::move(values), 0.5); }

// The gamma g in [0.25, 8] with sum of lhs^g = sum of rhs^g (readings clamped at 0), by bisection on ln g; NaN
// without a sign change (no root, or a root the readings cannot place).
double solve_gamma(const std::vector<double>& lhs, const std::vector<double>& rhs) {
  const auto balance = [&](double g) {
    double sum = 0.0;
    for (const double u : lhs) sum += std::pow(std::max(u, 0.0), g);
    for (const double u : rhs) sum -= std::pow(std::max(u, 0.0), g);
    return sum;
  };
  double lo = std::log(0.25), hi = std::log(8.0);
  if (!(balance(std::exp(lo)) > 0.0 && balance(std::exp(hi)) < 0.0)) return kNaN;
  for (int i = 0; i < 24; ++i) {  // ln g to 3.5 / 2^24
    const double mid = 0.5 * (lo + hi);
    (balance(std::exp(mid)) > 0.0 ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

// The g of "linear" or "gamma:<g>" (validate_manifest has accepted it).
double declared_gamma(const CaptureManifest& manifest) {
  const std::string prefix = "gamma:";
  return manifest.camera_response.rfind(prefix, 0) == 0 ? std::stod(manifest.camera_response.substr(prefix.size()))
                                                        : 1.0;
}

std::string pattern_name(const Pattern& pattern) {
  return std::string(pattern.kind == pattern_kind::kGrayColumn ? "column" : "row") + " bit " +
         std::to_string(pattern.bit);
}

}  // namespace

CaptureChecks::CaptureChecks(CaptureManifest manifest)
    : manifest_(std::move(manifest)), samples_(manifest_.frames.size()) {}

void CaptureChecks::add(std::size_t index, const cv::Mat& frame) {
  if (index >= samples_.size()) throw std::out_of_range("CaptureChecks::add: frame index out of range");
  if (frame.channels() != 1 || (frame.depth() != CV_32F && frame.depth() != CV_8U && frame.depth() != CV_16U)) {
    throw std::invalid_argument("CaptureChecks::add: expected one channel of CV_32F, CV_8U or CV_16U");
  }
  if (grid_.empty()) {
    const cv::Size size = manifest_.camera_size.empty() ? frame.size() : manifest_.camera_size;
    const double per_sample = static_cast<double>(size.area()) / static_cast<double>(kSampleCount);
    stride_ = std::max(1, static_cast<int>(std::sqrt(per_sample)));
    grid_ = cv::Size((size.width + stride_ - 1) / stride_, (size.height + stride_ - 1) / stride_);
  }
  if (frame.cols < (grid_.width - 1) * stride_ + 1 || frame.rows < (grid_.height - 1) * stride_ + 1) {
    throw std::invalid_argument("CaptureChecks::add: frame smaller than the camera size");
  }
  // Readings (sample - black_level) / span: what the declared response's curve applies to.
  const SampleMap map = sample_map(manifest_);
  const double inverse_gamma = 1.0 / declared_gamma(manifest_);
  std::vector<float>& samples = samples_[index];
  samples.resize(static_cast<std::size_t>(grid_.area()));
  std::size_t s = 0;
  for (int gy = 0; gy < grid_.height; ++gy) {
    const int y = gy * stride_;
    for (int gx = 0; gx < grid_.width; ++gx, ++s) {
      const int x = gx * stride_;
      switch (frame.depth()) {
        case CV_32F: {
          const float v = frame.at<float>(y, x);
          samples[s] =
              inverse_gamma == 1.0 ? v : static_cast<float>(std::copysign(std::pow(std::abs(v), inverse_gamma), v));
          break;
        }
        case CV_8U:
          samples[s] = (static_cast<float>(frame.at<std::uint8_t>(y, x)) - map.black) * map.scale;
          break;
        default:
          samples[s] = (static_cast<float>(frame.at<std::uint16_t>(y, x)) - map.black) * map.scale;
          break;
      }
    }
  }
}

namespace {

// The frames of a manifest by role. Pairs: a pattern and its inverse, Gray code's (axes 0, 1) or the phase family's
// order code (axes 2, 3). Phase steps: the N steps of one period of one axis, which add up to N / 2 (white + black).
struct Roles {
  std::size_t white = SIZE_MAX;
  std::size_t black = SIZE_MAX;
  std::map<std::pair<int, int>, std::pair<std::size_t, std::size_t>> pairs;  // (axis, bit) -> (pattern, inverse)
  std::vector<std::size_t> dots;
  std::map<std::pair<int, int>, std::vector<std::size_t>> phase_steps;  // (axis, level) -> steps
};

Roles roles_of(const CaptureManifest& manifest) {
  Roles roles;
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    const Pattern& pattern = manifest.frames[i].pattern;
    if (pattern.kind == pattern_kind::kWhite) {
      roles.white = i;
    } else if (pattern.kind == pattern_kind::kBlack) {
      roles.black = i;
    } else if (is_gray(pattern) || pattern.kind == pattern_kind::kOrderColumn ||
               pattern.kind == pattern_kind::kOrderRow) {
      const int axis = pattern.kind == pattern_kind::kGrayColumn    ? 0
                       : pattern.kind == pattern_kind::kGrayRow     ? 1
                       : pattern.kind == pattern_kind::kOrderColumn ? 2
                                                                    : 3;
      auto& pair = roles.pairs.try_emplace({axis, pattern.bit}, SIZE_MAX, SIZE_MAX).first->second;
      (pattern.inverse ? pair.second : pair.first) = i;
    } else if (pattern.kind == pattern_kind::kPhaseColumn || pattern.kind == pattern_kind::kPhaseRow) {
      roles.phase_steps[{pattern.kind == pattern_kind::kPhaseColumn ? 0 : 1, pattern.level}].push_back(i);
    } else if (pattern.kind == pattern_kind::kDot) {
      roles.dots.push_back(i);
    }
  }
  return roles;
}

// The sample arrays the analysis reads, with the declared response's linear values.
struct Readings {
  const std::vector<std::vector<float>>& samples;
  double gamma;
  bool has(std::size_t frame) const { return frame < samples.size() && !samples[frame].empty(); }
  double reading(std::size_t frame, std::size_t s) const { return samples[frame][s]; }
  double linear(std::size_t frame, std::size_t s) const {
    const double u = samples[frame][s];
    return gamma == 1.0 ? u : std::copysign(std::pow(std::abs(u), gamma), u);
  }
};

// Per sampled pixel: lit (white - black above the lit level) and saturated (top code in white or a pattern frame).
struct PixelMasks {
  std::vector<bool> lit;
  std::vector<bool> saturated;
  bool usable(std::size_t s) const { return lit[s] && !saturated[s]; }
};

}  // namespace

namespace {
double sample_span(const CaptureManifest& manifest) { return 1.0 / static_cast<double>(sample_map(manifest).scale); }

// pattern + inverse - white - black (expectation 0, four frames' noise) at the lit, unsaturated sampled pixels of every
// pair added, with the four frames' sum; empty before white and black are in.
std::vector<NoiseSample> pair_noise_samples(const CaptureManifest& manifest,
                                            const std::vector<std::vector<float>>& samples) {
  const Roles roles = roles_of(manifest);
  const Readings readings{samples, declared_gamma(manifest)};
  std::vector<NoiseSample> out;
  if (!readings.has(roles.white) || !readings.has(roles.black)) return out;
  const double top = 1.0 - 0.5 / sample_span(manifest);
  for (const auto& [key, pair] : roles.pairs) {
    if (!readings.has(pair.first) || !readings.has(pair.second)) continue;
    for (std::size_t s = 0; s < samples[roles.white].size(); ++s) {
      const double w = readings.linear(roles.white, s), b = readings.linear(roles.black, s);
      if (w - b <= CaptureChecks::kLitLevel || readings.reading(roles.white, s) >= top ||
          readings.reading(pair.first, s) >= top || readings.reading(pair.second, s) >= top) {
        continue;
      }
      const double p = readings.linear(pair.first, s), q = readings.linear(pair.second, s);
      out.push_back({p + q + w + b, p + q - w - b});
    }
  }
  return out;
}

// One reading's quantisation noise in linear units: 1 / (span sqrt 12).
double quantisation_sigma(const CaptureManifest& manifest) { return 1.0 / (sample_span(manifest) * std::sqrt(12.0)); }
}  // namespace

double CaptureChecks::noise_sigma() const {
  const std::vector<NoiseSample> samples = pair_noise_samples(manifest_, samples_);
  if (samples.empty()) return kNaN;
  std::vector<double> residuals(samples.size());
  std::transform(samples.begin(), samples.end(), residuals.begin(), [](const NoiseSample& n) { return n.residual; });
  const double centre = median(residuals);
  for (double& r : residuals) r = std::abs(r - centre);
  return std::max(1.4826 * median(std::move(residuals)) / 2.0, quantisation_sigma(manifest_));
}

CameraNoise CaptureChecks::camera_noise() const {
  const double quantisation = quantisation_sigma(manifest_);
  return fit_camera_noise(pair_noise_samples(manifest_, samples_), 4, quantisation * quantisation);
}

CaptureCheckResult CaptureChecks::finish() const {
  CaptureCheckResult result;
  const Roles roles = roles_of(manifest_);
  result.declared_gamma = declared_gamma(manifest_);
  const Readings readings{samples_, result.declared_gamma};
  if (!readings.has(roles.white) || !readings.has(roles.black)) return result;
  const std::size_t n = samples_[roles.white].size();
  const double span = sample_span(manifest_);
  const double black_level = manifest_.black_level;
  const double full_scale = std::ldexp(1.0, manifest_.bit_depth) - 1.0;
  const double top = 1.0 - 0.5 / span;  // half a code below the top code
  const auto add_finding = [&](const char* check, double value, std::string message) {
    result.findings.push_back({check, value, std::move(message)});
  };
  result.sampled_pixels = n;

  // Masks, saturation and the largest sample.
  PixelMasks masks{std::vector<bool>(n), std::vector<bool>(n, false)};
  double max_reading = -1.0;
  std::size_t black_brighter = 0, differing = 0;
  for (std::size_t f = 0; f < samples_.size(); ++f) {
    if (!readings.has(f)) continue;
    const bool pattern = f != roles.black;
    for (std::size_t s = 0; s < n; ++s) {
      const double u = readings.reading(f, s);
      max_reading = std::max(max_reading, u);
      if (pattern && u >= top) masks.saturated[s] = true;
    }
  }
  for (std::size_t s = 0; s < n; ++s) {
    const double difference = readings.linear(roles.white, s) - readings.linear(roles.black, s);
    masks.lit[s] = difference > kLitLevel;
    result.lit_pixels += masks.lit[s] ? 1 : 0;
    if (std::abs(difference) > kLitLevel) {
      ++differing;
      black_brighter += difference < 0.0 ? 1 : 0;
    }
  }
  result.saturated_share =
      static_cast<double>(std::count(masks.saturated.begin(), masks.saturated.end(), true)) / static_cast<double>(n);
  result.max_sample_dn = black_level + max_reading * span;

  // Black level, exposure.
  std::vector<double> black_readings(n), white_readings(n), signal;
  for (std::size_t s = 0; s < n; ++s) {
    black_readings[s] = readings.reading(roles.black, s);
    white_readings[s] = readings.reading(roles.white, s);
    if (masks.usable(s)) signal.push_back(readings.linear(roles.white, s) - readings.linear(roles.black, s));
  }
  result.black_frame_dn = black_level + percentile_of(black_readings, 0.01) * span;
  result.white_level = percentile_of(white_readings, 0.99);

  // Linearity: dot frames against white, pattern + inverse against white + black, per pair too.
  const bool all_dots = !roles.dots.empty() && std::all_of(roles.dots.begin(), roles.dots.end(),
                                                           [&](std::size_t f) { return readings.has(f); });
  std::vector<double> dot_ratios, pair_ratios, gammas;
  for (std::size_t s = 0; all_dots && s < n; ++s) {
    if (!masks.usable(s)) continue;
    const double w = readings.linear(roles.white, s), b = readings.linear(roles.black, s);
    double sum = 0.0;
    for (const std::size_t d : roles.dots) sum += readings.linear(d, s) - b;
    dot_ratios.push_back(sum / (w - b));
  }
  double worst_mismatch = 0.0;
  std::pair<std::size_t, std::size_t> worst_pair{SIZE_MAX, SIZE_MAX};
  for (const auto& [key, pair] : roles.pairs) {
    if (!readings.has(pair.first) || !readings.has(pair.second)) continue;
    std::size_t used = 0, mismatched = 0;
    for (std::size_t s = 0; s < n; ++s) {
      if (!masks.usable(s)) continue;
      const double w = readings.linear(roles.white, s), b = readings.linear(roles.black, s);
      const double ratio = (readings.linear(pair.first, s) + readings.linear(pair.second, s) - 2.0 * b) / (w - b);
      pair_ratios.push_back(ratio);
      ++used;
      mismatched += std::abs(ratio - 1.0) > kPairMismatch ? 1 : 0;
    }
    const double share = used == 0 ? 0.0 : static_cast<double>(mismatched) / static_cast<double>(used);
    if (share > worst_mismatch) {
      worst_mismatch = share;
      worst_pair = pair;
    }
  }
  result.dot_sum_ratio = median(dot_ratios);
  result.pair_sum_ratio = median(pair_ratios);

  // Response gamma: per sampled pixel and identity whose frames split the light (each part between a fifth and nine
  // tenths of white - black, in readings), the g that makes the readings^g add up; the median of those, over at most
  // kMaxResponseSamples identities spread evenly over the ones found.
  std::vector<std::pair<std::vector<double>, std::vector<double>>> identities;  // readings: sum lhs^g = sum rhs^g
  for (std::size_t s = 0; s < n; ++s) {
    if (!masks.usable(s)) continue;
    const double uw = readings.reading(roles.white, s), ub = readings.reading(roles.black, s);
    if (uw - ub < 0.1) continue;
    const auto part = [&](std::size_t f) { return (readings.reading(f, s) - ub) / (uw - ub); };
    const auto splits = [](double t) { return t >= 0.2 && t <= 0.9; };
    for (const auto& [key, pair] : roles.pairs) {
      if (!readings.has(pair.first) || !readings.has(pair.second)) continue;
      if (!splits(part(pair.first)) || !splits(part(pair.second))) continue;
      identities.push_back({{readings.reading(pair.first, s), readings.reading(pair.second, s)}, {uw, ub}});
    }
    if (!all_dots) continue;
    // Dots within 2 % of black add dot^g - black^g = 0 to both sides, whatever g: left out.
    std::vector<double> dots, rhs{uw};
    double largest = 0.0, total = 0.0;
    for (const std::size_t d : roles.dots) {
      if (part(d) < 0.02) continue;
      dots.push_back(readings.reading(d, s));
      if (dots.size() > 1) rhs.push_back(ub);  // sum of dot^g = white^g + (dots - 1) black^g
      largest = std::max(largest, part(d));
      total += part(d);
    }
    if (largest > 0.9 || total - largest < 0.2) continue;
    identities.push_back({std::move(dots), std::move(rhs)});
  }
  // Phase steps whose sinusoid spans at least 0.3 of white - black (in readings): sum of step^g = N / 2 (white^g +
  // black^g), both sides doubled for an odd N. One period of one axis per pixel (the first that qualifies), so the
  // identities stay as many as the sampled pixels whatever N.
  for (std::size_t s = 0; s < n; ++s) {
    if (!masks.usable(s)) continue;
    const double uw = readings.reading(roles.white, s), ub = readings.reading(roles.black, s);
    if (uw - ub < 0.1) continue;
    for (const auto& [key, steps] : roles.phase_steps) {
      if (steps.size() < 3 ||
          !std::all_of(steps.begin(), steps.end(), [&](std::size_t f) { return readings.has(f); })) {
        continue;
      }
      const int copies = steps.size() % 2 == 0 ? 1 : 2;
      std::vector<double> lhs, rhs;
      double lowest = 1.0, highest = 0.0;
      for (const std::size_t f : steps) {
        const double u = readings.reading(f, s);
        lhs.insert(lhs.end(), copies, u);
        lowest = std::min(lowest, (u - ub) / (uw - ub));
        highest = std::max(highest, (u - ub) / (uw - ub));
      }
      if (highest - lowest < 0.3) continue;
      for (std::size_t k = 0; k < steps.size() * static_cast<std::size_t>(copies) / 2; ++k) {
        rhs.push_back(uw);
        rhs.push_back(ub);
      }
      identities.push_back({std::move(lhs), std::move(rhs)});
      break;
    }
  }
  const std::size_t step =
      std::max<std::size_t>(1, (identities.size() + kMaxResponseSamples - 1) / kMaxResponseSamples);
  for (std::size_t i = 0; i < identities.size(); i += step) {
    const double g = solve_gamma(identities[i].first, identities[i].second);
    if (std::isfinite(g)) gammas.push_back(g);
  }
  result.response_samples = gammas.size();
  if (gammas.size() >= kMinResponseSamples) result.response_gamma = median(gammas);

  result.noise_sigma = noise_sigma();
  result.camera_noise = camera_noise();
  if (!signal.empty() && std::isfinite(result.noise_sigma)) {
    result.dynamic_range = percentile_of(signal, 0.99) / result.noise_sigma;
  }

  // Findings, most fundamental first.
  if (differing > 0 && static_cast<double>(black_brighter) / static_cast<double>(differing) > kSwappedShareLimit) {
    add_finding("frame_order", static_cast<double>(black_brighter) / static_cast<double>(differing),
                "the black frame (" + manifest_.frames[roles.black].file + ") is brighter than the white frame (" +
                    manifest_.frames[roles.white].file + ") on " +
                    percent(static_cast<double>(black_brighter) / static_cast<double>(differing)) +
                    " of the pixels where they differ: white and black are swapped");
  }
  const bool narrow_data = manifest_.bit_depth == 16 && result.max_sample_dn < 4096.0;  // the cause of a dim capture
  if (narrow_data) {
    const int bits = result.max_sample_dn < 1024.0 ? 10 : 12;
    add_finding("bit_depth", result.max_sample_dn,
                "no sampled reading exceeds " + number(result.max_sample_dn, "%.0f") +
                    " of 65535: the 16-bit files probably hold " + std::to_string(bits) +
                    "-bit data; declare bit_depth " + std::to_string(bits) + " in manifest.json, or pass --bit-depth " +
                    std::to_string(bits) + " with --layout opencv-graycode");
  } else if (result.max_sample_dn > full_scale + 0.5) {
    add_finding("bit_depth", result.max_sample_dn,
                "readings up to " + number(result.max_sample_dn, "%.0f") + " exceed bit_depth " +
                    std::to_string(manifest_.bit_depth) + "'s full scale " + number(full_scale, "%.0f") +
                    ": declare the camera's real bit depth");
  }
  if (result.saturated_share > kSaturatedShareLimit) {
    add_finding("saturation", result.saturated_share,
                percent(result.saturated_share) + " of the sampled pixels reach the top code (" +
                    number(full_scale, "%.0f") + ") in the white frame or a pattern frame (limit " +
                    percent(kSaturatedShareLimit) +
                    "): their readings are clipped, so their transport and decoding are wrong; lower the exposure "
                    "(or the projector's brightness)");
  }
  const std::string sums =
      (std::isfinite(result.dot_sum_ratio) ? "dot frames sum to " + number(result.dot_sum_ratio) + " x white, " : "") +
      "pattern + inverse to " + number(result.pair_sum_ratio) + " x white + black (median over " +
      std::to_string(pair_ratios.size()) + " unsaturated lit samples)";
  const bool response_off =
      std::isfinite(result.response_gamma) &&
      std::abs(std::log(result.response_gamma / result.declared_gamma)) > std::log1p(kGammaTolerance);
  if (response_off) {
    const std::string estimated = number(result.response_gamma, "%.2f");
    add_finding("response", result.response_gamma,
                "the camera's response looks like gamma " + estimated + " (reading = linear^(1/gamma), from " +
                    std::to_string(result.response_samples) + " pixels' frame sums; " + sums +
                    ") but the manifest declares '" + manifest_.camera_response +
                    "': turn the camera's gamma off and capture again, or set camera_response to \"gamma:" + estimated +
                    "\" in manifest.json");
  } else if ((std::isfinite(result.dot_sum_ratio) && std::abs(result.dot_sum_ratio - 1.0) > kDotSumTolerance) ||
             std::abs(result.pair_sum_ratio - 1.0) > kPairSumTolerance) {
    add_finding("linearity", std::isfinite(result.dot_sum_ratio) ? result.dot_sum_ratio : result.pair_sum_ratio,
                "the frames do not add up linearly: " + sums +
                    ", expected 1; fix the camera's exposure time and gain (no automatic exposure or gain) and check "
                    "the projector's brightness does not drift between frames");
  }
  if (worst_mismatch > kPairMismatchShareLimit) {
    add_finding("frame_order", worst_mismatch,
                "Gray pattern " + pattern_name(manifest_.frames[worst_pair.first].pattern) + " (" +
                    manifest_.frames[worst_pair.first].file + ") and its inverse (" +
                    manifest_.frames[worst_pair.second].file + ") differ from white + black by more than half on " +
                    percent(worst_mismatch) + " of the lit pixels (limit " + percent(kPairMismatchShareLimit) +
                    "): frames out of order or of other patterns; with --layout opencv-graycode the files are taken "
                    "sorted by name (zero-pad the numbers in their names)");
  }
  const double noise_dn = std::isfinite(result.noise_sigma) ? result.noise_sigma * span : 0.0;
  const double black_reading = (result.black_frame_dn - black_level) / span;
  const double black_linear = std::copysign(std::pow(std::abs(black_reading), result.declared_gamma), black_reading);
  if (result.black_frame_dn < black_level - (3.0 * noise_dn + 1.0)) {
    add_finding("black_level", result.black_frame_dn,
                "1% of the black frame reads " + number(result.black_frame_dn, "%.1f") +
                    " DN or less, below the declared black_level " + number(black_level, "%.1f") +
                    " DN by more than 3 noise sigma + 1 DN: black_level is too high; set it to " +
                    number(std::max(0.0, std::floor(result.black_frame_dn)), "%.0f") + " or less");
  } else if (!response_off && black_linear > kAmbientLimit) {
    add_finding("black_level", result.black_frame_dn,
                "the black frame's darkest 1% reads " + number(result.black_frame_dn, "%.1f") + " DN, " +
                    percent(black_linear) + " of full scale in linear units (limit " + percent(kAmbientLimit) +
                    ") above black_level " + number(black_level, "%.1f") +
                    " DN: ambient light, light the projector leaks at black, or an undeclared camera black level; "
                    "darken the room, or set black_level");
  }
  if (!narrow_data && result.white_level < kUnderexposedLevel) {
    add_finding("exposure", result.white_level,
                "the white frame's brightest 1% reaches only " + percent(result.white_level) +
                    " of full scale (limit " + percent(kUnderexposedLevel) +
                    (std::isfinite(result.dynamic_range)
                         ? "; lit signal up to " + number(result.dynamic_range, "%.0f") + " x the noise"
                         : std::string()) +
                    "): raise the exposure time (or the projector's brightness)");
  }
  return result;
}

std::vector<CheckMeasure> measures_of(const CaptureCheckResult& result) {
  return {{"saturated share", result.saturated_share, "of sampled pixels"},
          {"dot sum ratio", result.dot_sum_ratio, "x (white - black)"},
          {"pair sum ratio", result.pair_sum_ratio, "x (white - black)"},
          {"response gamma", result.response_gamma, "(reading = linear^(1/gamma))"},
          {"declared gamma", result.declared_gamma, ""},
          {"black frame 1%", result.black_frame_dn, "DN"},
          {"white frame 99%", result.white_level, "of full scale"},
          {"largest sample", result.max_sample_dn, "DN"},
          {"noise sigma", result.noise_sigma, "linear"},
          {"dynamic range", result.dynamic_range, "x noise sigma"},
          {"read noise", std::sqrt(result.camera_noise.read_variance), "linear"},
          {"electrons at full scale", 1.0 / result.camera_noise.variance_per_signal, "(shot noise)"}};
}

nlohmann::json to_json(const CaptureCheckResult& result) {
  const auto value = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json findings = nlohmann::json::array();
  for (const auto& finding : result.findings) {
    findings.push_back({{"check", finding.check}, {"value", value(finding.value)}, {"message", finding.message}});
  }
  return {{"sampled_pixels", result.sampled_pixels},
          {"lit_pixels", result.lit_pixels},
          {"saturated_share", value(result.saturated_share)},
          {"dot_sum_ratio", value(result.dot_sum_ratio)},
          {"pair_sum_ratio", value(result.pair_sum_ratio)},
          {"response_gamma", value(result.response_gamma)},
          {"response_samples", result.response_samples},
          {"declared_gamma", value(result.declared_gamma)},
          {"black_frame_dn", value(result.black_frame_dn)},
          {"white_level", value(result.white_level)},
          {"max_sample_dn", value(result.max_sample_dn)},
          {"noise_sigma", value(result.noise_sigma)},
          {"dynamic_range", value(result.dynamic_range)},
          {"noise_read_variance", value(result.camera_noise.read_variance)},
          {"noise_variance_per_signal", value(result.camera_noise.variance_per_signal)},
          {"findings", findings}};
}

CaptureCheckResult check_capture(const FrameSource& frames, CaptureManifest manifest) {
  // Without a camera size in the manifest, the first frame's: the loader then holds every other frame to it.
  if (manifest.camera_size.empty()) manifest.camera_size = frames.load(manifest, 0, FrameForm::kRaw).size();
  CaptureChecks checks(manifest);
  std::vector<std::vector<std::size_t>> groups(manifest.frames.size());
  for (std::size_t i = 0; i < groups.size(); ++i) groups[i] = {i};
  FrameReadAhead read_ahead(frames, manifest, std::move(groups), 2, 4, FrameForm::kRaw);
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) checks.add(i, read_ahead.take(i).front());
  return checks.finish();
}

}  // namespace rfrecon::capture
