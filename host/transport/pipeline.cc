// Streaming of capture frames through the decode and compression accumulators, with progress and timings.
#include "host/transport/pipeline.h"

#include <chrono>
#include <map>
#include <utility>

#include "host/common/errors.h"
#include "host/common/progress.h"

namespace rfrecon::transport {

namespace fs = std::filesystem;
using capture::PatternKind;

capture::CaptureManifest open_capture(const fs::path& capture_dir, const std::string& layout, cv::Size projector_size) {
  if (layout.empty() || layout == "manifest") return capture::read_manifest(capture_dir);
  if (layout != "opencv-graycode") {
    throw InputError("unknown capture layout '" + layout + "' (expected 'manifest' or 'opencv-graycode')");
  }
  if (projector_size.empty()) throw InputError("--layout opencv-graycode needs --projector WxH");
  return capture::manifest_from_opencv_layout(capture_dir, projector_size);
}

namespace {

// Accumulates wall time per named stage, in first-use order.
class StageClock {
 public:
  template <typename F>
  auto time(const std::string& stage, F&& work) {
    const auto start = std::chrono::steady_clock::now();
    struct Record {
      StageClock* clock;
      const std::string& stage;
      std::chrono::steady_clock::time_point start;
      ~Record() { clock->add(stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()); }
    } record{this, stage, start};
    return work();
  }

  std::vector<StageTiming> timings() const { return timings_; }

 private:
  void add(const std::string& stage, double seconds) {
    for (auto& timing : timings_) {
      if (timing.stage == stage) {
        timing.seconds += seconds;
        return;
      }
    }
    timings_.push_back({stage, seconds});
  }

  std::vector<StageTiming> timings_;
};

struct FrameIndex {
  std::size_t white = 0;
  std::size_t black = 0;
  std::map<std::pair<GrayAxis, int>, std::pair<std::size_t, std::size_t>> gray_pairs;  // -> (pattern, inverse)
  std::vector<std::size_t> dots;
};

// read_manifest / manifest_from_opencv_layout have checked that the protocol is complete.
FrameIndex index_frames(const capture::CaptureManifest& manifest) {
  FrameIndex index;
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    const auto& pattern = manifest.frames[i].pattern;
    switch (pattern.kind) {
      case PatternKind::kWhite:
        index.white = i;
        break;
      case PatternKind::kBlack:
        index.black = i;
        break;
      case PatternKind::kGrayColumn:
      case PatternKind::kGrayRow: {
        const GrayAxis axis = pattern.kind == PatternKind::kGrayColumn ? GrayAxis::kColumns : GrayAxis::kRows;
        auto& pair = index.gray_pairs[{axis, pattern.bit}];
        (pattern.inverse ? pair.second : pair.first) = i;
        break;
      }
      case PatternKind::kDot:
        index.dots.push_back(i);
        break;
    }
  }
  return index;
}

}  // namespace

TransportRun compute_transport(const fs::path& capture_dir, capture::CaptureManifest manifest, TransportSetup setup,
                               const AccumulatorFactory& make_accumulator) {
  const FrameIndex index = index_frames(manifest);
  StageClock clock;
  Progress progress("transport", manifest.frames.size(), "frames");
  const auto load = [&](std::size_t i) {
    cv::Mat frame = clock.time("read frames", [&] { return capture::load_frame(capture_dir, manifest, i); });
    progress.advance();
    return frame;
  };

  const cv::Mat white = load(index.white);
  if (manifest.camera_size.empty()) manifest.camera_size = white.size();  // later frames must match the first
  const cv::Mat black = load(index.black);
  double brightest = 0.0;
  cv::minMaxLoc(white - black, nullptr, &brightest);
  if (brightest <= setup.thresholds.black) {
    throw InputError("all-dark capture: no pixel of " + (capture_dir / manifest.frames[index.white].file).string() +
                     " is brighter than " + (capture_dir / manifest.frames[index.black].file).string() +
                     " by more than " + "the black threshold " + std::to_string(setup.thresholds.black) +
                     " (maximum difference " + std::to_string(brightest) + ")");
  }

  setup.camera_size = manifest.camera_size;
  setup.projector_size = manifest.projector_size;
  setup.dot_spacing = manifest.dot_spacing;
  auto accumulator = clock.time("setup", [&] { return make_accumulator(setup); });
  for (const auto& pair : index.gray_pairs) {
    const auto [axis, bit] = pair.first;
    const cv::Mat pattern = load(pair.second.first);
    const cv::Mat inverse = load(pair.second.second);
    clock.time("decode", [&, axis = axis, bit = bit] { accumulator->add_gray_pair(axis, bit, pattern, inverse); });
  }
  clock.time("decode", [&] { accumulator->finish_gray(white, black); });
  for (const std::size_t i : index.dots) {
    const cv::Mat frame = load(i);
    const auto& pattern = manifest.frames[i].pattern;
    clock.time("compress", [&] { accumulator->add_dot_frame(pattern.dot_offset_x, pattern.dot_offset_y, frame); });
  }
  TransportRun run;
  run.transport = clock.time("finalize", [&] { return accumulator->finish(); });
  run.timings = clock.timings();
  return run;
}

}  // namespace rfrecon::transport
