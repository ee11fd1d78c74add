// Feeds in-memory capture frames to an accumulator in protocol order (the all-at-once path of the tests), and the
// tiny captures the kernel tests feed.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "host/capture/manifest.h"
#include "host/transport/graycode_accumulator.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon::transport::testing {

// A 24 x 20 camera viewing a plane lit by a 16 x 12 projector through the whole protocol with dot spacing s (0: Gray
// code only): 8-bit frames with noise (seed 7). Tiny, so that CI reruns its tests under oclgrind.
struct TinyCapture {
  PlaneScene scene;
  std::vector<capture::Pattern> sequence;
  std::vector<cv::Mat> frames;  // 8-bit
};
TinyCapture tiny_capture(int dot_spacing);

// The tiny capture, Gray code only, with a projector sized for one full batch of RF_GRAY_PAIR_BATCH pattern/inverse
// pairs and a partial one of 2 pairs (1 for a batch of 2), the columns' pairs then the rows' (so that batches of 3
// or more mix both axes). None for a batch of 1 pair (every count fills whole batches) or beyond 20 pairs (the
// projector would not be tiny).
std::optional<TinyCapture> tiny_gray_capture_over_batches();

// The phase family's parameters of a capture.
struct PhaseParameters {
  int steps;
  int period;
  int ratio = 0;        // 0: unwrapped by the order code
  int dot_spacing = 0;  // the dot grid after the phases, or none
  // Another tool's conventions (capture::kPhaseOrigin, kPhaseReversed, kOrderUnit, kOrderInverses, kPhaseCoarsest).
  int origin_degrees = 0;
  int reversed = 0;
  int order_unit = 1;
  int order_inverses = 1;
  int coarsest = 0;
  int fringes = 0;     // capture::kPhaseFringes
  int heterodyne = 0;  // capture::kPhaseHeterodyne
  int projector_width = 16;
  int projector_height = 12;
};

// The tiny capture through the phase family's sequence on its projector (16 x 12 unless it says).
TinyCapture tiny_phase_capture(PhaseParameters phase);
// The setup of a phase capture of `frames`: the family and its parameters, K entries per pixel.
TransportSetup phase_setup_for(const std::vector<cv::Mat>& frames, PhaseParameters phase, int k);

// The tiny capture's compressed T as the C++ reference accumulator makes it, K entries per pixel.
CompressedTransport tiny_reference_transport(int dot_spacing, int k);

// Lights for the sparse products of T: uniform in [0, 1), one per projector and one per camera pixel (seed 3).
struct Lights {
  std::vector<float> projector;
  std::vector<float> camera;
};
Lights random_lights(const CompressedTransport& transport);

// Linear frames (8-bit readings / 255) of `frames`.
std::vector<cv::Mat> linearize(const std::vector<cv::Mat>& frames);

// Gray pairs, white/black, dot frames, finish: the whole capture held in memory.
CompressedTransport feed_all(GraycodeAccumulator& accumulator, const std::vector<capture::Pattern>& sequence,
                             const std::vector<cv::Mat>& linear_frames);
// The same with the Gray and dot frames from `frames` (raw samples, say) and white and black from `linear_frames`.
CompressedTransport feed_all(GraycodeAccumulator& accumulator, const std::vector<capture::Pattern>& sequence,
                             const std::vector<cv::Mat>& frames, const std::vector<cv::Mat>& linear_frames);

// The steps of `family`'s plan for `sequence`, then finish(): the steps' frames from `frames`, white and black from
// `linear_frames`.
CompressedTransport feed_plan(TransportAccumulator& accumulator, const std::string& family,
                              const std::vector<capture::Pattern>& sequence, const std::vector<cv::Mat>& frames,
                              const std::vector<cv::Mat>& linear_frames);

// The setup of a capture of `frames` (camera size of the first frame).
TransportSetup setup_for(const std::vector<cv::Mat>& frames, cv::Size projector_size, int dot_spacing, int k);

}  // namespace rfrecon::transport::testing
