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
#include "host/pipeline/reconstruct_scan.h"
#include "host/pipeline/transport_capture.h"
#include "host/transport/spmv.h"
#include "host/transport/spmv_on_devices.h"
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
  const std::vector<float> ones(transport.camera_pixels(), 1.0f);
  const auto product =
      transport::dual_on_devices(state_->devices, state_->programs, {}, transport::transpose(transport), ones);
  return cv::Mat(transport.setup.projector_size, CV_32F, const_cast<float*>(product.image.data())).clone();
}

cv::Mat Session::primal_image(const Transport& transport) {
  const State::Call call(*state_);
  const std::vector<float> ones(static_cast<std::size_t>(transport.setup.projector_size.area()), 1.0f);
  const auto product = transport::primal_on_devices(state_->devices, state_->programs, {}, transport, ones);
  return cv::Mat(transport.setup.camera_size, CV_32F, const_cast<float*>(product.image.data())).clone();
}

CalibrationResult Session::calibrate(const std::vector<Capture>& poses, const Board& board,
                                     const CalibrationOptions& options) {
  const State::Call call(*state_);
  std::map<std::string, int> uses;
  for (const auto& pose : poses) ++uses[pose.name()];
  std::vector<pipeline::PoseCapture> captures;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    // Names that several poses share (frames in memory all default to one) become "NAME 3" by position.
    const std::string name = poses[i].dir_.empty() ? poses[i].name() : poses[i].dir_.filename().string();
    captures.push_back({uses[poses[i].name()] > 1 ? name + " " + std::to_string(i) : name, state_->frames_of(poses[i]),
                        poses[i].manifest()});
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

std::vector<std::filesystem::path> Session::simulate(const std::string& scene, const std::filesystem::path& out_dir,
                                                     const SimulateRequest& request) {
  const State::Call call(*state_);
  sim::Scene resolved = sim::resolve_scene(scene, request.rig);
  if (!request.camera_size.empty()) sim::resize_device(resolved.camera, request.camera_size);
  if (!request.projector_size.empty()) sim::resize_device(resolved.projector, request.projector_size);
  if (request.seed) resolved.render.seed = *request.seed;
  std::vector<std::filesystem::path> inputs;
  std::error_code error;
  if (std::filesystem::is_regular_file(scene, error)) inputs.emplace_back(scene);
  sim::simulate(resolved, out_dir, {0, request.force, inputs});
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
