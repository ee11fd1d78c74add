// The Session: devices and programs kept between calls, each call with the caller's log, progress and cancellation.
#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <utility>

#include "host/cl/device_selection.h"
#include "host/cl/program_cache.h"
#include "host/core/log_forwarding.h"
#include "host/pipeline/calibrate_rig.h"
#include "host/pipeline/dual_image.h"
#include "host/pipeline/reconstruct_scan.h"
#include "host/pipeline/transport_capture.h"
#include "rfrecon/rfrecon.h"
#include "sim/builtin_scenes.h"
#include "sim/simulate.h"

namespace rfrecon {

struct Session::State {
  SessionOptions options;
  std::vector<cl::DeviceContext> devices;
  cl::ProgramCache programs;
  std::atomic<bool> cancel_requested{false};
  std::mutex calls;  // one call at a time: calls from several threads take turns

  // Throws Cancelled, once, when cancel() was called.
  void check_cancel() {
    if (cancel_requested.exchange(false)) throw Cancelled("cancelled (Session::cancel)");
  }

  // What every call of the session runs within: its log and progress callbacks, and a cancellation check first.
  class Call {
   public:
    explicit Call(State& state)
        : turn_(state.calls),
          logs_(state.options.log ? LogCallback([log = state.options.log](int level, const std::string& text) {
            log(static_cast<LogLevel>(level), text);
          })
                                  : LogCallback()),
          progress_(state.options.progress) {
      state.check_cancel();
    }

   private:
    std::lock_guard<std::mutex> turn_;
    ScopedLogForwarding logs_;
    ScopedProgressObserver progress_;
  };

  // T^T 1 or, with `primal`, T 1 as an image that owns its memory.
  cv::Mat view(const Transport& transport, bool primal) {
    auto run = pipeline::view_product(transport, primal, devices, programs);
    return cv::Mat(run.size, CV_32F, run.product.image.data()).clone();
  }

  // The capture's frames, each read checking for cancellation first.
  capture::FrameSource frames_of(const Capture& capture) {
    const capture::FrameSource source =
        capture.frame_ ? capture::FrameSource::from_callback(capture.frame_, capture.name_) : capture.dir_;
    return source.with_check([this] { check_cancel(); });
  }
};

Session::Session(SessionOptions options) : state_(std::make_unique<State>()) {
  state_->options = std::move(options);
  const State::Call call(*state_);
  state_->devices = cl::open_devices(state_->options.devices);
}

Session::~Session() = default;
Session::Session(Session&&) noexcept = default;
Session& Session::operator=(Session&&) noexcept = default;

std::vector<std::string> Session::devices() const {
  std::vector<std::string> names;
  for (const auto& device : state_->devices) names.push_back(cl::describe(device.info()));
  return names;
}

void Session::cancel() { state_->cancel_requested = true; }

TransportResult Session::transport(const Capture& capture, const TransportOptions& options) {
  const State::Call call(*state_);
  transport::TransportSetup setup;
  setup.entries_per_pixel = options.entries_per_pixel;
  setup.thresholds = options.thresholds;
  transport::check_setup_ranges(setup);
  auto run = pipeline::transport_frames(state_->frames_of(capture), capture.manifest(), setup, {},
                                        transport::kDefaultReaders, state_->devices, state_->programs);
  TransportResult result;
  result.transport = std::move(run.run.transport);
  for (const auto& finding : run.run.checks.findings) result.warnings.push_back(finding.message);
  result.decoded_pixels = run.decoded_pixels();
  return result;
}

cv::Mat Session::dual_image(const Transport& transport) {
  const State::Call call(*state_);
  return state_->view(transport, false);
}

cv::Mat Session::primal_image(const Transport& transport) {
  const State::Call call(*state_);
  return state_->view(transport, true);
}

CalibrationResult Session::calibrate(const std::vector<Capture>& poses, const Board& board,
                                     const CalibrationOptions& options) {
  const State::Call call(*state_);
  std::vector<std::string> names;
  std::map<std::string, int> uses;
  for (const auto& pose : poses) {
    names.push_back(pose.dir_.empty() ? pose.name() : pipeline::pose_name(pose.dir_));
    ++uses[names.back()];
  }
  std::vector<pipeline::PoseCapture> captures;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    // Names that several poses share (frames in memory all default to one) become "NAME 3" by position.
    const std::string name = uses[names[i]] > 1 ? names[i] + " " + std::to_string(i) : names[i];
    captures.push_back({name, state_->frames_of(poses[i]), poses[i].manifest()});
  }
  auto run = pipeline::calibrate_poses(captures, board, options, nullptr, state_->devices, state_->programs);
  CalibrationResult result;
  result.rig = std::move(run.calibration.rig);
  result.view_names = std::move(run.view_names);
  result.warnings = std::move(run.calibration.warnings);
  for (const auto& decision : run.calibration.gating) result.warnings.push_back("gating: " + decision.describe());
  return result;
}

ReconstructResult Session::reconstruct(const Transport& transport, const Rig& rig, const ReconstructOptions& options) {
  const State::Call call(*state_);
  depth::check_depth_options(options);
  pipeline::ReconstructRequest request;
  request.depth = options;
  auto run =
      pipeline::reconstruct_transport(transport, rig, "the rig in memory", request, state_->devices, state_->programs);
  return {std::move(run.depth.maps), std::move(run.depth.summary), rig};
}

CaptureReport Session::capture(Projector& projector, Camera& camera, const CaptureOptions& options,
                               const std::filesystem::path& out_dir, bool force) {
  const State::Call call(*state_);
  CaptureOptions checked = options;
  checked.before_pattern = [this, before = options.before_pattern] {
    state_->check_cancel();
    if (before) before();
  };
  return acquire::capture_scan(projector, camera, checked, out_dir, force);
}

std::vector<std::filesystem::path> Session::simulate(const std::string& scene, const std::filesystem::path& out_dir,
                                                     const SimulateRequest& request) {
  const State::Call call(*state_);
  sim::SceneChanges changes;
  changes.rig = request.rig;
  changes.camera_size = request.camera_size;
  changes.projector_size = request.projector_size;
  changes.seed = request.seed;
  sim::simulate(sim::resolve_scene(scene, changes), out_dir, {0, request.force, sim::scene_files(scene)});
  const std::filesystem::path capture = out_dir / "capture";
  if (std::filesystem::exists(capture / "manifest.json")) return {capture};
  std::vector<std::filesystem::path> poses;
  for (const auto& entry : std::filesystem::directory_iterator(capture)) {
    if (std::filesystem::exists(entry.path() / "manifest.json")) poses.push_back(entry.path());
  }
  std::sort(poses.begin(), poses.end());
  return poses;
}

}  // namespace rfrecon
