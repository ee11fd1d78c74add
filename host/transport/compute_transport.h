// The light transport stage: reads a capture frame by frame and streams it through a TransportAccumulator.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "host/capture/capture_checks.h"
#include "host/capture/frame_source.h"
#include "host/capture/manifest.h"
#include "host/cl/entry_choice.h"
#include "host/core/stage_clock.h"
#include "host/sched/report.h"
#include "host/transport/accumulator.h"
#include "host/transport/gray_decision.h"

namespace rfrecon::transport {

// Opens a capture directory: DIR/manifest.json when layout is empty or "manifest"; for "opencv-graycode", the
// files sorted by name as OpenCV GrayCodePattern's sequence for `projector_size`, of `bit_depth` bits (0: the files')
// (capture::manifest_from_opencv_layout). Throws InputError on an unknown layout or a missing projector size.
capture::CaptureManifest open_capture(const std::filesystem::path& capture_dir, const std::string& layout,
                                      cv::Size projector_size,
                                      capture::FramePaths frame_paths = capture::FramePaths::kInsideCapture,
                                      int bit_depth = 0);

struct TransportRun {
  CompressedTransport transport;
  // "read frames", "setup" (buffers, kernel builds; on devices "build programs" first, buffers within "decode"),
  // "decode", "compress", "finalize", "subpixel" (Gray-code-only captures: host/transport/gray_subpixel.h), "checks"
  std::vector<StageTiming> timings;
  std::vector<sched::RunReport> schedule;           // per stage and device (compute_transport_on_devices only)
  std::optional<GrayDecisionCounts> gray_decision;  // Gray-code-only captures: how their lit pixels were decided
  capture::CaptureCheckResult checks;               // the capture checks on the frames read (capture/capture_checks.h)
};

using AccumulatorFactory = std::function<std::unique_ptr<TransportAccumulator>(const TransportSetup&)>;

// Reads the frames one at a time (white and black, then each step the manifest's decoding family plans: at most two
// frames in memory besides white and black) and feeds them to the accumulator made for the capture's setup. `setup`
// gives K and the thresholds; sizes and dot spacing come from the manifest (camera size from the first frame when the
// manifest has none). Throws InputError naming the file (or the source and frame) for a missing, unreadable or
// mismatched frame, for a manifest that is not a complete protocol (capture::validate_manifest), and for an all-dark
// capture.
TransportRun compute_transport(const capture::FrameSource& frames, capture::CaptureManifest manifest,
                               TransportSetup setup, const AccumulatorFactory& make_accumulator);

// Threads reading frames ahead of the devices by default (each keeps two steps' frames in flight): measured on two
// cores in docs/performance.md.
inline constexpr int kDefaultReaders = 2;

// Camera row blocks per device when several devices share the transport stage (one block on a single device).
inline constexpr int kBlocksPerDevice = 4;

// The same stage on every device of `devices` (host/sched/block_runner.h): camera rows cut into blocks, each block's
// per-pixel state on the device that first took it, every frame read once and fed to all blocks. `readers` threads
// read the frames of the next 2 x readers steps (capture::FrameReadAhead) while the devices work on the current
// one. When a device fails, its blocks are rebuilt on the others by re-reading the earlier frames from `frames`;
// only when all fail does it throw (sched::AllDevicesFailed). The kernels are
// per pixel, so with one entry on every device the result equals the single-device result bit for bit. `entries`
// gives each device its kernel entry (auto: cl::preferred_entry); a per-device list of the wrong length throws
// UsageError before any frame is read. `storage`: an earlier transport (of any size) whose memory the result reuses,
// for a scanner that scans again and again (make_empty_transport); the result is the same.
TransportRun compute_transport_on_devices(const capture::FrameSource& frames, capture::CaptureManifest manifest,
                                          TransportSetup setup, std::vector<cl::DeviceContext>& devices,
                                          cl::ProgramCache& programs, const cl::EntryChoice& entries = {},
                                          int readers = kDefaultReaders, CompressedTransport storage = {});

}  // namespace rfrecon::transport
