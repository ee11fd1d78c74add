// The options every command reading a capture directory takes: --layout and --projector.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "host/capture/manifest.h"

namespace rfrecon::cli {

struct CaptureOptions {
  std::string layout = "manifest";  // or "opencv-graycode"
  std::string projector;            // WxH, required by opencv-graycode
};

// Adds --layout and --projector to `command`.
void add_capture_options(CLI::App* command, CaptureOptions& options);

// The capture's manifest for these options (transport::open_capture).
capture::CaptureManifest open_capture(const std::filesystem::path& capture_dir, const CaptureOptions& options);

}  // namespace rfrecon::cli
