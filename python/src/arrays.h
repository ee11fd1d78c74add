// numpy arrays and OpenCV matrices: views of each other's memory (no copies), frames copied in from Python, and
// library calls run without the GIL.
#pragma once

#include <string>

#include <opencv2/core.hpp>
#include <pybind11/numpy.h>

namespace rfrecon::python {

// A numpy view of `mat` ((rows, cols) or (rows, cols, channels)) that keeps its memory alive: the view may outlive
// everything else, including the session that made it.
pybind11::array array_of(const cv::Mat& mat);

// A matrix over a C-contiguous numpy array's memory (2-D, or 3-D with the channels last), valid while the array lives.
// Throws InputError for another layout or an element type OpenCV has no type for.
cv::Mat mat_of(const pybind11::array& array);

// A frame handed over from Python: 2-D uint8 or uint16, copied into memory the library owns. Throws InputError
// starting with `where` for anything else.
cv::Mat frame_of(const pybind11::array& frame, const std::string& where);

// What `call` returns, run without the GIL: library calls may log, and the log callback takes the GIL.
template <typename Call>
auto without_gil(const Call& call) {
  const pybind11::gil_scoped_release release;
  return call();
}

// A view of one array of the rfrecon.Transport `transport` ("indices", "weights": (H, W, K); "correspondence":
// (H, W, 2); "flags", "pixel_x", "pixel_y", "direct_energy", "white": (H, W)) that keeps the transport alive; None for
// an empty white frame.
pybind11::object transport_array(const pybind11::object& transport, const std::string& name);

}  // namespace rfrecon::python
