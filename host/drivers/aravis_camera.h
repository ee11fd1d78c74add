// GenICam cameras (GigE Vision, USB3 Vision) through Aravis: the industrial cameras structured-light rigs use.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "host/acquire/camera.h"

namespace rfrecon::drivers {

// Opens the camera `device_id` (Aravis's id, as `arv-tool-0.8` or list_aravis_cameras prints, or a GigE Vision
// camera's IPv4 address, opened without discovery; empty for the first one), in its deepest monochrome pixel format,
// streaming continuously. Throws HardwareError when it is not found (the message lists the cameras there are) or offers
// no monochrome format.
std::unique_ptr<acquire::Camera> open_aravis_camera(const std::string& device_id);

// The ids of the cameras Aravis finds now.
std::vector<std::string> list_aravis_cameras();

}  // namespace rfrecon::drivers
