// Views between numpy and OpenCV: a capsule owning a cv::Mat header keeps a matrix's memory for numpy.
#include "python/src/arrays.h"

#include <memory>
#include <vector>

#include "rfrecon/rfrecon.h"

namespace py = pybind11;

namespace rfrecon::python {

namespace {
py::dtype dtype_of(int depth) {
  switch (depth) {
    case CV_8U:
      return py::dtype::of<std::uint8_t>();
    case CV_16U:
      return py::dtype::of<std::uint16_t>();
    case CV_32S:
      return py::dtype::of<std::int32_t>();
    case CV_32F:
      return py::dtype::of<float>();
    case CV_64F:
      return py::dtype::of<double>();
    default:
      throw InputError("an OpenCV matrix of depth " + std::to_string(depth) + " has no numpy type here");
  }
}

int depth_of(const py::dtype& dtype) {
  if (dtype.is(py::dtype::of<std::uint8_t>())) return CV_8U;
  if (dtype.is(py::dtype::of<std::uint16_t>())) return CV_16U;
  if (dtype.is(py::dtype::of<std::int32_t>())) return CV_32S;
  if (dtype.is(py::dtype::of<float>())) return CV_32F;
  if (dtype.is(py::dtype::of<double>())) return CV_64F;
  throw InputError("an array of dtype " + py::str(dtype).cast<std::string>() +
                   " (uint8, uint16, int32, float32 or float64 are taken)");
}

// A view of `data` with `shape` that keeps `owner` (a Python object) alive.
template <typename T>
py::array view(const std::vector<T>& data, std::vector<py::ssize_t> shape, const py::object& owner) {
  py::array array = py::array_t<T>(shape, data.data(), owner);
  array.attr("setflags")(py::arg("write") = false);  // the transport is shared: read-only views
  return array;
}
}  // namespace

py::array array_of(const cv::Mat& mat) {
  const cv::Mat continuous = mat.isContinuous() ? mat : mat.clone();
  auto* owned = new cv::Mat(continuous);  // shares the data's reference count
  const py::capsule owner(owned, [](void* p) { delete static_cast<cv::Mat*>(p); });
  std::vector<py::ssize_t> shape{continuous.rows, continuous.cols};
  if (continuous.channels() > 1) shape.push_back(continuous.channels());
  return py::array(dtype_of(continuous.depth()), shape, continuous.data, owner);
}

cv::Mat mat_of(const py::array& array) {
  if (!(array.flags() & py::array::c_style))
    throw InputError("an array that is not C-contiguous (np.ascontiguousarray)");
  if (array.ndim() != 2 && array.ndim() != 3)
    throw InputError("an array of " + std::to_string(array.ndim()) +
                     " dimensions (2, or 3 with channels last, are taken)");
  const int channels = array.ndim() == 3 ? static_cast<int>(array.shape(2)) : 1;
  if (channels < 1 || channels > CV_CN_MAX) throw InputError("an array of " + std::to_string(channels) + " channels");
  return cv::Mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)),
                 CV_MAKETYPE(depth_of(array.dtype()), channels), const_cast<void*>(array.data()));
}

py::object transport_array(const py::object& transport, const std::string& name) {
  const auto& t = *transport.cast<std::shared_ptr<rfrecon::Transport>>();
  const py::ssize_t height = t.setup.camera_size.height, width = t.setup.camera_size.width;
  const py::ssize_t k = t.setup.entries_per_pixel;
  if (name == "indices") return view(t.indices, {height, width, k}, transport);
  if (name == "weights") return view(t.weights, {height, width, k}, transport);
  if (name == "correspondence") return view(t.correspondence, {height, width, 2}, transport);
  if (name == "flags") return view(t.flags, {height, width}, transport);
  if (name == "pixel_x") return view(t.pixel_x, {height, width}, transport);
  if (name == "pixel_y") return view(t.pixel_y, {height, width}, transport);
  if (name == "direct_energy") return view(t.direct_energy, {height, width}, transport);
  if (name == "white") return t.white.empty() ? py::object(py::none()) : view(t.white, {height, width}, transport);
  throw InputError("no transport array '" + name + "'");
}

cv::Mat frame_of(const pybind11::array& frame, const std::string& where) {
  if (frame.ndim() != 2) throw InputError(where + ": a frame must be a 2-D array (rows, columns)");
  if (py::isinstance<py::array_t<std::uint8_t>>(frame) || py::isinstance<py::array_t<std::uint16_t>>(frame)) {
    return mat_of(frame).clone();
  }
  throw InputError(where + ": a frame must be uint8 or uint16, not " + py::str(frame.dtype()).cast<std::string>());
}

}  // namespace rfrecon::python
