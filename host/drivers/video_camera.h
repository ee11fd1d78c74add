// Cameras that OpenCV's VideoCapture opens: V4L2/UVC devices (webcams, UVC industrial cameras) and GStreamer
// pipelines ending in appsink.
#pragma once

#include <memory>
#include <string>

#include "host/acquire/camera.h"

namespace rfrecon::drivers {

// A V4L2 device: its index (0 for /dev/video0) or path. Throws HardwareError when it cannot be opened.
std::unique_ptr<acquire::Camera> open_v4l2_camera(const std::string& device);

// A GStreamer pipeline whose last element is an appsink, e.g. "ximagesrc ! videoconvert ! appsink". Throws
// HardwareError when it does not start.
std::unique_ptr<acquire::Camera> open_gstreamer_camera(const std::string& pipeline);

}  // namespace rfrecon::drivers
