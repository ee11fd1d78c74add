// The Python module rfrecon._rfrecon: the front door (rfrecon/rfrecon.h) over numpy arrays.
#include <algorithm>
#include <array>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python/src/arrays.h"
#include "python/src/capture_bindings.h"
#include "python/src/rig_dict.h"
#include "rfrecon/rfrecon.h"

namespace py = pybind11;
using rfrecon::python::array_of;
using rfrecon::python::frame_of;
using rfrecon::python::mat_of;
using rfrecon::python::without_gil;

namespace {

// The Python exception classes, each with the command-line tool's exit code for the same failure (docs/cli.md).
void register_errors(py::module_& module) {
  static py::exception<std::runtime_error> error(module, "Error", PyExc_RuntimeError);
  error.attr("exit_code") = 1;
  const auto derived = [&](const char* name, int exit_code) {
    auto type = py::exception<std::runtime_error>(module, name, error.ptr());
    type.attr("exit_code") = exit_code;
    return type;
  };
  static auto usage = derived("UsageError", 2);
  static auto input = derived("InputError", 3);
  static auto device = derived("DeviceError", 4);
  static auto opencl = derived("OpenCLError", 5);
  static auto processing = derived("ProcessingError", 6);
  static auto output = derived("OutputError", 8);
  static auto hardware = derived("HardwareError", 10);
  static auto cancelled = derived("Cancelled", 130);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const rfrecon::UsageError& e) {
      PyErr_SetString(usage.ptr(), e.what());
    } catch (const rfrecon::InputError& e) {
      PyErr_SetString(input.ptr(), e.what());
    } catch (const rfrecon::DeviceSelectionError& e) {
      PyErr_SetString(device.ptr(), e.what());
    } catch (const rfrecon::OpenCLError& e) {
      PyErr_SetString(opencl.ptr(), e.what());
    } catch (const rfrecon::ProcessingError& e) {
      PyErr_SetString(processing.ptr(), e.what());
    } catch (const rfrecon::OutputError& e) {
      PyErr_SetString(output.ptr(), e.what());
    } catch (const rfrecon::HardwareError& e) {
      PyErr_SetString(hardware.ptr(), e.what());
    } catch (const rfrecon::Cancelled& e) {
      PyErr_SetString(cancelled.ptr(), e.what());
    }
  });
}

cv::Size size_of(const std::pair<int, int>& width_height) { return {width_height.first, width_height.second}; }
std::pair<int, int> pair_of(cv::Size size) { return {size.width, size.height}; }

// A Python callable shared with the library's threads: the last copy may go in a thread without the GIL, so the
// reference is dropped under it.
std::shared_ptr<py::function> shared_callable(py::function function) {
  return {new py::function(std::move(function)), [](py::function* held) {
            const py::gil_scoped_acquire gil;
            delete held;
          }};
}

// A Python callable run from the library's threads: it takes the GIL; what it raises is reported as unraisable.
template <typename... Args>
auto with_gil(py::function function) {
  return [function = shared_callable(std::move(function))](Args... args) {
    const py::gil_scoped_acquire gil;
    try {
      (*function)(args...);
    } catch (py::error_already_set& error) {
      error.discard_as_unraisable("rfrecon callback");
    }
  };
}

// The method and the tuning options by name, underscores for the flags' hyphens (crease, sigma_step).
rfrecon::ReconstructOptions reconstruct_options(const std::string& method, const py::kwargs& tuning) {
  rfrecon::ReconstructOptions options;
  options.method = rfrecon::depth_method(method).name();
  for (const auto& [key, value] : tuning) {
    std::string name = py::str(key);
    std::replace(name.begin(), name.end(), '_', '-');
    if (!py::isinstance<py::int_>(value) && !py::isinstance<py::float_>(value)) {
      throw rfrecon::UsageError("depth option '" + name + "' must be a number, not " +
                                py::str(py::type::of(value).attr("__name__")).cast<std::string>());
    }
    rfrecon::set_depth_option(options, name, value.cast<double>());
  }
  return options;
}

// The depth's standard deviations by their dict keys.
std::array<std::pair<const char*, cv::Mat*>, 3> sigma_fields(rfrecon::outputs::Reconstruction& maps) {
  return {{{"depth_sigma_mm", &maps.depth_sigma_mm},
           {"depth_sigma_calibration_mm", &maps.depth_sigma_calibration_mm},
           {"depth_sigma_observation_mm", &maps.depth_sigma_observation_mm}}};
}

py::dict reconstruction_dict(rfrecon::ReconstructResult result) {
  py::dict maps;
  maps["depth_mm"] = array_of(result.maps.depth_mm);
  maps["points_mm"] = array_of(result.maps.points_mm);
  maps["normals"] = array_of(result.maps.normals);
  maps["confidence"] = array_of(result.maps.confidence);
  maps["white"] = result.maps.white.empty() ? py::object(py::none()) : py::object(array_of(result.maps.white));
  for (const auto& [key, sigma] : sigma_fields(result.maps)) {
    maps[key] = sigma->empty() ? py::object(py::none()) : py::object(array_of(*sigma));
  }
  maps["summary"] = py::module_::import("json").attr("loads")(result.summary.dump());
  maps["rig"] = rfrecon::python::rig_dict(result.rig);
  return maps;
}

// The maps of a reconstruct() dict (a user's dict: a missing key is an InputError naming it), and its summary.
rfrecon::ReconstructResult reconstruction_of(const py::dict& maps) {
  const auto map = [&](const char* key) {
    if (!maps.contains(key)) throw rfrecon::InputError(std::string("reconstruction dict: missing key '") + key + "'");
    return mat_of(maps[key].cast<py::array>());
  };
  rfrecon::ReconstructResult result;
  result.maps.depth_mm = map("depth_mm");
  result.maps.points_mm = map("points_mm");
  result.maps.normals = map("normals");
  result.maps.confidence = map("confidence");
  if (maps.contains("white") && !maps["white"].is_none()) result.maps.white = map("white");
  for (const auto& [key, sigma] : sigma_fields(result.maps)) {
    if (maps.contains(key) && !maps[key].is_none()) *sigma = map(key);
  }
  const py::object summary = maps.contains("summary") ? py::object(maps["summary"]) : py::object(py::dict());
  result.summary = nlohmann::json::parse(py::module_::import("json").attr("dumps")(summary).cast<std::string>());
  return result;
}

}  // namespace

PYBIND11_MODULE(_rfrecon, module) {
  module.doc() = "rfrecon's front door (rfrecon/rfrecon.h) over numpy arrays; see the rfrecon package.";
  module.attr("__version__") = RFRECON_VERSION;
  register_errors(module);

  py::class_<rfrecon::Manifest>(module, "Manifest", "A capture's patterns, sizes and camera (manifest.json).")
      .def_property_readonly("projector_size", [](const rfrecon::Manifest& m) { return pair_of(m.projector_size); })
      .def_property_readonly("camera_size", [](const rfrecon::Manifest& m) { return pair_of(m.camera_size); })
      .def_readwrite("bit_depth", &rfrecon::Manifest::bit_depth)
      .def_readwrite("black_level", &rfrecon::Manifest::black_level)
      .def_readwrite("camera_response", &rfrecon::Manifest::camera_response)
      .def_readonly("dot_spacing", &rfrecon::Manifest::dot_spacing)
      .def_readonly("family", &rfrecon::Manifest::family)
      .def_property_readonly("frame_files",
                             [](const rfrecon::Manifest& m) {
                               std::vector<std::string> files;
                               for (const auto& frame : m.frames) files.push_back(frame.file);
                               return files;
                             })
      .def("__len__", [](const rfrecon::Manifest& m) { return m.frames.size(); });

  module.def(
      "make_manifest",
      [](std::pair<int, int> projector_size, std::pair<int, int> camera_size, int bit_depth, int dot_spacing,
         const std::string& family, const std::map<std::string, int>& parameters) {
        const py::gil_scoped_release release;
        return rfrecon::make_manifest(size_of(projector_size), size_of(camera_size), bit_depth, dot_spacing, family,
                                      parameters);
      },
      py::arg("projector_size"), py::arg("camera_size"), py::arg("bit_depth") = 8, py::arg("dot_spacing") = 8,
      py::arg("family") = "graycode", py::arg("parameters") = std::map<std::string, int>{},
      "A pattern family's manifest (graycode: white, black, Gray code with inverses, dot grid) for (width, height) "
      "sizes, with the family's whole-number parameters (phase: phase_steps, phase_period, phase_ratio).");
  module.def("pattern_families", &rfrecon::pattern_family_names,
             "The pattern families' names, for make_manifest(family=...): graycode, then any registered in C++.");
  module.def(
      "pattern_image",
      [](const rfrecon::Manifest& manifest, std::size_t index) {
        return array_of(without_gil([&] { return rfrecon::pattern_image(manifest, index); }));
      },
      py::arg("manifest"), py::arg("index"), "The uint8 image to show on the projector for frame `index`.");

  py::class_<rfrecon::Capture>(module, "Capture", "Where a capture's frames come from, with their manifest.")
      .def_static(
          "from_directory",
          [](const std::filesystem::path& dir, const std::string& layout, std::optional<std::pair<int, int>> projector,
             int bit_depth) {
            const py::gil_scoped_release release;
            return rfrecon::Capture::from_directory(dir, layout, projector ? size_of(*projector) : cv::Size(),
                                                    bit_depth);
          },
          py::arg("dir"), py::arg("layout") = "", py::arg("projector_size") = py::none(), py::arg("bit_depth") = 0)
      .def_static(
          "from_frames",
          [](rfrecon::Manifest manifest, const std::vector<py::array>& frames, const std::string& name) {
            std::vector<cv::Mat> copies;
            for (std::size_t i = 0; i < frames.size(); ++i) {
              copies.push_back(frame_of(frames[i], name + " frame " + std::to_string(i)));
            }
            return rfrecon::Capture::from_frames(std::move(manifest), std::move(copies), name);
          },
          py::arg("manifest"), py::arg("frames"), py::arg("name") = "frames in memory",
          "Frames as 2-D uint8 or uint16 arrays, one per manifest frame (copied once).")
      .def_static(
          "from_callback",
          [](rfrecon::Manifest manifest, py::function frame, const std::string& name) {
            auto shared = shared_callable(std::move(frame));
            return rfrecon::Capture::from_callback(
                std::move(manifest),
                [shared, name](std::size_t index) {
                  const py::gil_scoped_acquire gil;
                  return frame_of((*shared)(index).cast<py::array>(), name + " frame " + std::to_string(index));
                },
                name);
          },
          py::arg("manifest"), py::arg("frame"), py::arg("name"),
          "frame(i) returns frame i as a 2-D uint8 or uint16 array (a camera after showing pattern i).")
      .def(
          "frame",
          [](const rfrecon::Capture& c, std::size_t i) { return array_of(without_gil([&] { return c.frame(i); })); },
          py::arg("index"), "Frame `index` as the camera gave it (2-D uint8 or uint16).")
      .def_property_readonly("manifest", &rfrecon::Capture::manifest)
      .def_property_readonly("name", &rfrecon::Capture::name);

  py::class_<rfrecon::Transport, std::shared_ptr<rfrecon::Transport>>(
      module, "Transport", "T: the K strongest entries of each camera pixel's row (T.h5). Arrays are views.")
      .def_property_readonly("camera_size", [](const rfrecon::Transport& t) { return pair_of(t.setup.camera_size); })
      .def_property_readonly("projector_size",
                             [](const rfrecon::Transport& t) { return pair_of(t.setup.projector_size); })
      .def_property_readonly("entries_per_pixel", [](const rfrecon::Transport& t) { return t.setup.entries_per_pixel; })
      .def_property_readonly("indices",
                             [](py::object self) { return rfrecon::python::transport_array(self, "indices"); })
      .def_property_readonly("weights",
                             [](py::object self) { return rfrecon::python::transport_array(self, "weights"); })
      .def_property_readonly("correspondence",
                             [](py::object self) { return rfrecon::python::transport_array(self, "correspondence"); })
      .def_property_readonly("flags", [](py::object self) { return rfrecon::python::transport_array(self, "flags"); })
      .def_property_readonly("pixel_x",
                             [](py::object self) { return rfrecon::python::transport_array(self, "pixel_x"); })
      .def_property_readonly("pixel_y",
                             [](py::object self) { return rfrecon::python::transport_array(self, "pixel_y"); })
      // The names of these two before 2026-12 (they held the Gray code's pixel before other families): kept for
      // scripts that use them.
      .def_property_readonly("gray_x",
                             [](py::object self) { return rfrecon::python::transport_array(self, "pixel_x"); })
      .def_property_readonly("gray_y",
                             [](py::object self) { return rfrecon::python::transport_array(self, "pixel_y"); })
      .def_property_readonly("direct_energy",
                             [](py::object self) { return rfrecon::python::transport_array(self, "direct_energy"); })
      .def_property_readonly("white", [](py::object self) { return rfrecon::python::transport_array(self, "white"); });

  py::class_<rfrecon::Session>(module, "Session", "OpenCL devices and their programs, kept between calls.")
      .def(py::init(
               [](const std::string& devices, std::optional<py::function> log, std::optional<py::function> progress) {
                 rfrecon::SessionOptions options;
                 options.devices = devices;
                 if (log) {
                   auto call = with_gil<int, std::string>(*log);
                   options.log = [call](rfrecon::LogLevel level, const std::string& text) {
                     call(static_cast<int>(level), text);
                   };
                 }
                 if (progress) {
                   auto call = with_gil<std::string, std::size_t, std::size_t, std::string>(*progress);
                   options.progress = [call](const rfrecon::ProgressStep& step) {
                     call(step.label, step.done, step.total, step.unit);
                   };
                 }
                 const py::gil_scoped_release release;
                 return std::make_unique<rfrecon::Session>(std::move(options));
               }),
           py::arg("devices") = "", py::arg("log") = py::none(), py::arg("progress") = py::none(),
           "Opens the OpenCL devices (devices: the --devices syntax; \"\": $RFRECON_DEVICES, else all). log(level, "
           "text) receives the library's log lines (0 debug, 1 info, 2 warning, 3 error), progress(label, done, total, "
           "unit) each step of a long call; both run in the library's threads with the GIL.")
      .def_property_readonly("devices", &rfrecon::Session::devices,
                             "The devices' descriptions, in the order they share work.")
      .def(
          "transport",
          [](rfrecon::Session& session, const rfrecon::Capture& capture, int entries_per_pixel, float black_threshold,
             float white_threshold, float noise_threshold) {
            rfrecon::TransportOptions options;
            options.entries_per_pixel = entries_per_pixel;
            options.thresholds = {black_threshold, white_threshold, noise_threshold};
            auto result = without_gil([&] { return session.transport(capture, options); });
            return py::make_tuple(std::make_shared<rfrecon::Transport>(std::move(result.transport)), result.warnings);
          },
          py::arg("capture"), py::arg("entries_per_pixel") = RF_K, py::arg("black_threshold") = 0.04f,
          py::arg("white_threshold") = 0.0f, py::arg("noise_threshold") = 0.0f,
          "T of a capture, decoded and compressed on the devices, as `rfrecon transport`: (Transport, warnings of the "
          "capture checks). Thresholds as --black-threshold, --white-threshold, --noise-threshold (0: automatic).")
      .def(
          "dual_image",
          [](rfrecon::Session& session, const rfrecon::Transport& t) {
            return array_of(without_gil([&] { return session.dual_image(t); }));
          },
          py::arg("transport"), "T^T 1, the scene seen from the projector: float32, (projector height, width).")
      .def(
          "primal_image",
          [](rfrecon::Session& session, const rfrecon::Transport& t) {
            return array_of(without_gil([&] { return session.primal_image(t); }));
          },
          py::arg("transport"), "T 1: float32, (camera height, width).")
      .def(
          "calibrate",
          [](rfrecon::Session& session, const std::vector<rfrecon::Capture>& poses, std::tuple<int, int, double> board,
             int dense_points, bool gating) {
            rfrecon::CalibrationOptions options;
            options.dense_points = dense_points;
            options.gating = gating;
            const rfrecon::Board spec{std::get<0>(board), std::get<1>(board), std::get<2>(board)};
            auto result = without_gil([&] { return session.calibrate(poses, spec, options); });
            return py::make_tuple(rfrecon::python::rig_dict(result.rig), result.view_names, result.warnings);
          },
          py::arg("poses"), py::arg("board"), py::arg("dense_points") = 2000, py::arg("gating") = true,
          "Camera and projector from one capture per board pose, as `rfrecon calibrate`; board = (inner corners "
          "across, down, square size in mm). Returns (rig dict, the poses used, warnings).")
      .def(
          "reconstruct",
          [](rfrecon::Session& session, const rfrecon::Transport& t, const py::dict& rig, const std::string& method,
             const py::kwargs& tuning) {
            const rfrecon::Rig native = rfrecon::python::rig_of(rig);
            const auto options = reconstruct_options(method, tuning);
            return reconstruction_dict(without_gil([&] { return session.reconstruct(t, native, options); }));
          },
          py::arg("transport"), py::arg("rig"), py::arg("method") = "fused",
          "Depth of T with the rig, as `rfrecon reconstruct`: a dict of depth_mm (H, W), points_mm and normals "
          "(H, W, 3), confidence, white, depth_sigma_mm and its parts depth_sigma_calibration_mm and "
          "depth_sigma_observation_mm (float32, NaN where none), summary (summary.json's dict) and the rig. "
          "Tuning options by their command-line names with underscores (crease=8.0, sigma_step=0.2; docs/cli.md), "
          "each checked against its range.")
      .def(
          "simulate",
          [](rfrecon::Session& session, const std::string& scene, const std::filesystem::path& out_dir,
             const std::string& rig, std::optional<std::pair<int, int>> camera_size,
             std::optional<std::pair<int, int>> projector_size, std::optional<unsigned long long> seed, bool force) {
            rfrecon::SimulateRequest request;
            request.rig = rig;
            if (camera_size) request.camera_size = size_of(*camera_size);
            if (projector_size) request.projector_size = size_of(*projector_size);
            request.seed = seed;
            request.force = force;
            const py::gil_scoped_release release;
            return session.simulate(scene, out_dir, request);
          },
          py::arg("scene"), py::arg("out_dir"), py::arg("rig") = "", py::arg("camera_size") = py::none(),
          py::arg("projector_size") = py::none(), py::arg("seed") = py::none(), py::arg("force") = false,
          "Renders a built-in scene or scene file into out_dir (capture/ and truth/) as `rfrecon simulate`; returns "
          "the capture directories (one per board pose for multi-view scenes).")
      .def("cancel", &rfrecon::Session::cancel,
           "From any thread: the running transport or calibrate raises Cancelled at its next frame, capture at its "
           "next pattern; other calls when they start.");
  rfrecon::python::bind_capture(module);

  module.def(
      "read_transport",
      [](const std::filesystem::path& file) {
        const py::gil_scoped_release release;
        return std::make_shared<rfrecon::Transport>(rfrecon::read_transport(file));
      },
      py::arg("file"), "T.h5 as `rfrecon transport` writes it (docs/formats.md).");
  module.def(
      "depth_methods", &rfrecon::depth_method_names,
      "The depth methods' names, for Session.reconstruct(method=...): the built-ins, then any registered in C++.");
  module.def("write_transport", &rfrecon::write_transport, py::arg("transport"), py::arg("file"),
             py::arg("force") = false, py::call_guard<py::gil_scoped_release>(),
             "T.h5, written atomically; an existing file only with force.");
  module.def(
      "read_rig",
      [](const std::filesystem::path& file) {
        return rfrecon::python::rig_dict(without_gil([&] { return rfrecon::read_rig(file); }));
      },
      py::arg("file"), "rig.yaml as a dict of OpenCV's names (float64 arrays, (width, height) sizes).");
  module.def(
      "write_rig",
      [](const py::dict& rig, const std::filesystem::path& file, bool force) {
        const rfrecon::Rig native = rfrecon::python::rig_of(rig);
        const py::gil_scoped_release release;
        rfrecon::write_rig(native, file, force);
      },
      py::arg("rig"), py::arg("file"), py::arg("force") = false,
      "rig.yaml, written atomically; an existing file only with force.");
  module.def(
      "write_reconstruction",
      [](const py::dict& maps, const std::filesystem::path& dir, bool force) {
        const rfrecon::ReconstructResult result = reconstruction_of(maps);
        const py::gil_scoped_release release;
        try {
          rfrecon::write_reconstruction(result, dir, force);
        } catch (const std::invalid_argument& e) {  // a map of another type or size than depth_mm's
          throw rfrecon::InputError(std::string("reconstruction dict: ") + e.what());
        }
      },
      py::arg("reconstruction"), py::arg("dir"), py::arg("force") = false,
      "The directory `rfrecon reconstruct` writes (depth.tiff, points.ply, ...), from reconstruct()'s dict; an "
      "existing non-empty directory only with force.");
}
