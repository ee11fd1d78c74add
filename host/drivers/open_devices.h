// The capture hardware a command line names: `--camera aravis[:ID] | v4l2:DEVICE | gst:PIPELINE` and
// `--projector display:N` (docs/capture.md).
#pragma once

#include <memory>
#include <string>

#include "host/acquire/camera.h"
#include "host/acquire/projector.h"

namespace rfrecon::drivers {

// Opens the camera `spec` names; throws UsageError for a spec of no known kind, HardwareError when it cannot open.
std::unique_ptr<acquire::Camera> open_camera(const std::string& spec);

// Opens the projector `spec` names ("display:N", SDL2's display N); throws as open_camera.
std::unique_ptr<acquire::Projector> open_projector(const std::string& spec);

}  // namespace rfrecon::drivers
