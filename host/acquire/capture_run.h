// `rfrecon capture` as a library call: shows each pattern of the protocol on a projector, grabs the camera in step
// (after the measured latency, at each exposure), checks every frame as it comes and writes a capture directory that
// `transport` reads, whole or not at all.
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "host/acquire/camera.h"
#include "host/acquire/projector.h"
#include "host/capture/capture_checks.h"
#include "host/capture/manifest.h"
#include "host/capture/protocol.h"

namespace rfrecon::acquire {

struct CaptureRunOptions {
  capture::ProtocolOptions protocol;        // projector_size {0, 0}: the projector's own size
  std::vector<double> exposures_us;         // empty: the camera's exposure as it is (autos off); several: HDR, merged
  int latency_frames = -1;                  // frames discarded after each change; -1: measured first
  std::string camera_response = "linear";   // the manifest's camera_response for the camera's raw frames
  std::optional<double> black_level_dn;     // the camera's reading with no light, when it does not report its own
  std::string format = "tiff";              // frame files: "tiff" (uncompressed) or "png"
  int retries = 2;                          // captures again of a repeated frame or a failed Gray pair
  std::chrono::milliseconds timeout{2000};  // the longest wait for one frame
  // Called before each pattern is shown; what it throws ends the run with nothing written (a library caller's
  // cancellation).
  std::function<void()> before_pattern;
};

// What a run did, besides the files.
struct CaptureRunReport {
  capture::CaptureManifest manifest;
  int latency_frames = 0;
  std::size_t grabs = 0;             // frames taken from the camera, discarded ones included
  std::size_t repeated_frames = 0;   // grabs identical to the one before, taken again
  std::size_t recaptured_pairs = 0;  // Gray pairs that did not add up to white + black, captured again
  capture::CaptureCheckResult checks;
};

// Captures one scan into `out_dir`, which appears whole or not at all (an existing non-empty one is refused unless
// `force`; a signal or an error leaves nothing). Throws HardwareError when the camera or the display fails, or a frame
// stays wrong after `retries` captures again; UsageError when the protocol's projector size exceeds the display's.
CaptureRunReport capture_scan(Projector& projector, Camera& camera, const CaptureRunOptions& options,
                              const std::filesystem::path& out_dir, bool force);

// The latency of the pair (measure_latency_frames) with the camera locked at the options' longest exposure and
// waiting options.timeout for a frame: what capture_scan measures when options.latency_frames is -1.
int measure_latency(Projector& projector, Camera& camera, const CaptureRunOptions& options);

// Captures `poses` board poses for `calibrate` into out_dir/pose_01, pose_02, ..., one scan each, calling
// `before_pose(index)` (0-based) first: it waits for the user (a key, a timer) or moves a simulated board. The
// latency is measured once. out_dir appears whole or not at all.
std::vector<CaptureRunReport> capture_poses(Projector& projector, Camera& camera, const CaptureRunOptions& options,
                                            int poses, const std::function<void(int pose)>& before_pose,
                                            const std::filesystem::path& out_dir, bool force);

}  // namespace rfrecon::acquire
