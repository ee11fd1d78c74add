// rfrecon's front door: a Session holds the OpenCL devices and the programs built for them, and runs each stage on data
// in memory (docs/api.md). What this header names is the stable API; the layer headers are installed but internal.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "calib/rig.h"
#include "calib/stereo_calibration.h"
#include "host/acquire/capture_run.h"
#include "host/capture/manifest.h"
#include "host/capture/pattern_family.h"
#include "host/cl/error.h"
#include "host/core/errors.h"
#include "host/core/progress.h"
#include "host/depth/depth_option_table.h"
#include "host/depth/reconstruct_depth.h"
#include "host/outputs/reconstruction.h"
#include "host/transport/decoding_family.h"
#include "host/transport/transport_types.h"

namespace rfrecon {

// The data the calls take and return: plain structs of OpenCV matrices and vectors, documented where they are
// defined (and in docs/formats.md, as the files that hold them).
using Rig = calib::StereoRig;    // camera, projector, their pose and rectification (rig.yaml)
using Board = calib::BoardSpec;  // inner corners and square size of the printed checkerboard
using CalibrationOptions = calib::CalibrationOptions;
using Manifest = capture::CaptureManifest;         // a capture's patterns, sizes, bit depth (manifest.json)
using Transport = transport::CompressedTransport;  // T: K strongest entries per camera pixel (T.h5)
using Thresholds = transport::Thresholds;
using ReconstructOptions = depth::DepthOptions;  // .method: a registered depth method's name, "fused" by default
// The depth-method seam (docs/architecture.md#extension-points): subclass DepthMethod, register it, and name it in
// ReconstructOptions.method; depth_method(name) throws InputError listing the names for an unknown one.
using depth::depth_method;
using depth::depth_method_names;
using depth::DepthMethod;
using depth::MethodScan;
using depth::register_depth_method;
// The pattern-family seam (the same page): a PatternFamily (its patterns, images and manifest entries) and its
// DecodingFamily (how its frames stream into T), each registered; `patterns`, `simulate`, `capture`, `transport` and
// the manifest reader then take the family by name.
using capture::Pattern;
using capture::pattern_family_names;
using capture::PatternFamily;
using capture::ProtocolOptions;
using capture::register_pattern_family;
using transport::DecodingFamily;
using transport::kFinishStep;
using transport::register_decoding_family;
using transport::TransportAccumulator;
using transport::TransportRefinement;
using transport::TransportStep;
// A tuning option of ReconstructOptions by its command-line name ("crease", "sigma-step": docs/cli.md), checked
// against its documented range (UsageError naming it otherwise); depth_option_table() lists them.
using depth::depth_option_table;
using depth::set_depth_option;
using Reconstruction = outputs::Reconstruction;  // depth_mm, points_mm, normals, confidence, white

// The capture seams (docs/capture.md): implement Camera for a vendor SDK (and Projector for a display of your own), or
// open the drivers by the command line's specs (open_camera, open_projector).
using Camera = acquire::Camera;
using CameraFormat = acquire::CameraFormat;
using Projector = acquire::Projector;
using CaptureOptions = acquire::CaptureRunOptions;  // dot spacing, exposures (HDR), latency, retries, timeout
using CaptureReport = acquire::CaptureRunReport;    // the manifest written, latency, grabs, frames taken again

// The errors, each with the tool's exit code (docs/cli.md): UsageError (2), InputError (3), ProcessingError (6),
// OutputError (8) and HardwareError (10: a camera or display missing or failing) of host/core/errors.h, and these
// from the OpenCL side:
using DeviceSelectionError = cl::DeviceSelectionError;  // 4: no device matches the selection, or none is installed
using OpenCLError = cl::ClError;                        // 5: an OpenCL call or kernel build failed

// A call stopped by Session::cancel (130).
class Cancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class LogLevel { kDebug, kInfo, kWarning, kError };

struct SessionOptions {
  std::string devices;  // the --devices syntax (docs/cli.md): "" for $RFRECON_DEVICES, else every OpenCL device
  // The library's log lines while this session's calls run, from any of its threads, one at a time; empty: spdlog's
  // default logger (stderr). The library logs process-wide, so calls of two sessions running at once with callbacks
  // each see the other's lines.
  std::function<void(LogLevel level, const std::string& message)> log;
  // Each step of a long call ("transport", 12 of 94 frames; "calibrate", 2 of 4 poses), from the thread that made it.
  // Neither callback may throw or call the library, except Session::cancel.
  std::function<void(const ProgressStep& step)> progress;
};

// Where a capture's frames come from, with their manifest.
class Capture {
 public:
  // The directory `rfrecon transport` reads: manifest.json, or with layout "opencv-graycode" OpenCV's Gray-code files
  // sorted by name for `projector_size` (bit_depth 0: the files'). Throws InputError naming the file.
  static Capture from_directory(const std::filesystem::path& dir, const std::string& layout = "",
                                cv::Size projector_size = {}, int bit_depth = 0);
  // Frame i of `manifest` is frames[i]: one channel, CV_8U or CV_16U as manifest.bit_depth says, the camera size.
  // The images are shared, not copied, and must not change until the capture is dropped.
  static Capture from_frames(Manifest manifest, std::vector<cv::Mat> frames, std::string name = "frames in memory");
  // Frame i from a function (a camera SDK after showing pattern i), called from one thread at a time.
  static Capture from_callback(Manifest manifest, std::function<cv::Mat(std::size_t index)> frame, std::string name);

  // Frame `index` as the camera gave it (one channel, CV_8U or CV_16U). Throws InputError naming the file or frame.
  cv::Mat frame(std::size_t index) const;
  const Manifest& manifest() const { return manifest_; }
  const std::string& name() const { return name_; }  // stands for the capture in messages

 private:
  friend class Session;
  Capture() = default;
  Manifest manifest_;
  std::string name_;
  std::filesystem::path dir_;                  // from_directory
  std::function<cv::Mat(std::size_t)> frame_;  // the others
};

// The manifest of `family`'s sequence for a rig (graycode: white, black, Gray code of both axes with inverses, then the
// dot grid of `dot_spacing`, 0 for none), frames named as `rfrecon patterns` names them (000_white.png, ...), with the
// camera's fields and the family's `parameters` (pattern_family(family).parameters(); absent ones take their defaults,
// phase: phase_steps, phase_period, phase_ratio). InputError for an unknown family, an option or a parameter it does
// not take, or a parameter out of its range.
Manifest make_manifest(cv::Size projector_size, cv::Size camera_size, int bit_depth = 8, int dot_spacing = 8,
                       const std::string& family = capture::kDefaultFamily,
                       const std::map<std::string, int>& parameters = {});
// The image to show on the projector for frame `index` of `manifest` (CV_8U, projector size).
cv::Mat pattern_image(const Manifest& manifest, std::size_t index);

struct TransportOptions {
  int entries_per_pixel = RF_K;  // K, 1 to 64
  Thresholds thresholds;
};

struct TransportResult {
  Transport transport;
  std::vector<std::string> warnings;  // what the capture checks found (saturated, too dark, non-linear), with advice
  std::size_t decoded_pixels = 0;     // camera pixels with a projector correspondence
};

struct CalibrationResult {
  Rig rig;                              // with rms, per-view errors and standard deviations
  std::vector<std::string> view_names;  // the poses used, in the order of rig.per_view_errors
  std::vector<std::string> warnings;
};

struct ReconstructResult {
  Reconstruction maps;     // on the camera grid, millimetres; white is T's white frame
  nlohmann::json summary;  // what summary.json holds: method, options, counts, per-stage seconds
  Rig rig;                 // the rig the maps were made with
};

// The options of `rfrecon simulate` (docs/cli.md).
struct SimulateRequest {
  std::string rig;                         // a built-in rig replacing the scene's camera and projector; "": none
  cv::Size camera_size;                    // the camera's resolution, field of view kept; empty: the scene's
  cv::Size projector_size;                 // the same for the projector
  std::optional<unsigned long long> seed;  // the frames' noise seed; none: the scene's render.seed
  bool force = false;                      // replace a non-empty out_dir
};

class Session {
 public:
  // Opens the devices; throws cl::DeviceSelectionError (exit code 4 in the tool) when a term names no device or the
  // machine has no OpenCL device, listing those that exist. Programs are built on first use and kept.
  explicit Session(SessionOptions options = {});
  ~Session();
  Session(Session&&) noexcept;
  Session& operator=(Session&&) noexcept;

  // The devices' descriptions ("pocl: cpu-... (CPU, 2 compute units)"), in the order they share work.
  std::vector<std::string> devices() const;

  // T of a capture: decoded and compressed on the devices. Errors as `rfrecon transport`: UsageError for K or a
  // threshold outside its range, InputError naming the file or frame, ProcessingError when no pixel decodes.
  TransportResult transport(const Capture& capture, const TransportOptions& options = {});
  // T^T 1, the scene seen from the projector (CV_32F, projector size), and T 1 (CV_32F, camera size).
  cv::Mat dual_image(const Transport& transport);
  cv::Mat primal_image(const Transport& transport);
  // The rig from one capture per board pose, as `rfrecon calibrate` (no report files): ProcessingError when too few
  // poses show the board or the intrinsics are not determined.
  CalibrationResult calibrate(const std::vector<Capture>& poses, const Board& board,
                              const CalibrationOptions& options = {});
  // Depth, points, normals and confidence of T with the rig, as `rfrecon reconstruct`. UsageError for an option
  // outside its range, InputError when T and the rig differ in size or the rig cannot be rectified.
  ReconstructResult reconstruct(const Transport& transport, const Rig& rig, const ReconstructOptions& options = {});

  // The synthetic rig (docs/sim.md), as `rfrecon simulate`: renders `scene` (a built-in name of `rfrecon simulate
  // --list`, or a scene file) into out_dir with its ground truth (the true rig is out_dir/truth/rig.yaml); returns the
  // capture directories, one, or one per board pose. Throws InputError for an unknown scene or an out_dir that is not
  // empty without `force`.
  std::vector<std::filesystem::path> simulate(const std::string& scene, const std::filesystem::path& out_dir,
                                              const SimulateRequest& request = {});

  // `rfrecon capture`: shows the protocol on `projector`, grabs `camera` in step (the latency measured first unless
  // options.latency_frames gives it) and writes the capture directory out_dir, whole or not at all (an existing
  // non-empty one only with `force`). Throws HardwareError when the camera or display fails or frames stay dropped,
  // UsageError for a protocol larger than the display. The camera and projector are called from this thread.
  CaptureReport capture(Projector& projector, Camera& camera, const CaptureOptions& options,
                        const std::filesystem::path& out_dir, bool force = false);

  // From any thread: the running call throws Cancelled at its next frame read (transport, calibrate) or pattern
  // (capture) or, for the other calls, the next call does when it starts; a cancel while no call runs stops the next
  // call.
  void cancel();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The capture hardware the command line names (docs/cli.md): "aravis[:ID]", "v4l2:DEVICE" or "gst:PIPELINE" for a
// camera, "display:N" for the projector (SDL2's display N, full screen). Throws UsageError for a spec of no known kind,
// HardwareError when the device cannot be opened.
std::unique_ptr<Camera> open_camera(const std::string& spec);
std::unique_ptr<Projector> open_projector(const std::string& spec);

// A rig from its measured keys (sizes, intrinsics, distortion, R, T): checked, with E, F and the rectification
// computed, as read_rig does. Throws InputError starting with `where` and naming the key.
using calib::complete_rig;

// Files, as the command-line tool reads and writes them (docs/formats.md). Writes are atomic and, as the tool's, refuse
// an existing output (UsageError naming it) unless `force`. Call them qualified (rfrecon::write_rig): the layers'
// functions of the same names are found by argument-dependent lookup too.
Transport read_transport(const std::filesystem::path& file);
void write_transport(const Transport& transport, const std::filesystem::path& file, bool force = false);
using calib::read_rig;  // rig.yaml, OpenCV's FileStorage names; InputError naming the file and key
void write_rig(const Rig& rig, const std::filesystem::path& file, bool force = false);
// The reconstruction directory of `rfrecon reconstruct` (depth.tiff, points.ply, ...): a new or empty directory, or
// with `force` any.
void write_reconstruction(const ReconstructResult& result, const std::filesystem::path& dir, bool force = false);

}  // namespace rfrecon
