// Reading, writing and completing the stereo rig file.
#include "calib/rig.h"

#include <string>

#include <opencv2/calib3d.hpp>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"

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

// Checks every matrix of the rig; `file` names the rig in messages.
void check_rig(const StereoRig& rig, const std::string& file) {
  for (const auto& [size, key] : {std::pair{rig.camera_size, "camera_size"}, {rig.projector_size, "projector_size"}}) {
    if (size.width <= 0 || size.height <= 0) throw InputError(file + ": key '" + key + "' must be [w, h] > 0");
  }
  check_shape(rig.camera_matrix, 3, 3, "camera_matrix", file);
  check_dist(rig.dist_coeffs, "dist_coeffs", file);
  check_shape(rig.projector_matrix, 3, 3, "projector_matrix", file);
  check_dist(rig.projector_dist_coeffs, "projector_dist_coeffs", file);
  check_shape(rig.R, 3, 3, "R", file);
  check_shape(rig.T, 3, 1, "T", file);
  check_shape(rig.E, 3, 3, "E", file);
  check_shape(rig.F, 3, 3, "F", file);
  check_shape(rig.R1, 3, 3, "R1", file);
  check_shape(rig.R2, 3, 3, "R2", file);
  check_shape(rig.P1, 3, 4, "P1", file);
  check_shape(rig.P2, 3, 4, "P2", file);
  check_shape(rig.Q, 4, 4, "Q", file);
}

cv::Mat as_double(const cv::Mat& m) {
  cv::Mat out;
  m.convertTo(out, CV_64F);
  return out;
}

cv::Mat read_mat(const cv::FileStorage& fs, const char* key, const std::string& file) {
  const cv::FileNode node = fs[key];
  if (node.empty()) throw InputError(file + ": missing key '" + key + "'");
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
  if (!node.isSeq() || node.size() != 2) throw InputError(file + ": key '" + key + "' must be [width, height]");
  return {static_cast<int>(node[0]), static_cast<int>(node[1])};
}
}  // namespace

void compute_stereo_geometry(StereoRig& rig) {
  check_shape(rig.R, 3, 3, "R", "stereo rig");
  check_shape(rig.T, 3, 1, "T", "stereo rig");
  const cv::Mat t = as_double(rig.T);
  const cv::Mat t_cross = (cv::Mat_<double>(3, 3) << 0, -t.at<double>(2), t.at<double>(1), t.at<double>(2), 0,
                           -t.at<double>(0), -t.at<double>(1), t.at<double>(0), 0);
  rig.E = t_cross * as_double(rig.R);
  rig.F = as_double(rig.projector_matrix).inv().t() * rig.E * as_double(rig.camera_matrix).inv();
  rig.F /= rig.F.at<double>(2, 2);
  cv::stereoRectify(rig.camera_matrix, rig.dist_coeffs, rig.projector_matrix, rig.projector_dist_coeffs,
                    rig.camera_size, rig.R, rig.T, rig.R1, rig.R2, rig.P1, rig.P2, rig.Q, cv::CALIB_ZERO_DISPARITY,
                    kRectifyAlpha, rig.camera_size);
}

void write_rig(const StereoRig& rig, const fs::path& file) {
  check_rig(rig, file.string());
  cv::FileStorage fs("rig.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs << "camera_size" << rig.camera_size << "projector_size" << rig.projector_size;
  fs << "camera_matrix" << as_double(rig.camera_matrix) << "dist_coeffs" << as_double(rig.dist_coeffs).reshape(1, 1);
  fs << "projector_matrix" << as_double(rig.projector_matrix) << "projector_dist_coeffs"
     << as_double(rig.projector_dist_coeffs).reshape(1, 1);
  fs << "R" << as_double(rig.R) << "T" << as_double(rig.T) << "E" << as_double(rig.E) << "F" << as_double(rig.F);
  fs << "R1" << as_double(rig.R1) << "R2" << as_double(rig.R2) << "P1" << as_double(rig.P1) << "P2" << as_double(rig.P2)
     << "Q" << as_double(rig.Q);
  fs << "rms" << rig.rms << "per_view_errors" << rig.per_view_errors;
  fs << "board"
     << "{"
     << "cols" << rig.board.cols << "rows" << rig.board.rows << "square_size" << rig.board.square_size << "}";
  write_file_atomically(file, fs.releaseAndGetString());
}

StereoRig read_rig(const fs::path& file) {
  const std::string name = file.string();
  cv::FileStorage fs;
  try {
    fs.open(name, cv::FileStorage::READ | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& error) {
    throw InputError(name + ": not a readable OpenCV YAML file (" + error.err + ")");
  }
  if (!fs.isOpened()) throw InputError("cannot read rig file " + name);
  StereoRig rig;
  rig.camera_size = read_size(fs, "camera_size", name);
  rig.projector_size = read_size(fs, "projector_size", name);
  rig.camera_matrix = read_mat(fs, "camera_matrix", name);
  rig.dist_coeffs = read_mat(fs, "dist_coeffs", name);
  rig.projector_matrix = read_mat(fs, "projector_matrix", name);
  rig.projector_dist_coeffs = read_mat(fs, "projector_dist_coeffs", name);
  rig.R = read_mat(fs, "R", name);
  rig.T = read_mat(fs, "T", name);
  rig.E = read_mat(fs, "E", name);
  rig.F = read_mat(fs, "F", name);
  rig.R1 = read_mat(fs, "R1", name);
  rig.R2 = read_mat(fs, "R2", name);
  rig.P1 = read_mat(fs, "P1", name);
  rig.P2 = read_mat(fs, "P2", name);
  rig.Q = read_mat(fs, "Q", name);
  if (fs["rms"].empty()) throw InputError(name + ": missing key 'rms'");
  rig.rms = static_cast<double>(fs["rms"]);
  if (!fs["per_view_errors"].empty()) fs["per_view_errors"] >> rig.per_view_errors;
  const cv::FileNode board = fs["board"];
  if (!board.empty()) {
    if (!board.isMap()) throw InputError(name + ": key 'board' must be a map {cols, rows, square_size}");
    rig.board.cols = static_cast<int>(board["cols"]);
    rig.board.rows = static_cast<int>(board["rows"]);
    rig.board.square_size = static_cast<double>(board["square_size"]);
  }
  check_rig(rig, name);
  return rig;
}

}  // namespace rfrecon::calib
