// Capture checks: linearity, camera response, black level, saturation, dynamic range and frame order, measured on
// a fixed grid of sampled pixels while the frames are read (docs/method.md, "Capture checks").
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "host/capture/camera_noise.h"
#include "host/capture/frame_source.h"
#include "host/capture/manifest.h"

namespace rfrecon::capture {

// One problem the checks found: which check, the number it measured and a message that says what to change.
struct CheckFinding {
  std::string check;  // "saturation", "response", "linearity", "black_level", "exposure", "bit_depth", "frame_order"
  double value = 0.0;
  std::string message;
};

// What the checks measured. Ratios are medians over lit, unsaturated sampled pixels, in the linear units the
// declared response gives; NaN where a measure had no pixel to use.
struct CaptureCheckResult {
  std::size_t sampled_pixels = 0;
  std::size_t lit_pixels = 0;    // sampled pixels with white - black above kLitLevel
  double saturated_share = 0.0;  // of sampled pixels: at the top code in white or in any pattern frame
  double dot_sum_ratio = std::numeric_limits<double>::quiet_NaN();   // sum of (dot - black) over (white - black)
  double pair_sum_ratio = std::numeric_limits<double>::quiet_NaN();  // (pattern + inverse - 2 black) / (white - black)
  double response_gamma = std::numeric_limits<double>::quiet_NaN();  // estimated camera gamma: reading = linear^(1/g)
  std::size_t response_samples = 0;  // (pixel, identity) pairs the estimate used (at most 2000)
  double declared_gamma = 1.0;       // the manifest's camera_response
  double black_frame_dn = 0.0;       // the black frame's 1st percentile, digital numbers
  double white_level = 0.0;          // the white frame's 99th percentile, fraction of full scale above black_level
  double max_sample_dn = 0.0;        // the largest sample in any sampled frame, digital numbers
  double noise_sigma = std::numeric_limits<double>::quiet_NaN();    // one frame's noise, linear units (noise_sigma())
  double dynamic_range = std::numeric_limits<double>::quiet_NaN();  // (white - black) 99th percentile / noise_sigma
  CameraNoise camera_noise;  // the noise as a function of the signal (camera_noise())
  std::vector<CheckFinding> findings;
};

// One measured figure of a result, as the commands print it.
struct CheckMeasure {
  const char* name;  // "saturated share", "pair sum ratio", ...
  double value;      // NaN where it was not measured (no dot frames, too few samples)
  const char* unit;  // "of sampled pixels", "DN", ... ("" for none)
};

// The result's figures in the order `rfrecon check` prints them.
std::vector<CheckMeasure> measures_of(const CaptureCheckResult& result);

// The result as JSON (the transport summary's "capture_checks", `rfrecon check --json`); NaN as null.
nlohmann::json to_json(const CaptureCheckResult& result);

// Fed every frame of a capture once, in any order, as it is read; keeps the samples of a fixed grid of about
// kSampleCount pixels (a stride of floor(sqrt(pixels / kSampleCount)) in x and y, at least 1), so the cost per frame
// is independent of the camera size.
class CaptureChecks {
 public:
  static constexpr std::size_t kSampleCount = 8192;
  // A pixel is lit when white - black exceeds this (linear units): the transport's default black threshold.
  static constexpr double kLitLevel = 0.04;

  // `manifest` gives the frames' patterns, bit depth, black level and declared response; its camera_size must be set
  // (or is taken from the first frame added).
  explicit CaptureChecks(CaptureManifest manifest);

  // Frame `index` of the manifest: linear CV_32F (capture::linearize_frame) or raw CV_8U / CV_16U samples.
  void add(std::size_t index, const cv::Mat& frame);

  // One frame's noise sigma in linear units, from the pattern / inverse pairs (Gray or order code) added so far: 1.4826
  // MAD / 2 of pattern + inverse - white - black over lit, unsaturated sampled pixels (four frames of about equal
  // noise), at least the quantisation's 1 / (span sqrt 12). NaN before white, black and one pair are in.
  double noise_sigma() const;
  // The noise as a function of the signal, fitted to the same differences (the four frames' sum as their level).
  CameraNoise camera_noise() const;

  // The measures and findings over the frames added (all of them, for a complete check); thresholds in
  // docs/method.md.
  CaptureCheckResult finish() const;

 private:
  const CaptureManifest manifest_;
  int stride_ = 1;
  cv::Size grid_;
  std::vector<std::vector<float>> samples_;  // per frame: readings (sample - black_level) / span, empty until added
};

// Runs the checks alone over every frame of the capture (read raw, on two threads): `rfrecon check`. Throws
// InputError naming the frame when one is missing, unreadable or does not match the manifest or the first frame.
CaptureCheckResult check_capture(const FrameSource& frames, CaptureManifest manifest);

}  // namespace rfrecon::capture
