// Streaming of capture frames through the decode and compression accumulators, with progress and timings.
#include "host/transport/compute_transport.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <utility>

#include "host/capture/frame_read_ahead.h"
#include "host/core/errors.h"
#include "host/core/progress.h"
#include "host/core/stage_clock.h"
#include "host/sched/block_runner.h"
#include "host/transport/gray_decision.h"
#include "host/transport/gray_subpixel.h"

namespace rfrecon::transport {

namespace fs = std::filesystem;
using capture::PatternKind;

capture::CaptureManifest open_capture(const fs::path& capture_dir, const std::string& layout, cv::Size projector_size,
                                      capture::FramePaths frame_paths, int bit_depth) {
  if (layout.empty() || layout == "manifest") {
    if (bit_depth != 0) throw UsageError("--bit-depth is for --layout opencv-graycode; a manifest declares bit_depth");
    return capture::read_manifest(capture_dir, frame_paths);
  }
  if (layout != "opencv-graycode") {
    throw InputError("unknown capture layout '" + layout + "' (expected 'manifest' or 'opencv-graycode')");
  }
  if (projector_size.empty()) throw InputError("--layout opencv-graycode needs --projector WxH");
  return capture::manifest_from_opencv_layout(capture_dir, projector_size, bit_depth);
}

namespace {

struct FrameIndex {
  std::size_t white = 0;
  std::size_t black = 0;
  std::map<std::pair<GrayAxis, int>, std::pair<std::size_t, std::size_t>> gray_pairs;  // -> (pattern, inverse)
  std::vector<std::size_t> dots;
};

// capture::validate_manifest has checked that the protocol is complete.
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

// One call on the accumulator and the capture frames it takes (indices into the manifest).
struct Step {
  enum class Kind { kGrayPair, kFinishGray, kDot, kFinish };
  Kind kind;
  std::vector<std::size_t> frames;  // the pattern and inverse of a Gray pair; the dot frame; none otherwise
  GrayAxis axis = GrayAxis::kColumns;
  int bit = 0;
  int offset_x = 0;
  int offset_y = 0;

  const char* stage() const { return kind == Kind::kDot ? "compress" : kind == Kind::kFinish ? "finalize" : "decode"; }
};

// Gray pairs, finish_gray, dot frames, finish: the order TransportAccumulator requires.
std::vector<Step> plan_steps(const FrameIndex& index, const capture::CaptureManifest& manifest) {
  std::vector<Step> steps;
  for (const auto& pair : index.gray_pairs) {
    Step step{Step::Kind::kGrayPair, {pair.second.first, pair.second.second}};
    step.axis = pair.first.first;
    step.bit = pair.first.second;
    steps.push_back(step);
  }
  steps.push_back({Step::Kind::kFinishGray, {}});
  for (const std::size_t i : index.dots) {
    Step step{Step::Kind::kDot, {i}};
    step.offset_x = manifest.frames[i].pattern.dot_offset_x;
    step.offset_y = manifest.frames[i].pattern.dot_offset_y;
    steps.push_back(step);
  }
  steps.push_back({Step::Kind::kFinish, {}});
  return steps;
}

// Consecutive steps given to the devices as one call per block, steps [first, end): up to RF_FRAME_BATCH frames of
// Gray pairs (with finish_gray after the last) or of dot frames, the frames of one kernel launch; finish alone. Each
// call is a hand-over between threads (the tile timeout's), so one per launch rather than one per frame.
struct Launch {
  std::size_t first = 0;
  std::size_t end = 0;
};

// Whether `step` may share the launch that `first` began.
bool same_launch(const Step& first, const Step& step) {
  switch (step.kind) {
    case Step::Kind::kGrayPair:
    case Step::Kind::kFinishGray:
      return first.kind == Step::Kind::kGrayPair;
    case Step::Kind::kDot:
      return first.kind == Step::Kind::kDot;
    case Step::Kind::kFinish:
      break;
  }
  return false;
}

std::vector<Launch> plan_launches(const std::vector<Step>& steps) {
  std::vector<Launch> launches;
  std::size_t frames = 0;  // in the last launch
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::size_t more = steps[i].frames.size();
    if (!launches.empty() && same_launch(steps[launches.back().first], steps[i]) &&
        frames + more <= static_cast<std::size_t>(RF_FRAME_BATCH)) {
      launches.back().end = i + 1;
      frames += more;
    } else {
      launches.push_back({i, i + 1});
      frames = more;
    }
  }
  return launches;
}

// Feeds one step to an accumulator: `frames` are the step's frames, white/black the capture's (or row blocks of
// them). The finish step is not applied here (it returns the transport).
void apply(TransportAccumulator& accumulator, const Step& step, const std::vector<cv::Mat>& frames,
           const cv::Mat& white, const cv::Mat& black) {
  switch (step.kind) {
    case Step::Kind::kGrayPair:
      accumulator.add_gray_pair(step.axis, step.bit, frames[0], frames[1]);
      break;
    case Step::Kind::kFinishGray:
      accumulator.finish_gray(white, black);
      break;
    case Step::Kind::kDot:
      accumulator.add_dot_frame(step.offset_x, step.offset_y, frames[0]);
      break;
    case Step::Kind::kFinish:
      break;
  }
}

// The capture opened for streaming: manifest with the camera size, white and black in memory, the setup resolved.
struct OpenedCapture {
  capture::CaptureManifest manifest;
  FrameIndex index;
  cv::Mat white;
  cv::Mat black;
  TransportSetup setup;
};

OpenedCapture open_frames(const capture::FrameSource& frames, capture::CaptureManifest manifest, TransportSetup setup,
                          const std::function<cv::Mat(const capture::CaptureManifest&, std::size_t)>& load) {
  capture::validate_manifest(manifest, frames.name());  // a callback's manifest was never read from a file
  OpenedCapture opened;
  opened.index = index_frames(manifest);
  opened.white = load(manifest, opened.index.white);
  if (manifest.camera_size.empty()) manifest.camera_size = opened.white.size();  // later frames must match the first
  opened.black = load(manifest, opened.index.black);
  double brightest = 0.0;
  cv::minMaxLoc(opened.white - opened.black, nullptr, &brightest);
  if (brightest <= setup.thresholds.black) {
    throw InputError("all-dark capture: no pixel of " + frames.describe(manifest, opened.index.white) +
                     " is brighter than " + frames.describe(manifest, opened.index.black) + " by more than " +
                     "the black threshold " + std::to_string(setup.thresholds.black) + " (maximum difference " +
                     std::to_string(brightest) + ")" +
                     (manifest.bit_depth == 16 ? "; if the 16-bit files hold 10- or 12-bit data, declare bit_depth "
                                                 "(--bit-depth with --layout opencv-graycode)"
                                               : ""));
  }
  setup.camera_size = manifest.camera_size;
  setup.projector_size = manifest.projector_size;
  setup.dot_spacing = manifest.dot_spacing;
  setup.thresholds = resolve_thresholds(setup.thresholds, manifest.bit_depth);
  opened.setup = setup;
  opened.manifest = std::move(manifest);
  return opened;
}

// Which pixels of Gray-code-only captures are decoded (GrayDecision) and their sub-pixel correspondences
// (GraySubpixel), on the host for both paths alike; captures with the dot grid keep their dot centroids. Timed as
// the stage "subpixel".
class SubpixelGray {
 public:
  SubpixelGray(const OpenedCapture& capture, StageClock& clock) : clock_(clock) {
    if (capture.setup.dot_spacing != 0) return;
    decision_.emplace(capture.white, capture.black);
    gray_.emplace(capture.setup.camera_size);
  }
  // `frames` as the accumulators take them (setup.frame_depth): raw ones are made linear first.
  void add(const Step& step, const std::vector<cv::Mat>& frames, const TransportSetup& setup) {
    if (!gray_ || step.kind != Step::Kind::kGrayPair) return;
    clock_.time("subpixel", [&] {
      const bool linear = setup.frame_depth == CV_32F;
      const cv::Mat pattern = linear ? frames[0] : capture::linearize_samples(frames[0], setup.samples);
      const cv::Mat inverse = linear ? frames[1] : capture::linearize_samples(frames[1], setup.samples);
      decision_->add_gray_pair(step.axis, gray_bit_mask(setup, step.axis, step.bit), pattern, inverse);
      gray_->add_gray_pair(step.axis, pattern, inverse);
    });
  }
  // The decision's counts for Gray-code-only captures.
  std::optional<GrayDecisionCounts> refine(CompressedTransport& transport) const {
    if (!gray_) return std::nullopt;
    return clock_.time("subpixel", [&] {
      const GrayDecisionCounts counts = decision_->decide(transport);
      gray_->refine(transport);
      return counts;
    });
  }

 private:
  StageClock& clock_;
  std::optional<GrayDecision> decision_;
  std::optional<GraySubpixel> gray_;
};

// The capture checks fed the frames as they are read: white and black at once, then each step's frames. Timed as the
// stage "checks".
class CheckedFrames {
 public:
  CheckedFrames(const OpenedCapture& capture, StageClock& clock) : checks_(capture.manifest), clock_(clock) {
    clock_.time("checks", [&] {
      checks_.add(capture.index.white, capture.white);
      checks_.add(capture.index.black, capture.black);
    });
  }
  void add(const Step& step, const std::vector<cv::Mat>& frames) {
    clock_.time("checks", [&] {
      for (std::size_t i = 0; i < step.frames.size(); ++i) checks_.add(step.frames[i], frames[i]);
    });
  }
  capture::CaptureCheckResult finish() const {
    return clock_.time("checks", [&] { return checks_.finish(); });
  }

 private:
  capture::CaptureChecks checks_;
  StageClock& clock_;
};

// How the Gray and dot frames are loaded for accumulators of `setup`.
capture::FrameForm frame_form(const TransportSetup& setup) {
  return setup.frame_depth == CV_32F ? capture::FrameForm::kLinear : capture::FrameForm::kRaw;
}

// The transport stage's side of the block runner: one device accumulator per camera row block. `storage` (an
// earlier transport's memory) goes to the one block's accumulator, or with several blocks to the stacked result.
class TransportBlocks final : public sched::BlockTask {
 public:
  TransportBlocks(const capture::FrameSource& source, const OpenedCapture& capture, const std::vector<Step>& steps,
                  const std::vector<Launch>& launches, const std::vector<sched::Tile>& blocks,
                  cl::ProgramCache& programs, CompressedTransport storage)
      : source_(source),
        capture_(capture),
        steps_(steps),
        launches_(launches),
        blocks_(blocks),
        programs_(programs),
        storage_(std::move(storage)),
        accumulators_(blocks.size()),
        results_(blocks.size()) {}

  // The current launch's frames, its steps' frames in order.
  void set_frames(std::vector<cv::Mat> frames) { frames_ = std::move(frames); }

  void prepare(sched::Worker& worker) override {
    for (const auto& request : transport_programs(capture_.setup, worker.entry())) {
      programs_.get(worker.device(), request.kernel_path, request.options);
    }
  }

  void create(sched::Worker& worker, std::size_t block) override {
    TransportSetup setup = capture_.setup;
    setup.camera_size.height = static_cast<int>(blocks_[block].size());
    // A block rebuilt on another device after a failure gets new memory: storage_ went to its first accumulator.
    accumulators_[block] = make_device_accumulator(setup, worker.device(), programs_, worker.entry(), {},
                                                   blocks_.size() == 1 ? std::move(storage_) : CompressedTransport{});
  }

  // Runner step `launch`: the launch's steps in order.
  void step(sched::Worker& worker, std::size_t block, std::size_t launch, bool replay) override {
    // Held by the call: after a timeout the block's next owner replaces it while this call may still run.
    const std::shared_ptr<TransportAccumulator> accumulator = accumulators_[block];
    std::size_t next_frame = 0;  // in frames_
    for (std::size_t index = launches_[launch].first; index < launches_[launch].end; ++index) {
      const Step& step = steps_[index];
      if (step.kind == Step::Kind::kFinish) {
        CompressedTransport result = accumulator->finish();
        worker.deliver([&] { results_[block] = std::move(result); });
        return;
      }
      std::vector<cv::Mat> frames;
      for (const std::size_t frame : step.frames) {
        frames.push_back(rows(
            replay ? source_.load(capture_.manifest, frame, frame_form(capture_.setup)) : frames_[next_frame], block));
        ++next_frame;
      }
      apply(*accumulator, step, frames, rows(capture_.white, block), rows(capture_.black, block));
    }
  }

  // The blocks' transports stacked into the whole camera image (moved out, once).
  CompressedTransport assemble() {
    if (blocks_.size() == 1) return std::move(results_.front());  // the whole image: nothing to stack
    CompressedTransport whole = make_empty_transport(capture_.setup, std::move(storage_));
    const auto width = static_cast<std::size_t>(capture_.setup.camera_size.width);
    const auto k = static_cast<std::size_t>(capture_.setup.entries_per_pixel);
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      const std::size_t first = blocks_[b].begin * width;
      const CompressedTransport& part = results_[b];
      std::copy(part.indices.begin(), part.indices.end(), whole.indices.begin() + first * k);
      std::copy(part.weights.begin(), part.weights.end(), whole.weights.begin() + first * k);
      std::copy(part.correspondence.begin(), part.correspondence.end(), whole.correspondence.begin() + 2 * first);
      std::copy(part.gray_x.begin(), part.gray_x.end(), whole.gray_x.begin() + first);
      std::copy(part.gray_y.begin(), part.gray_y.end(), whole.gray_y.begin() + first);
      std::copy(part.flags.begin(), part.flags.end(), whole.flags.begin() + first);
      std::copy(part.direct_energy.begin(), part.direct_energy.end(), whole.direct_energy.begin() + first);
    }
    return whole;
  }

 private:
  // Full-width rows of a continuous frame are continuous, as the accumulators require.
  cv::Mat rows(const cv::Mat& frame, std::size_t block) const {
    return frame.rowRange(static_cast<int>(blocks_[block].begin), static_cast<int>(blocks_[block].end));
  }

  const capture::FrameSource& source_;
  const OpenedCapture& capture_;
  const std::vector<Step>& steps_;
  const std::vector<Launch>& launches_;
  const std::vector<sched::Tile>& blocks_;
  cl::ProgramCache& programs_;
  CompressedTransport storage_;
  std::vector<cv::Mat> frames_;  // the current launch's frames
  std::vector<std::shared_ptr<TransportAccumulator>> accumulators_;
  std::vector<CompressedTransport> results_;
};

}  // namespace

TransportRun compute_transport(const capture::FrameSource& frames, capture::CaptureManifest manifest,
                               TransportSetup setup, const AccumulatorFactory& make_accumulator) {
  StageClock clock;
  Progress progress("transport", manifest.frames.size(), "frames");
  const auto load = [&](const capture::CaptureManifest& with_size, std::size_t i) {
    cv::Mat frame = clock.time("read frames", [&] { return frames.load(with_size, i); });
    progress.advance();
    return frame;
  };
  const OpenedCapture capture = open_frames(frames, std::move(manifest), setup, load);
  auto accumulator = clock.time("setup", [&] { return make_accumulator(capture.setup); });
  SubpixelGray subpixel(capture, clock);
  CheckedFrames checks(capture, clock);
  TransportRun run;
  for (const Step& step : plan_steps(capture.index, capture.manifest)) {
    if (step.kind == Step::Kind::kFinish) {
      run.transport = clock.time(step.stage(), [&] { return accumulator->finish(); });
      break;
    }
    std::vector<cv::Mat> step_frames;
    for (const std::size_t i : step.frames) step_frames.push_back(load(capture.manifest, i));
    clock.time(step.stage(), [&] { apply(*accumulator, step, step_frames, capture.white, capture.black); });
    subpixel.add(step, step_frames, capture.setup);
    checks.add(step, step_frames);
  }
  run.gray_decision = subpixel.refine(run.transport);
  run.transport.white.assign(capture.white.begin<float>(), capture.white.end<float>());
  run.checks = checks.finish();
  run.timings = clock.timings();
  return run;
}

TransportRun compute_transport_on_devices(const capture::FrameSource& frames, capture::CaptureManifest manifest,
                                          TransportSetup setup, std::vector<cl::DeviceContext>& devices,
                                          cl::ProgramCache& programs, const cl::EntryChoice& entries, int readers,
                                          CompressedTransport storage) {
  if (readers < 1) throw UsageError("transport: --readers must be at least 1");
  entries.check_device_count(devices.size());
  StageClock clock;
  Progress progress("transport", manifest.frames.size(), "frames");
  const auto load = [&](const capture::CaptureManifest& with_size, std::size_t i) { return frames.load(with_size, i); };
  OpenedCapture capture = clock.time("read frames", [&] {
    auto opened = open_frames(frames, std::move(manifest), setup, load);
    progress.advance(2);
    return opened;
  });
  // With a linear response the kernels take the camera's raw samples and make them linear in registers: half the
  // bytes of float frames (16-bit cameras), and no conversion on the reader threads.
  if (capture::linear_response(capture.manifest)) {
    capture.setup.frame_depth = capture.manifest.bit_depth == 8 ? CV_8U : CV_16U;
    capture.setup.samples = capture::sample_map(capture.manifest);
  }
  clock.time("build programs", [&] {
    cl::prepare_programs(devices, programs, [&](std::size_t position) {
      return transport_programs(capture.setup, entries.entry_for(position, devices[position].info()));
    });
  });
  const std::vector<Step> steps = plan_steps(capture.index, capture.manifest);
  const std::vector<Launch> launches = plan_launches(steps);
  const auto rows = static_cast<std::size_t>(capture.setup.camera_size.height);
  const std::vector<sched::Tile> blocks =
      sched::split_rows(rows, devices.size() == 1 ? 1 : kBlocksPerDevice * devices.size());
  TransportBlocks task(frames, capture, steps, launches, blocks, programs, std::move(storage));
  sched::BlockOptions options;
  options.items_per_row = static_cast<std::size_t>(capture.setup.camera_size.width);
  options.entries = entries;
  sched::BlockRunner runner(devices, blocks, task, options);

  // The frames of the next steps are read on `readers` threads while the devices work on the current launch.
  std::vector<std::vector<std::size_t>> groups(steps.size());
  std::transform(steps.begin(), steps.end(), groups.begin(), [](const Step& step) { return step.frames; });
  capture::FrameReadAhead read_ahead(frames, capture.manifest, std::move(groups), readers,
                                     2 * static_cast<std::size_t>(readers), frame_form(capture.setup));
  SubpixelGray subpixel(capture, clock);
  CheckedFrames checks(capture, clock);
  for (std::size_t l = 0; l < launches.size(); ++l) {
    std::vector<cv::Mat> launch_frames;
    for (std::size_t i = launches[l].first; i < launches[l].end; ++i) {
      std::vector<cv::Mat> step_frames = clock.time("read frames", [&] { return read_ahead.take(i); });
      progress.advance(steps[i].frames.size());
      subpixel.add(steps[i], step_frames, capture.setup);
      checks.add(steps[i], step_frames);
      launch_frames.insert(launch_frames.end(), step_frames.begin(), step_frames.end());
    }
    task.set_frames(std::move(launch_frames));
    const char* stage = steps[launches[l].first].stage();
    clock.time(stage, [&] { runner.run_step(l, stage); });
  }
  TransportRun run;
  run.transport = clock.time("finalize", [&] { return task.assemble(); });
  run.gray_decision = subpixel.refine(run.transport);
  run.transport.white.assign(capture.white.begin<float>(), capture.white.end<float>());
  run.checks = checks.finish();
  run.timings = clock.timings();
  run.schedule = runner.reports();
  return run;
}

}  // namespace rfrecon::transport
