// Streaming of capture frames through the decode and compression accumulators, with progress and timings.
#include "host/transport/compute_transport.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <string_view>
#include <utility>

#include "host/capture/frame_read_ahead.h"
#include "host/capture/pattern_family.h"
#include "host/core/errors.h"
#include "host/core/progress.h"
#include "host/core/stage_clock.h"
#include "host/sched/block_runner.h"
#include "host/transport/decoding_family.h"

namespace rfrecon::transport {

namespace fs = std::filesystem;

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

// The white and black frames' indices (capture::validate_manifest has checked that there is one of each).
struct WhiteBlack {
  std::size_t white = 0;
  std::size_t black = 0;
};

WhiteBlack find_white_black(const capture::CaptureManifest& manifest) {
  WhiteBlack found;
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    if (manifest.frames[i].pattern.kind == capture::pattern_kind::kWhite) found.white = i;
    if (manifest.frames[i].pattern.kind == capture::pattern_kind::kBlack) found.black = i;
  }
  return found;
}

bool is_finish(const TransportStep& step) { return step.op == kFinishStep; }

// Consecutive steps given to the devices as one call per block, steps [first, end): up to RF_FRAME_BATCH frames of
// steps of one stage (Gray pairs and finish_gray, or dot frames), the frames of one kernel launch; finish alone. Each
// call is a hand-over between threads (the tile timeout's), so one per launch rather than one per frame.
struct Launch {
  std::size_t first = 0;
  std::size_t end = 0;
};

// Whether `step` may share the launch that `first` began: the same stage, and neither ends the capture.
bool same_launch(const TransportStep& first, const TransportStep& step) {
  return !is_finish(first) && !is_finish(step) && std::string_view(first.stage) == step.stage;
}

std::vector<Launch> plan_launches(const std::vector<TransportStep>& steps) {
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

// The capture opened for streaming: manifest with the camera size, white and black in memory, the setup resolved.
struct OpenedCapture {
  capture::CaptureManifest manifest;
  const DecodingFamily* family = nullptr;
  WhiteBlack index;
  cv::Mat white;
  cv::Mat black;
  TransportSetup setup;
};

OpenedCapture open_frames(const capture::FrameSource& frames, capture::CaptureManifest manifest, TransportSetup setup,
                          const std::function<cv::Mat(const capture::CaptureManifest&, std::size_t)>& load) {
  capture::validate_manifest(manifest, frames.name());  // a callback's manifest was never read from a file
  OpenedCapture opened;
  opened.family = &decoding_family(manifest.family);
  opened.index = find_white_black(manifest);
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
  // Without dot frames each pixel's row holds its decoded projector pixel alone: one entry, not K.
  if (setup.dot_spacing == 0) setup.entries_per_pixel = 1;
  setup.family = manifest.family;
  const capture::PatternFamily& patterns = capture::pattern_family(manifest.family);
  for (const auto& parameter : patterns.parameters()) {
    setup.parameters[parameter.name] =
        capture::family_parameter(patterns, capture::protocol_options(manifest), parameter.name);
  }
  setup.thresholds = resolve_thresholds(setup.thresholds, manifest.bit_depth);
  opened.setup = setup;
  opened.manifest = std::move(manifest);
  return opened;
}

// The family's host refinement, when it has one, fed each step's frames. Timed as the stage "subpixel".
class Refinement {
 public:
  Refinement(const OpenedCapture& capture, StageClock& clock)
      : clock_(clock), refinement_(capture.family->refinement(capture.setup, capture.white, capture.black)) {}
  void add(const TransportStep& step, const std::vector<cv::Mat>& frames) {
    if (refinement_) clock_.time("subpixel", [&] { refinement_->add(step, frames); });
  }
  std::optional<GrayDecisionCounts> refine(CompressedTransport& transport) const {
    if (!refinement_) return std::nullopt;
    return clock_.time("subpixel", [&] { return refinement_->refine(transport); });
  }

 private:
  StageClock& clock_;
  std::unique_ptr<TransportRefinement> refinement_;
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
  void add(const TransportStep& step, const std::vector<cv::Mat>& frames) {
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
  TransportBlocks(const capture::FrameSource& source, const OpenedCapture& capture,
                  const std::vector<TransportStep>& steps, const std::vector<Launch>& launches,
                  const std::vector<sched::Tile>& blocks, cl::ProgramCache& programs, CompressedTransport storage)
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
    for (const auto& request : capture_.family->programs(capture_.setup, worker.entry())) {
      programs_.get(worker.device(), request.kernel_path, request.options);
    }
  }

  void create(sched::Worker& worker, std::size_t block) override {
    TransportSetup setup = capture_.setup;
    setup.camera_size.height = static_cast<int>(blocks_[block].size());
    // A block rebuilt on another device after a failure gets new memory: storage_ went to its first accumulator.
    accumulators_[block] =
        capture_.family->make_device(setup, worker.device(), programs_, worker.entry(),
                                     blocks_.size() == 1 ? std::move(storage_) : CompressedTransport{});
  }

  // Runner step `launch`: the launch's steps in order.
  void step(sched::Worker& worker, std::size_t block, std::size_t launch, bool replay) override {
    // Held by the call: after a timeout the block's next owner replaces it while this call may still run.
    const std::shared_ptr<TransportAccumulator> accumulator = accumulators_[block];
    std::size_t next_frame = 0;  // in frames_
    for (std::size_t index = launches_[launch].first; index < launches_[launch].end; ++index) {
      const TransportStep& step = steps_[index];
      if (is_finish(step)) {
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
      accumulator->add(step, frames, rows(capture_.white, block), rows(capture_.black, block));
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
      std::copy(part.pixel_x.begin(), part.pixel_x.end(), whole.pixel_x.begin() + first);
      std::copy(part.pixel_y.begin(), part.pixel_y.end(), whole.pixel_y.begin() + first);
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
  const std::vector<TransportStep>& steps_;
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
  const OpenedCapture capture = open_frames(frames, std::move(manifest), std::move(setup), load);
  auto accumulator = clock.time("setup", [&] { return make_accumulator(capture.setup); });
  Refinement refinement(capture, clock);
  CheckedFrames checks(capture, clock);
  TransportRun run;
  for (const TransportStep& step : capture.family->plan(capture.manifest)) {
    if (is_finish(step)) {
      run.transport = clock.time(step.stage, [&] { return accumulator->finish(); });
      break;
    }
    std::vector<cv::Mat> step_frames;
    for (const std::size_t i : step.frames) step_frames.push_back(load(capture.manifest, i));
    clock.time(step.stage, [&] { accumulator->add(step, step_frames, capture.white, capture.black); });
    refinement.add(step, step_frames);
    checks.add(step, step_frames);
  }
  run.gray_decision = refinement.refine(run.transport);
  run.transport.white.assign(capture.white.begin<float>(), capture.white.end<float>());
  run.checks = checks.finish();
  run.transport.camera_noise = run.checks.camera_noise;
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
    auto opened = open_frames(frames, std::move(manifest), std::move(setup), load);
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
      return capture.family->programs(capture.setup, entries.entry_for(position, devices[position].info()));
    });
  });
  const std::vector<TransportStep> steps = capture.family->plan(capture.manifest);
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
  std::transform(steps.begin(), steps.end(), groups.begin(), [](const TransportStep& step) { return step.frames; });
  capture::FrameReadAhead read_ahead(frames, capture.manifest, std::move(groups), readers,
                                     2 * static_cast<std::size_t>(readers), frame_form(capture.setup));
  Refinement refinement(capture, clock);
  CheckedFrames checks(capture, clock);
  for (std::size_t l = 0; l < launches.size(); ++l) {
    std::vector<cv::Mat> launch_frames;
    for (std::size_t i = launches[l].first; i < launches[l].end; ++i) {
      std::vector<cv::Mat> step_frames = clock.time("read frames", [&] { return read_ahead.take(i); });
      progress.advance(steps[i].frames.size());
      refinement.add(steps[i], step_frames);
      checks.add(steps[i], step_frames);
      launch_frames.insert(launch_frames.end(), step_frames.begin(), step_frames.end());
    }
    task.set_frames(std::move(launch_frames));
    const char* stage = steps[launches[l].first].stage;
    clock.time(stage, [&] { runner.run_step(l, stage); });
  }
  TransportRun run;
  run.transport = clock.time("finalize", [&] { return task.assemble(); });
  run.gray_decision = refinement.refine(run.transport);
  run.transport.white.assign(capture.white.begin<float>(), capture.white.end<float>());
  run.checks = checks.finish();
  run.transport.camera_noise = run.checks.camera_noise;
  run.timings = clock.timings();
  run.schedule = runner.reports();
  return run;
}

}  // namespace rfrecon::transport
