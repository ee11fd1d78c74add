// The options every command reading a capture directory takes: --layout and --projector.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "host/transport/capture_views.h"

namespace rfrecon::cli {

struct CaptureOptions {
  std::string layout = "manifest";    // or "opencv-graycode"
  std::string projector;              // WxH, required by opencv-graycode
  bool allow_outside_frames = false;  // manifest frames may lie outside the capture directory
};

// Adds --layout, --projector and --allow-outside-frames to `command`.
void add_capture_options(CLI::App* command, CaptureOptions& options);

// The layout these options name; throws InputError for a malformed --projector.
transport::CaptureSource capture_source(const CaptureOptions& options);

}  // namespace rfrecon::cli
