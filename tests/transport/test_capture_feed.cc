// In-memory feeding of capture frames for the transport tests, and their tiny capture.
#include "tests/transport/test_capture_feed.h"

#include <algorithm>
#include <random>

#include "host/capture/graycode_patterns.h"
#include "host/capture/phase_patterns.h"
#include "host/capture/protocol.h"
#include "host/transport/decoding_family.h"
#include "kernels/transport/gray_decode.h"

namespace rfrecon::transport::testing {

namespace pattern_kind = capture::pattern_kind;

namespace {

TinyCapture tiny_capture_of(cv::Size projector_size, int dot_spacing) {
  SceneOptions options;
  options.camera_size = {24, 20};
  options.projector_size = projector_size;
  TinyCapture capture{make_plane_scene(options), {}, {}};
  capture.sequence = capture::make_protocol({options.projector_size, dot_spacing});
  capture.frames = render_frames(capture.scene, capture.sequence, dot_spacing, 1.0, 7);
  return capture;
}

}  // namespace

TinyCapture tiny_capture(int dot_spacing) { return tiny_capture_of({16, 12}, dot_spacing); }

std::map<std::string, int> phase_parameters(PhaseParameters phase) {
  return {{capture::kPhaseSteps, phase.steps},
          {capture::kPhasePeriod, phase.period},
          {capture::kPhaseRatio, phase.ratio},
          {capture::kPhaseOrigin, phase.origin_degrees},
          {capture::kPhaseReversed, phase.reversed},
          {capture::kOrderUnit, phase.order_unit},
          {capture::kOrderInverses, phase.order_inverses},
          {capture::kPhaseFringes, phase.fringes},
          {capture::kPhaseHeterodyne, phase.heterodyne},
          {capture::kPhaseCoarsest, phase.coarsest}};
}

TinyCapture tiny_phase_capture(PhaseParameters phase) {
  SceneOptions options;
  options.camera_size = {24, 20};
  options.projector_size = {phase.projector_width, phase.projector_height};
  const capture::ProtocolOptions protocol{options.projector_size, phase.dot_spacing, "phase", phase_parameters(phase)};
  TinyCapture capture{make_plane_scene(options), capture::make_protocol(protocol), {}};
  capture.frames = render_frames(capture.scene, capture.sequence, protocol, 1.0, 7);
  return capture;
}

TransportSetup phase_setup_for(const std::vector<cv::Mat>& frames, PhaseParameters phase, int k) {
  TransportSetup setup = setup_for(frames, {phase.projector_width, phase.projector_height}, phase.dot_spacing, k);
  setup.family = "phase";
  setup.parameters = phase_parameters(phase);
  return setup;
}

std::optional<TinyCapture> tiny_gray_capture_over_batches() {
  constexpr int kBatch = RF_GRAY_PAIR_BATCH;
  const int pairs = kBatch + std::min(2, kBatch - 1);
  if (kBatch < 2 || pairs > 20) return std::nullopt;
  // 3/4 of 2^b projector pixels take b Gray bits (gray_bits rounds log2 up).
  const auto size_of = [](int bits) { return (1 << bits) - ((1 << bits) >> 2); };
  return tiny_capture_of({size_of((pairs + 1) / 2), size_of(pairs / 2)}, 0);
}

CompressedTransport tiny_reference_transport(int dot_spacing, int k) {
  const auto capture = tiny_capture(dot_spacing);
  const auto linear = linearize(capture.frames);
  auto reference = make_reference_accumulator(setup_for(linear, capture.scene.projector_size, dot_spacing, k));
  return feed_all(*reference, capture.sequence, linear);
}

Lights random_lights(const CompressedTransport& transport) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  Lights lights{std::vector<float>(transport.projector_pixels()), std::vector<float>(transport.camera_pixels())};
  for (auto& value : lights.projector) value = uniform(random);
  for (auto& value : lights.camera) value = uniform(random);
  return lights;
}

std::vector<cv::Mat> linearize(const std::vector<cv::Mat>& frames) {
  std::vector<cv::Mat> linear;
  for (const auto& frame : frames) {
    cv::Mat value;
    frame.convertTo(value, CV_32F, 1.0 / 255.0);
    linear.push_back(value);
  }
  return linear;
}

CompressedTransport feed_all(GraycodeAccumulator& accumulator, const std::vector<capture::Pattern>& sequence,
                             const std::vector<cv::Mat>& linear_frames) {
  return feed_all(accumulator, sequence, linear_frames, linear_frames);
}

CompressedTransport feed_all(GraycodeAccumulator& accumulator, const std::vector<capture::Pattern>& sequence,
                             const std::vector<cv::Mat>& frames, const std::vector<cv::Mat>& linear_frames) {
  cv::Mat white;
  cv::Mat black;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const auto& pattern = sequence[i];
    if (pattern.kind == pattern_kind::kWhite) white = linear_frames[i];
    if (pattern.kind == pattern_kind::kBlack) black = linear_frames[i];
    if ((pattern.kind == pattern_kind::kGrayColumn || pattern.kind == pattern_kind::kGrayRow) && !pattern.inverse) {
      // make_protocol puts each inverse right after its pattern.
      const GrayAxis axis = pattern.kind == pattern_kind::kGrayColumn ? GrayAxis::kColumns : GrayAxis::kRows;
      accumulator.add_gray_pair(axis, pattern.bit, frames[i], frames[i + 1]);
    }
  }
  accumulator.finish_gray(white, black);
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    if (sequence[i].kind == pattern_kind::kDot) {
      accumulator.add_dot_frame(sequence[i].dot_offset_x, sequence[i].dot_offset_y, frames[i]);
    }
  }
  return accumulator.finish();
}

CompressedTransport feed_plan(TransportAccumulator& accumulator, const std::string& family,
                              const std::vector<capture::Pattern>& sequence, const std::vector<cv::Mat>& frames,
                              const std::vector<cv::Mat>& linear_frames) {
  capture::CaptureManifest manifest;
  manifest.family = family;
  cv::Mat white;
  cv::Mat black;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    manifest.frames.push_back({});
    manifest.frames.back().pattern = sequence[i];
    if (sequence[i].kind == pattern_kind::kWhite) white = linear_frames[i];
    if (sequence[i].kind == pattern_kind::kBlack) black = linear_frames[i];
  }
  for (const TransportStep& step : decoding_family(family).plan(manifest)) {
    if (step.op == kFinishStep) break;
    std::vector<cv::Mat> step_frames;
    for (const std::size_t i : step.frames) step_frames.push_back(frames[i]);
    accumulator.add(step, step_frames, white, black);
  }
  return accumulator.finish();
}

TransportSetup setup_for(const std::vector<cv::Mat>& frames, cv::Size projector_size, int dot_spacing, int k) {
  TransportSetup setup;
  setup.camera_size = frames.front().size();
  setup.projector_size = projector_size;
  setup.dot_spacing = dot_spacing;
  setup.entries_per_pixel = k;
  return setup;
}

}  // namespace rfrecon::transport::testing
