// rig.yaml's keys as a dict of float64 arrays, and the measured keys back into a Rig.
#include "python/src/rig_dict.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "python/src/arrays.h"

namespace py = pybind11;

namespace rfrecon::python {

namespace {
py::object matrix(const cv::Mat& mat) {
  if (mat.empty()) return py::none();
  cv::Mat as_double;
  mat.convertTo(as_double, CV_64F);
  return array_of(as_double);
}

py::tuple size_tuple(cv::Size size) { return py::make_tuple(size.width, size.height); }

// The key's value as a float64 matrix (a copy), `rows` x `cols` where given (0: any).
cv::Mat matrix_of(const py::dict& dict, const char* key) {
  if (!dict.contains(key)) throw InputError(std::string("rig dict: missing key '") + key + "'");
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(dict[key]);
  if (!array) throw InputError(std::string("rig dict: key '") + key + "' is not an array of numbers");
  const py::ssize_t rows = array.ndim() == 2 ? array.shape(0) : 1;
  const py::ssize_t cols = array.ndim() == 2 ? array.shape(1) : array.ndim() == 1 ? array.shape(0) : 0;
  if (array.ndim() > 2 || cols == 0) throw InputError(std::string("rig dict: key '") + key + "' must be 1-D or 2-D");
  return cv::Mat(static_cast<int>(rows), static_cast<int>(cols), CV_64F, const_cast<double*>(array.data())).clone();
}

cv::Size size_of(const py::dict& dict, const char* key) {
  if (!dict.contains(key)) throw InputError(std::string("rig dict: missing key '") + key + "'");
  const auto pair = dict[key].cast<std::pair<int, int>>();
  return {pair.first, pair.second};
}
}  // namespace

py::dict rig_dict(const Rig& rig) {
  py::dict dict = py::module_::import("rfrecon").attr("Rig")();
  dict["camera_size"] = size_tuple(rig.camera_size);
  dict["projector_size"] = size_tuple(rig.projector_size);
  dict["camera_matrix"] = matrix(rig.camera_matrix);
  dict["dist_coeffs"] = matrix(rig.dist_coeffs.reshape(1, 1));
  dict["projector_matrix"] = matrix(rig.projector_matrix);
  dict["projector_dist_coeffs"] = matrix(rig.projector_dist_coeffs.reshape(1, 1));
  for (const auto& [key, mat] : {std::pair{"R", &rig.proj_from_cam_rotation},
                                 {"T", &rig.proj_from_cam_translation_mm},
                                 {"E", &rig.essential},
                                 {"F", &rig.fundamental},
                                 {"R1", &rig.rect_from_cam},
                                 {"R2", &rig.rect_from_proj},
                                 {"P1", &rig.rect_cam_image_from_rect},
                                 {"P2", &rig.rect_proj_image_from_rect},
                                 {"Q", &rig.rect_from_disparity}}) {
    dict[key] = matrix(*mat);
  }
  dict["rectified_camera_size"] = size_tuple(rig.rectified_camera_size);
  dict["rectified_projector_size"] = size_tuple(rig.rectified_projector_size);
  dict["rms"] = rig.rms;
  dict["per_view_errors"] = rig.per_view_errors;
  dict["board"] = py::make_tuple(rig.board.cols, rig.board.rows, rig.board.square_size);
  const auto& u = rig.uncertainty;
  if (!u.empty()) {
    dict["camera_intrinsics_std"] = matrix(u.camera_intrinsics);
    dict["dist_coeffs_std"] = matrix(u.camera_dist_coeffs);
    dict["projector_intrinsics_std"] = matrix(u.projector_intrinsics);
    dict["projector_dist_coeffs_std"] = matrix(u.projector_dist_coeffs);
    dict["om_std"] = matrix(u.proj_from_cam_rotation_vector);
    dict["T_std"] = matrix(u.proj_from_cam_translation_mm);
    if (!u.parameter_covariance.empty()) dict["parameter_covariance"] = matrix(u.parameter_covariance);
  }
  return dict;
}

Rig rig_of(const py::dict& dict) {
  Rig rig;
  rig.camera_size = size_of(dict, "camera_size");
  rig.projector_size = size_of(dict, "projector_size");
  rig.camera_matrix = matrix_of(dict, "camera_matrix");
  rig.dist_coeffs = matrix_of(dict, "dist_coeffs").reshape(1, 1);
  rig.projector_matrix = matrix_of(dict, "projector_matrix");
  rig.projector_dist_coeffs = matrix_of(dict, "projector_dist_coeffs").reshape(1, 1);
  rig.proj_from_cam_rotation = matrix_of(dict, "R");
  rig.proj_from_cam_translation_mm = matrix_of(dict, "T");
  if (rig.proj_from_cam_translation_mm.rows == 1)
    rig.proj_from_cam_translation_mm = rig.proj_from_cam_translation_mm.t();  // 3x1 from a flat array as well
  rig.rms = dict.contains("rms") ? dict["rms"].cast<double>() : 0.0;
  if (dict.contains("per_view_errors")) rig.per_view_errors = dict["per_view_errors"].cast<std::vector<double>>();
  if (dict.contains("board")) {
    const auto board = dict["board"].cast<std::tuple<int, int, double>>();
    rig.board = {std::get<0>(board), std::get<1>(board), std::get<2>(board)};
  }
  if (dict.contains("camera_intrinsics_std")) {
    auto& u = rig.uncertainty;
    u.camera_intrinsics = matrix_of(dict, "camera_intrinsics_std");
    u.camera_dist_coeffs = matrix_of(dict, "dist_coeffs_std");
    u.projector_intrinsics = matrix_of(dict, "projector_intrinsics_std");
    u.projector_dist_coeffs = matrix_of(dict, "projector_dist_coeffs_std");
    u.proj_from_cam_rotation_vector = matrix_of(dict, "om_std");
    u.proj_from_cam_translation_mm = matrix_of(dict, "T_std");
    if (dict.contains("parameter_covariance")) u.parameter_covariance = matrix_of(dict, "parameter_covariance");
  }
  return complete_rig(std::move(rig), "rig dict");
}

}  // namespace rfrecon::python
