// `rfrecon capture` as a library call: opens the camera and projector a command line names (or the simulated rig
// of a scene) and runs the capture of a scan or of board poses (host/acquire/capture_run.h).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "host/acquire/capture_run.h"
#include "sim/simulated_rig.h"

namespace rfrecon::pipeline {

struct CaptureRequest {
  std::string camera;     // "aravis[:ID]", "v4l2:DEVICE", "gst:PIPELINE", or "sim:SCENE" (a built-in scene or file)
  std::string projector;  // "display:N"; unused with a simulated camera (its scene's projector shows the patterns)
  acquire::CaptureRunOptions run;
  // 0: one scan into `output`; N: N board poses into output/pose_01 ... (a simulated multi-view scene: each view in
  // turn, and N = 0 takes them all).
  int poses = 0;
  // Called before each pose of a real rig (waits for the user); a simulated rig moves its board instead.
  std::function<void(int pose)> before_pose;
  std::optional<unsigned long long> seed;  // a simulated camera's noise seed (default: the scene's)
  sim::SimulatedRigFaults faults;          // injected into a simulated rig (tests)
  std::filesystem::path output;
  bool force = false;
};

// Runs the capture; returns one report per scan (one, or one per pose).
std::vector<acquire::CaptureRunReport> capture(const CaptureRequest& request);

// The frames between showing a pattern and the camera seeing it (acquire::measure_latency) for the rig the request
// names.
int measure_latency(const CaptureRequest& request);

}  // namespace rfrecon::pipeline
