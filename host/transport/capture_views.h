// What calibration needs of one board pose's capture: the camera's white frame, the dual image T^T 1 seen from the
// projector (paper section 3, after Sen et al.'s dual photography) and the decoded correspondences.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "host/capture/capture_checks.h"
#include "host/capture/frame_source.h"
#include "host/capture/manifest.h"
#include "host/cl/device_context.h"
#include "host/cl/program_cache.h"
#include "host/sched/report.h"
#include "host/transport/transport_types.h"

namespace rfrecon::transport {

// How a capture directory is laid out (open_capture).
struct CaptureSource {
  std::string layout;       // "" or "manifest" (manifest.json), or "opencv-graycode"
  cv::Size projector_size;  // needed for opencv-graycode
  capture::FramePaths frame_paths = capture::FramePaths::kInsideCapture;  // kAnywhere: --allow-outside-frames
  int bit_depth = 0;  // opencv-graycode: the camera's bits per sample, 0 for the files' own
};

struct CaptureViews {
  cv::Mat camera_image;                    // CV_32F linear white frame (camera size)
  cv::Mat dual_image;                      // CV_32F T^T 1 (projector size)
  cv::Mat dual_reached;                    // CV_8U: 255 where T has an entry for the projector pixel
  cv::Mat correspondence;                  // CV_32FC2: camera pixel -> projector (x, y), NaN where unknown
  std::vector<sched::RunReport> schedule;  // the transport and dual stages per device
  capture::CaptureCheckResult checks;      // the capture checks on the pose's frames (host/capture/capture_checks.h)
};

// Builds T for the capture in `capture_dir` on `devices` (K = 8, default thresholds but a black threshold at the noise
// level, so the board's dark squares are lit), forms T^T 1 and reads the white frame; each device runs the kernel
// entry that suits it (cl::preferred_entry). Input errors (missing frames, bad manifest) throw InputError.
CaptureViews view_capture(const std::filesystem::path& capture_dir, const CaptureSource& source,
                          std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);
// The same for frames from any source (a capture directory, a camera, memory) described by `manifest`.
CaptureViews view_capture(const capture::FrameSource& frames, const capture::CaptureManifest& manifest,
                          std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);

}  // namespace rfrecon::transport
