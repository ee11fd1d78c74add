// Camera and Projector implemented in Python (pybind11 trampolines that call the object's methods with the GIL) or
// opened by spec, and Session.capture running them without the GIL.
#include "python/src/capture_bindings.h"

#include <pybind11/chrono.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python/src/arrays.h"
#include "rfrecon/rfrecon.h"

namespace py = pybind11;

namespace rfrecon::python {

namespace {

class PyCamera : public Camera {
 public:
  std::string name() const override { PYBIND11_OVERRIDE_PURE(std::string, Camera, name, ); }
  CameraFormat format() const override { PYBIND11_OVERRIDE_PURE(CameraFormat, Camera, format, ); }
  double lock_exposure(double exposure_us) override {
    PYBIND11_OVERRIDE_PURE(double, Camera, lock_exposure, exposure_us);
  }
  cv::Mat grab(std::chrono::milliseconds timeout) override {
    const py::gil_scoped_acquire gil;
    const py::function grab = py::get_override(static_cast<const Camera*>(this), "grab");
    if (!grab) throw UsageError("a Camera subclass must define grab(timeout_ms)");
    return frame_of(grab(timeout.count()).cast<py::array>(), name() + " grab");
  }
};

class PyProjector : public Projector {
 public:
  std::string name() const override { PYBIND11_OVERRIDE_PURE(std::string, Projector, name, ); }
  cv::Size size() const override {
    const py::gil_scoped_acquire gil;
    const py::function size = py::get_override(static_cast<const Projector*>(this), "size");
    if (!size) throw UsageError("a Projector subclass must define size()");
    const auto [width, height] = size().cast<std::pair<int, int>>();
    return {width, height};
  }
  void show(const cv::Mat& image) override {
    const py::gil_scoped_acquire gil;
    const py::function show = py::get_override(static_cast<const Projector*>(this), "show");
    if (!show) throw UsageError("a Projector subclass must define show(image)");
    show(array_of(image.clone()));
  }
};

py::dict report_dict(const CaptureReport& report) {
  py::dict result;
  result["manifest"] = report.manifest;
  result["latency_frames"] = report.latency_frames;
  result["grabs"] = report.grabs;
  result["repeated_frames"] = report.repeated_frames;
  result["recaptured_pairs"] = report.recaptured_pairs;
  py::list warnings;
  for (const auto& finding : report.checks.findings) warnings.append(finding.message);
  result["warnings"] = warnings;
  return result;
}

}  // namespace

void bind_capture(py::module_& module) {
  py::class_<CameraFormat>(module, "CameraFormat", "What a camera's frames are: size, bit depth, black level.")
      .def(py::init([](std::pair<int, int> size, int bit_depth, double black_level_dn) {
             return CameraFormat{{size.first, size.second}, bit_depth, black_level_dn};
           }),
           py::arg("size"), py::arg("bit_depth") = 8, py::arg("black_level_dn") = 0.0)
      .def_property_readonly("size", [](const CameraFormat& f) { return std::make_pair(f.size.width, f.size.height); })
      .def_readonly("bit_depth", &CameraFormat::bit_depth)
      .def_readonly("black_level_dn", &CameraFormat::black_level_dn);

  py::class_<Camera, PyCamera>(module, "Camera",
                               "A camera for Session.capture. Subclass it (call super().__init__()) and define name(), "
                               "format() -> CameraFormat, lock_exposure(us) -> us applied (0: keep; return 0 when "
                               "unknown) and grab(timeout_ms) -> 2-D uint8/uint16 array; or use open_camera(spec).")
      .def(py::init<>())
      .def("name", &Camera::name)
      .def("format", &Camera::format)
      .def("lock_exposure", &Camera::lock_exposure, py::arg("exposure_us"), py::call_guard<py::gil_scoped_release>())
      .def(
          "grab",
          [](Camera& camera, int timeout_ms) {
            return array_of(without_gil([&] { return camera.grab(std::chrono::milliseconds(timeout_ms)); }));
          },
          py::arg("timeout_ms") = 2000);

  py::class_<Projector, PyProjector>(module, "Projector",
                                     "A projector for Session.capture. Subclass it (call super().__init__()) and "
                                     "define name(), size() -> (width, height) and show(image: 2-D uint8); or use "
                                     "open_projector(spec).")
      .def(py::init<>())
      .def("name", &Projector::name)
      .def("size", [](const Projector& p) { return std::make_pair(p.size().width, p.size().height); })
      .def(
          "show",
          [](Projector& p, const py::array& image) {
            const cv::Mat frame = frame_of(image, p.name() + " show");
            if (frame.type() != CV_8UC1 || frame.size() != p.size()) {
              throw InputError(p.name() + " show: the image must be uint8 of the projector's size (" +
                               std::to_string(p.size().height) + ", " + std::to_string(p.size().width) + ")");
            }
            p.show(frame);
          },
          py::arg("image"));

  module.def("open_camera", &open_camera, py::arg("spec"), py::call_guard<py::gil_scoped_release>(),
             "The camera a --camera spec names: 'aravis[:ID]', 'v4l2:DEVICE', 'gst:PIPELINE' (HardwareError when it "
             "cannot open).");
  module.def("open_projector", &open_projector, py::arg("spec"), py::call_guard<py::gil_scoped_release>(),
             "The projector 'display:N' names: SDL2's display N, full screen.");

  auto session = py::reinterpret_borrow<py::class_<Session>>(module.attr("Session"));
  session.def(
      "capture",
      [](Session& s, Projector& projector, Camera& camera, const std::filesystem::path& out_dir, int dot_spacing,
         std::optional<std::pair<int, int>> projector_size, std::vector<double> exposures_us, int latency_frames,
         std::string camera_response, std::optional<double> black_level_dn, std::string format, int retries,
         int timeout_ms, bool force) {
        CaptureOptions options;
        options.protocol.dot_spacing = dot_spacing;
        if (projector_size) options.protocol.projector_size = {projector_size->first, projector_size->second};
        options.exposures_us = std::move(exposures_us);
        options.latency_frames = latency_frames;
        options.camera_response = std::move(camera_response);
        options.black_level_dn = black_level_dn;
        options.format = std::move(format);
        options.retries = retries;
        options.timeout = std::chrono::milliseconds(timeout_ms);
        return report_dict(without_gil([&] { return s.capture(projector, camera, options, out_dir, force); }));
      },
      py::arg("projector"), py::arg("camera"), py::arg("out_dir"), py::arg("dot_spacing") = 8,
      py::arg("projector_size") = py::none(), py::arg("exposures_us") = std::vector<double>{},
      py::arg("latency_frames") = -1, py::arg("camera_response") = "linear", py::arg("black_level_dn") = py::none(),
      py::arg("format") = "tiff", py::arg("retries") = 2, py::arg("timeout_ms") = 2000, py::arg("force") = false,
      "`rfrecon capture`: shows the protocol on projector, grabs camera in step (latency measured unless given; "
      "several "
      "exposures merged) and writes the capture directory out_dir whole or not at all. Returns {manifest, "
      "latency_frames, grabs, repeated_frames, recaptured_pairs, warnings}. HardwareError when hardware fails.");
}

}  // namespace rfrecon::python
