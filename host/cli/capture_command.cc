// `rfrecon capture`: shows the patterns on the projector, grabs the camera in step and writes a capture directory
// (or one per board pose); also measures the latency and lists displays and cameras.
#include <chrono>
#include <iostream>
#include <optional>
#include <string>
#include <thread>

#include <spdlog/spdlog.h>

#include "host/cli/commands.h"
#include "host/cli/number_checks.h"
#include "host/cli/protocol_option.h"
#include "host/cli/size_option.h"
#include "host/core/errors.h"
#include "host/drivers/aravis_camera.h"
#include "host/drivers/sdl_projector.h"
#include "host/pipeline/capture_rig.h"

namespace rfrecon::cli {

namespace {

struct CaptureCommandOptions {
  pipeline::CaptureRequest request;
  std::shared_ptr<capture::ProtocolOptions> protocol = std::make_shared<capture::ProtocolOptions>();
  std::string projector_size;
  std::string pose_wait = "enter";
  int timeout_ms = 2000;
  bool measure_latency = false;
  bool list_displays = false;
  bool list_cameras = false;
  std::optional<unsigned long long> seed;
  std::optional<double> black_level;
};

// Waits between board poses: for Enter on standard input, or a number of seconds.
std::function<void(int)> pose_waiter(const std::string& wait, int poses) {
  if (wait == "enter") {
    return [poses](int pose) {
      std::cerr << "pose " << pose + 1 << " of " << poses << ": place the board, then press Enter" << std::endl;
      std::string line;
      if (!std::getline(std::cin, line)) {
        throw UsageError("standard input closed while waiting for pose " + std::to_string(pose + 1) +
                         ": give --pose-wait SECONDS to capture poses on a timer");
      }
    };
  }
  std::size_t used = 0;
  double seconds = -1.0;
  try {
    seconds = std::stod(wait, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != wait.size() || !(seconds >= 0.0 && seconds <= 3600.0)) {
    throw UsageError("--pose-wait '" + wait + "': expected 'enter' or seconds from 0 to 3600");
  }
  return [seconds, poses](int pose) {
    spdlog::info("capture: pose {} of {} in {} s: place the board", pose + 1, poses, seconds);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  };
}

void run_capture(CaptureCommandOptions& o) {
  if (o.list_displays) {
    for (const auto& line : drivers::list_displays()) std::cout << line << "\n";
    return;
  }
  if (o.list_cameras) {
    for (const auto& id : drivers::list_aravis_cameras()) std::cout << "aravis:" << id << "\n";
    return;
  }
  if (o.request.camera.empty()) throw UsageError("--camera is required");
  auto& request = o.request;
  request.seed = o.seed;
  request.run.black_level_dn = o.black_level;
  request.run.timeout = std::chrono::milliseconds(o.timeout_ms);
  request.run.protocol.family = o.protocol->family;
  request.run.protocol.dot_spacing = o.protocol->dot_spacing;
  request.run.protocol.parameters = o.protocol->parameters;
  if (!o.projector_size.empty()) request.run.protocol.projector_size = parse_size(o.projector_size, "--projector-size");
  if (o.measure_latency) {
    const int frames = pipeline::measure_latency(request);
    std::cout << "latency: " << frames << " frames\n";
    return;
  }
  if (request.output.empty()) throw UsageError("-o/--output is required (or give --measure-latency)");
  if (request.poses > 0) request.before_pose = pose_waiter(o.pose_wait, request.poses);
  const auto reports = pipeline::capture(request);
  for (const auto& report : reports) {
    spdlog::info(
        "capture: {} frames ({} grabs, latency {} frames, {} repeated frames and {} Gray pairs captured again)",
        report.manifest.frames.size(), report.grabs, report.latency_frames, report.repeated_frames,
        report.recaptured_pairs);
  }
  spdlog::info("capture: wrote {}", request.output.string());
}

}  // namespace

void add_capture_command(CLI::App& app) {
  auto o = std::make_shared<CaptureCommandOptions>();
  auto& r = o->request;
  auto* command = app.add_subcommand("capture", "Show the patterns on a projector and capture them with a camera");
  command->add_option("-o,--output", r.output, "Capture directory (created; with --poses, one pose_NN per pose)");
  command->add_option("--camera", r.camera, "aravis[:ID] | v4l2:DEVICE | gst:PIPELINE | sim:SCENE");
  command->add_option("--projector", r.projector, "display:N: SDL2's display N, full screen (--list-displays)");
  command->add_option("--projector-size", o->projector_size, "Pattern size WxH (default: the display's size)");
  add_protocol_options(*command, o->protocol);
  command
      ->add_option("--exposures", r.run.exposures_us,
                   "Exposure times in microseconds; several are merged per pattern (HDR)")
      ->delimiter(',')
      ->check(finite_positive());
  command
      ->add_option("--latency-frames", r.run.latency_frames,
                   "Frames to discard after each pattern (default: "
                   "measured)")
      ->check(CLI::Range(0, 100));
  command->add_flag("--measure-latency", o->measure_latency, "Measure the latency, print it and capture nothing");
  command->add_option("--camera-response", r.run.camera_response, "linear or gamma:G (the camera's response curve)")
      ->capture_default_str();
  command->add_option("--black-level", o->black_level, "Camera reading with no light, DN (default: the camera's own)")
      ->check(finite_non_negative());
  command
      ->add_option("--format", r.run.format,
                   "Frame files: tiff (uncompressed, read at memory speed) or png (smaller, 10x slower to read)")
      ->check(CLI::IsMember({"tiff", "png"}))
      ->capture_default_str();
  command->add_option("--poses", r.poses, "Capture N board poses for calibrate (sim: every view when 0)")
      ->check(CLI::Range(0, 100));
  command->add_option("--pose-wait", o->pose_wait, "Between poses: enter (a key press) or SECONDS")
      ->capture_default_str();
  command->add_option("--timeout", o->timeout_ms, "Longest wait for one frame, milliseconds")
      ->check(CLI::Range(1, 600000))
      ->capture_default_str();
  command->add_option("--seed", o->seed, "Noise seed of a simulated camera (sim:SCENE; default: the scene's)");
  command->add_flag("--list-displays", o->list_displays, "List the displays SDL2 sees and exit");
  command->add_flag("--list-cameras", o->list_cameras, "List the GenICam cameras Aravis finds and exit");
  command->add_flag("--force", r.force, "Replace an existing non-empty output directory");
  command->callback([o] { run_capture(*o); });
}

}  // namespace rfrecon::cli
