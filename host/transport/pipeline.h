// The light transport stage: reads a capture frame by frame and streams it through a TransportAccumulator.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "host/capture/manifest.h"
#include "host/transport/accumulator.h"

namespace rfrecon::transport {

// Opens a capture directory: DIR/manifest.json when layout is empty or "manifest"; for "opencv-graycode", the
// files sorted by name as OpenCV GrayCodePattern's sequence for `projector_size`
// (capture::manifest_from_opencv_layout). Throws InputError on an unknown layout or a missing projector size.
capture::CaptureManifest open_capture(const std::filesystem::path& capture_dir, const std::string& layout,
                                      cv::Size projector_size);

struct StageTiming {
  std::string stage;
  double seconds = 0.0;
};

struct TransportRun {
  CompressedTransport transport;
  std::vector<StageTiming>
      timings;  // "read frames", "setup" (buffers, kernel builds), "decode", "compress", "finalize"
};

using AccumulatorFactory = std::function<std::unique_ptr<TransportAccumulator>(const TransportSetup&)>;

// Reads the frames one at a time (white, black, Gray pairs, dot frames: at most two in memory besides white and
// black) and feeds them to the accumulator made for the capture's setup. `setup` gives K and the thresholds; sizes
// and dot spacing come from the manifest (camera size from the first frame when the manifest has none).
// Throws InputError naming the file for a missing, unreadable or mismatched frame, and for an all-dark capture.
TransportRun compute_transport(const std::filesystem::path& capture_dir, capture::CaptureManifest manifest,
                               TransportSetup setup, const AccumulatorFactory& make_accumulator);

}  // namespace rfrecon::transport
