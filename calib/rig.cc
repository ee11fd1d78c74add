// Reading, writing and completing the stereo rig file.
#include "calib/rig.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <opencv2/calib3d.hpp>

#include "calib/rectification.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/limits.h"
#include "host/core/opencv_yaml.h"

namespace rfrecon::calib {

namespace fs = std::filesystem;

namespace {
bool valid_dist_size(const cv::Mat& m) {
  const auto n = m.total();
  return (m.rows == 1 || m.cols == 1) && (n == 4 || n == 5 || n == 8 || n == 12 || n == 14);
}

void check_shape(const cv::Mat& m, int rows, int cols, const char* key, const std::string& file) {
  if (m.rows != rows || m.cols != cols || m.channels() != 1) {
    throw InputError(file + ": key '" + key + "' must be a " + std::to_string(rows) + "x" + std::to_string(cols) +
                     " matrix, got " + std::to_string(m.rows) + "x" + std::to_string(m.cols));
  }
}

void check_dist(const cv::Mat& m, const char* key, const std::string& file) {
  if (!valid_dist_size(m)) {
    throw InputError(file + ": key '" + key + "' must hold 4, 5, 8, 12 or 14 distortion coefficients, got " +
                     std::to_string(m.total()));
  }
}

void check_finite(const cv::Mat& m, const char* key, const std::string& file) {
  if (!cv::checkRange(m)) throw InputError(file + ": key '" + key + "' holds a value that is not finite");
}

// Checks the measured keys of the rig (sizes, intrinsics, R, T); `file` names the rig in messages.
void check_measured(const StereoRig& rig, const std::string& file) {
  for (const auto& [size, key] : {std::pair{rig.camera_size, "camera_size"}, {rig.projector_size, "projector_size"}}) {
    if (size.width <= 0 || size.height <= 0) throw InputError(file + ": key '" + key + "' must be [w, h] > 0");
  }
  check_shape(rig.camera_matrix, 3, 3, "camera_matrix", file);
  check_dist(rig.dist_coeffs, "dist_coeffs", file);
  check_shape(rig.projector_matrix, 3, 3, "projector_matrix", file);
  check_dist(rig.projector_dist_coeffs, "projector_dist_coeffs", file);
  check_shape(rig.proj_from_cam_rotation, 3, 3, "R", file);
  check_shape(rig.proj_from_cam_translation_mm, 3, 1, "T", file);
  for (const auto& [m, key] : {std::pair{&rig.camera_matrix, "camera_matrix"},
                               {&rig.dist_coeffs, "dist_coeffs"},
                               {&rig.projector_matrix, "projector_matrix"},
                               {&rig.projector_dist_coeffs, "projector_dist_coeffs"},
                               {&rig.proj_from_cam_rotation, "R"},
                               {&rig.proj_from_cam_translation_mm, "T"}}) {
    check_finite(*m, key, file);
  }
  const cv::Mat should_be_identity = rig.proj_from_cam_rotation.t() * rig.proj_from_cam_rotation;
  // 1e-4: R typed in with five decimals (from another toolbox's report) still reads.
  if (cv::norm(should_be_identity, cv::Mat::eye(3, 3, CV_64F), cv::NORM_INF) > 1e-4 ||
      cv::determinant(rig.proj_from_cam_rotation) < 0.0) {
    throw InputError(file + ": key 'R' is not a rotation matrix (orthonormal, determinant +1)");
  }
}

// Checks every matrix of the rig.
void check_rig(const StereoRig& rig, const std::string& file) {
  check_measured(rig, file);
  check_shape(rig.essential, 3, 3, "E", file);
  check_shape(rig.fundamental, 3, 3, "F", file);
  check_shape(rig.rect_from_cam, 3, 3, "R1", file);
  check_shape(rig.rect_from_proj, 3, 3, "R2", file);
  check_shape(rig.rect_cam_image_from_rect, 3, 4, "P1", file);
  check_shape(rig.rect_proj_image_from_rect, 3, 4, "P2", file);
  check_shape(rig.rect_from_disparity, 4, 4, "Q", file);
}

cv::Mat as_double(const cv::Mat& m) {
  cv::Mat out;
  m.convertTo(out, CV_64F);
  return out;
}

constexpr long long kMaxMatrixElements = 16;
// The parameter covariance of the largest distortion model: G = 2 (4 + 14) + 6.
constexpr long long kMaxCovarianceElements = 42LL * 42;

// Rig matrices are at most 4x4 (or 1x14 coefficients), the covariance G x G: a larger declared shape is refused before
// it is allocated.
cv::Mat read_mat(const cv::FileStorage& fs, const char* key, const std::string& file,
                 long long max_elements = kMaxMatrixElements) {
  const cv::FileNode node = fs[key];
  if (node.empty()) throw InputError(file + ": missing key '" + key + "'");
  if (!node.isMap() || !node["rows"].isInt() || !node["cols"].isInt() || static_cast<int>(node["rows"]) < 1 ||
      static_cast<int>(node["cols"]) < 1 ||
      static_cast<long long>(static_cast<int>(node["rows"])) * static_cast<int>(node["cols"]) > max_elements) {
    throw InputError(file + ": key '" + key + "' is not an OpenCV matrix (!!opencv-matrix) of at most " +
                     std::to_string(max_elements) + " elements");
  }
  cv::Mat m;
  try {
    node >> m;
  } catch (const cv::Exception&) {
    m.release();
  }
  if (m.empty()) throw InputError(file + ": key '" + key + "' is not an OpenCV matrix (!!opencv-matrix)");
  return as_double(m);
}

cv::Size read_size(const cv::FileStorage& fs, const char* key, const std::string& file) {
  const cv::FileNode node = fs[key];
  if (node.empty()) throw InputError(file + ": missing key '" + key + "'");
  if (!node.isSeq() || node.size() != 2 || !node[0].isInt() || !node[1].isInt()) {
    throw InputError(file + ": key '" + key + "' must be [width, height] (integers)");
  }
  const cv::Size size(static_cast<int>(node[0]), static_cast<int>(node[1]));
  check_image_size(size, file + ": key '" + key + "'");
  return size;
}
}  // namespace

void compute_stereo_geometry(StereoRig& rig) {
  for (cv::Mat* m : {&rig.camera_matrix, &rig.dist_coeffs, &rig.projector_matrix, &rig.projector_dist_coeffs,
                     &rig.proj_from_cam_rotation, &rig.proj_from_cam_translation_mm}) {
    *m = as_double(*m);
  }
  check_measured(rig, "stereo rig");
  const cv::Mat t = rig.proj_from_cam_translation_mm;
  const cv::Mat t_cross = (cv::Mat_<double>(3, 3) << 0, -t.at<double>(2), t.at<double>(1), t.at<double>(2), 0,
                           -t.at<double>(0), -t.at<double>(1), t.at<double>(0), 0);
  rig.essential = t_cross * as_double(rig.proj_from_cam_rotation);
  rig.fundamental = as_double(rig.projector_matrix).inv().t() * rig.essential * as_double(rig.camera_matrix).inv();
  if (std::abs(rig.fundamental.at<double>(2, 2)) > 1e-12 * cv::norm(rig.fundamental))
    rig.fundamental /= rig.fundamental.at<double>(2, 2);
  const RowRectification rectification = rectify_rig(rig);
  rig.rect_from_cam = cv::Mat(rectification.rect_from_cam).clone();
  rig.rect_from_proj = cv::Mat(rectification.rect_from_proj).clone();
  rig.rect_cam_image_from_rect = rectification.rect_cam_image_from_rect;
  rig.rect_proj_image_from_rect = rectification.rect_proj_image_from_rect;
  rig.rect_from_disparity = rectification.rect_from_disparity;
  rig.rectified_camera_size = rectification.camera_size;
  rig.rectified_projector_size = rectification.projector_size;
}

void write_rig(const StereoRig& rig, const fs::path& file) {
  check_rig(rig, file.string());
  cv::FileStorage fs("rig.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs << "format" << kRigFormat << "version" << kRigVersion;
  fs << "camera_size" << rig.camera_size << "projector_size" << rig.projector_size;
  fs << "camera_matrix" << as_double(rig.camera_matrix) << "dist_coeffs" << as_double(rig.dist_coeffs).reshape(1, 1);
  fs << "projector_matrix" << as_double(rig.projector_matrix) << "projector_dist_coeffs"
     << as_double(rig.projector_dist_coeffs).reshape(1, 1);
  fs << "R" << as_double(rig.proj_from_cam_rotation) << "T" << as_double(rig.proj_from_cam_translation_mm) << "E"
     << as_double(rig.essential) << "F" << as_double(rig.fundamental);
  fs << "R1" << as_double(rig.rect_from_cam) << "R2" << as_double(rig.rect_from_proj) << "P1"
     << as_double(rig.rect_cam_image_from_rect) << "P2" << as_double(rig.rect_proj_image_from_rect) << "Q"
     << as_double(rig.rect_from_disparity);
  fs << "rectified_camera_size" << rig.rectified_camera_size << "rectified_projector_size"
     << rig.rectified_projector_size;
  fs << "rms" << rig.rms << "per_view_errors" << rig.per_view_errors;
  if (!rig.uncertainty.empty()) {
    const RigUncertainty& u = rig.uncertainty;
    fs << "camera_intrinsics_std" << u.camera_intrinsics << "dist_coeffs_std" << u.camera_dist_coeffs;
    fs << "projector_intrinsics_std" << u.projector_intrinsics << "projector_dist_coeffs_std"
       << u.projector_dist_coeffs;
    fs << "om_std" << u.proj_from_cam_rotation_vector << "T_std" << u.proj_from_cam_translation_mm;
    if (!u.parameter_covariance.empty()) fs << "parameter_covariance" << u.parameter_covariance;
  }
  fs << "board"
     << "{"
     << "cols" << rig.board.cols << "rows" << rig.board.rows << "square_size" << rig.board.square_size << "}";
  write_file_atomically(file, fs.releaseAndGetString());
}

namespace {
StereoRig read_rig_file(const fs::path& file) {
  const std::string name = file.string();
  const cv::FileStorage fs = open_opencv_yaml(file);
  if (!fs["format"].empty()) {
    if (!fs["format"].isString() || static_cast<std::string>(fs["format"]) != kRigFormat) {
      throw InputError(name + ": key 'format' must be '" + kRigFormat + "'");
    }
    if (!fs["version"].isInt() || static_cast<int>(fs["version"]) < 1 ||
        static_cast<int>(fs["version"]) > kRigVersion) {
      throw InputError(name + ": key 'version' must be an integer from 1 to " + std::to_string(kRigVersion) +
                       " (a newer rfrecon wrote this file?)");
    }
  }
  StereoRig rig;
  rig.camera_size = read_size(fs, "camera_size", name);
  rig.projector_size = read_size(fs, "projector_size", name);
  rig.camera_matrix = read_mat(fs, "camera_matrix", name);
  rig.dist_coeffs = read_mat(fs, "dist_coeffs", name);
  rig.projector_matrix = read_mat(fs, "projector_matrix", name);
  rig.projector_dist_coeffs = read_mat(fs, "projector_dist_coeffs", name);
  rig.proj_from_cam_rotation = read_mat(fs, "R", name);
  rig.proj_from_cam_translation_mm = read_mat(fs, "T", name);
  if (fs["rms"].empty()) throw InputError(name + ": missing key 'rms'");
  rig.rms = static_cast<double>(fs["rms"]);
  if (!fs["per_view_errors"].empty()) fs["per_view_errors"] >> rig.per_view_errors;
  if (!fs["camera_intrinsics_std"].empty()) {
    RigUncertainty& u = rig.uncertainty;
    for (const auto& [m, key, cols] : {std::tuple{&u.camera_intrinsics, "camera_intrinsics_std", 4},
                                       {&u.camera_dist_coeffs, "dist_coeffs_std", 0},
                                       {&u.projector_intrinsics, "projector_intrinsics_std", 4},
                                       {&u.projector_dist_coeffs, "projector_dist_coeffs_std", 0},
                                       {&u.proj_from_cam_rotation_vector, "om_std", 3},
                                       {&u.proj_from_cam_translation_mm, "T_std", 3}}) {
      *m = read_mat(fs, key, name);
      if (cols > 0) check_shape(*m, 1, cols, key, name);
    }
    if (!fs["parameter_covariance"].empty()) {
      u.parameter_covariance = read_mat(fs, "parameter_covariance", name, kMaxCovarianceElements);
      const int globals = rig_parameter_count(rig);
      check_shape(u.parameter_covariance, globals, globals, "parameter_covariance", name);
      check_finite(u.parameter_covariance, "parameter_covariance", name);
    }
  }
  const cv::FileNode board = fs["board"];
  if (!board.empty()) {
    if (!board.isMap()) throw InputError(name + ": key 'board' must be a map {cols, rows, square_size}");
    rig.board.cols = static_cast<int>(board["cols"]);
    rig.board.rows = static_cast<int>(board["rows"]);
    rig.board.square_size = static_cast<double>(board["square_size"]);
  }
  return complete_rig(std::move(rig), name);
}
}  // namespace

int rig_parameter_count(const StereoRig& rig) { return 2 * (4 + static_cast<int>(rig.dist_coeffs.total())) + 6; }

std::vector<double> rig_parameters(const StereoRig& rig, int dist_size) {
  std::vector<double> p;
  for (const auto& [matrix, dist] : {std::pair{&rig.camera_matrix, &rig.dist_coeffs},
                                     std::pair{&rig.projector_matrix, &rig.projector_dist_coeffs}}) {
    p.insert(p.end(),
             {matrix->at<double>(0, 0), matrix->at<double>(1, 1), matrix->at<double>(0, 2), matrix->at<double>(1, 2)});
    for (int i = 0; i < dist_size; ++i) p.push_back(i < static_cast<int>(dist->total()) ? dist->at<double>(i) : 0.0);
  }
  cv::Vec3d om;
  cv::Rodrigues(rig.proj_from_cam_rotation, om);
  p.insert(p.end(), {om[0], om[1], om[2]});
  for (int i = 0; i < 3; ++i) p.push_back(rig.proj_from_cam_translation_mm.at<double>(i));
  return p;
}

void set_rig_parameters(StereoRig& rig, const std::vector<double>& p, int dist_size) {
  const int block = 4 + dist_size;
  if (static_cast<int>(p.size()) < 2 * block + 6) {
    throw std::invalid_argument("set_rig_parameters: " + std::to_string(p.size()) + " parameters, fewer than a rig's " +
                                std::to_string(2 * block + 6));
  }
  for (auto [matrix, dist, at] : {std::tuple{&rig.camera_matrix, &rig.dist_coeffs, 0},
                                  std::tuple{&rig.projector_matrix, &rig.projector_dist_coeffs, block}}) {
    *matrix = (cv::Mat_<double>(3, 3) << p[at], 0, p[at + 2], 0, p[at + 1], p[at + 3], 0, 0, 1);
    *dist = cv::Mat(1, dist_size, CV_64F);
    std::copy(p.begin() + at + 4, p.begin() + at + block, dist->begin<double>());
  }
  const double* pose = p.data() + 2 * static_cast<std::size_t>(block);  // rotation vector, then T
  cv::Rodrigues(cv::Vec3d(pose[0], pose[1], pose[2]), rig.proj_from_cam_rotation);
  rig.proj_from_cam_translation_mm = (cv::Mat_<double>(3, 1) << pose[3], pose[4], pose[5]);
}

StereoRig complete_rig(StereoRig rig, const std::string& where) {
  check_measured(rig, where);
  try {
    compute_stereo_geometry(rig);
  } catch (const InputError& error) {
    throw InputError(where + ": " + error.what());
  }
  return rig;
}

StereoRig read_rig(const fs::path& file) {
  try {
    return read_rig_file(file);
  } catch (const cv::Exception& error) {
    throw InputError(file.string() + ": not a valid rig file (" + error.err + ")");
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& error) {  // OpenCV's YAML parser throws std::length_error on some inputs
    throw InputError(file.string() + ": not a valid rig file (" + error.what() + ")");
  }
}

}  // namespace rfrecon::calib
