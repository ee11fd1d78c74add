// The options every command reading a capture directory takes (--layout, --projector, --bit-depth), and the capture
// checks' findings printed.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "host/capture/capture_checks.h"
#include "host/transport/capture_views.h"

namespace rfrecon::cli {

struct CaptureOptions {
  std::string layout = "manifest";    // or "opencv-graycode"
  std::string projector;              // WxH, required by opencv-graycode
  bool allow_outside_frames = false;  // manifest frames may lie outside the capture directory
  int bit_depth = 0;                  // opencv-graycode: bits per sample, 0 for the files' own
};

// Adds --layout, --projector, --bit-depth and --allow-outside-frames to `command`.
void add_capture_options(CLI::App* command, CaptureOptions& options);

// The layout these options name; throws InputError for a malformed --projector.
transport::CaptureSource capture_source(const CaptureOptions& options);

// Logs each finding of the capture checks as a warning naming `capture_dir`, and the measures at info level.
void log_check_findings(const capture::CaptureCheckResult& result, const std::string& capture_dir);

}  // namespace rfrecon::cli
