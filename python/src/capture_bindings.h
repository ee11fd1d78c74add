// The capture seams in Python: Camera and Projector as classes a Python object implements (or the drivers opened by
// spec), and Session.capture.
#pragma once

#include <pybind11/pybind11.h>

namespace rfrecon::python {

// Adds CameraFormat, Camera, Projector, open_camera, open_projector and Session.capture to `module` (Session bound).
void bind_capture(pybind11::module_& module);

}  // namespace rfrecon::python
