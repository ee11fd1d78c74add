// How many camera frames pass between showing a pattern and the camera seeing it: measured by flashing white after
// black, never guessed, because displays add 1 to 3 refreshes and camera streams buffer frames.
#pragma once

#include <chrono>

#include "host/acquire/camera.h"
#include "host/acquire/projector.h"

namespace rfrecon::acquire {

struct LatencyOptions {
  int max_frames = 12;  // grabs after each change: the longest delay it can find is max_frames - 1
  int trials = 3;       // flashes; the largest delay is kept
  std::chrono::milliseconds timeout{2000};
};

// The number of frames to discard after Projector::show before a grabbed frame shows the new pattern: for each trial,
// shows black and lets it settle, shows white, and counts the grabs whose mean reading stays below the midpoint of
// black's and white's. Throws HardwareError when white is not brighter than black by 2 % of full scale (the camera
// does not see the projector) or the flash is not seen within max_frames.
int measure_latency_frames(Projector& projector, Camera& camera, const LatencyOptions& options = {});

}  // namespace rfrecon::acquire
