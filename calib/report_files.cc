// Report charts, report.json and corners.json of a calibration.
#include "calib/report_files.h"

#include <algorithm>

#include <opencv2/calib3d.hpp>

#include "calib/report.h"
#include "calib/residual_field.h"
#include "host/core/atomic_file.h"
#include "host/core/image_file.h"

namespace rfrecon::calib {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
std::vector<double> values(const cv::Mat& m) {
  std::vector<double> out;
  for (std::size_t i = 0; i < m.total(); ++i) out.push_back(m.at<double>(static_cast<int>(i)));
  return out;
}

json intrinsics_json(const cv::Mat& matrix, const cv::Mat& dist, const cv::Mat& intrinsics_std,
                     const cv::Mat& dist_std) {
  return {{"fx", matrix.at<double>(0, 0)},
          {"fy", matrix.at<double>(1, 1)},
          {"cx", matrix.at<double>(0, 2)},
          {"cy", matrix.at<double>(1, 2)},
          {"dist_coeffs", values(dist)},
          {"std",
           {{"fx", intrinsics_std.at<double>(0)},
            {"fy", intrinsics_std.at<double>(1)},
            {"cx", intrinsics_std.at<double>(2)},
            {"cy", intrinsics_std.at<double>(3)},
            {"dist_coeffs", values(dist_std)}}}};
}

std::vector<std::vector<cv::Point2f>> corners_of(const std::vector<StereoView>& views, bool projector) {
  std::vector<std::vector<cv::Point2f>> out;
  out.reserve(views.size());
  for (const auto& view : views) out.push_back(projector ? view.projector_corners : view.camera_corners);
  return out;
}
std::size_t dropped_count(const std::vector<std::vector<unsigned char>>& dropped, std::size_t view) {
  return view < dropped.size() ? static_cast<std::size_t>(std::count(dropped[view].begin(), dropped[view].end(), 1))
                               : 0;
}

cv::Mat field_background(const cv::Mat& background, cv::Size size) {
  return background.empty() ? cv::Mat(size, CV_8UC1, cv::Scalar(0)) : background;
}
}  // namespace

json camera_report_json(const CameraCalibration& calibration) {
  json views = json::array();
  for (std::size_t i = 0; i < calibration.view_names.size(); ++i) {
    views.push_back({{"name", calibration.view_names[i]}, {"rms_px", calibration.per_view_errors[i]}});
  }
  return {{"rms_px", calibration.rms},
          {"camera", intrinsics_json(calibration.camera_matrix, calibration.dist_coeffs, calibration.intrinsics_std,
                                     calibration.dist_coeffs_std)},
          {"views", views},
          {"tilt_spread_deg", calibration.tilt_spread_deg},
          {"coverage", {{"camera", calibration.coverage}}},
          {"warnings", calibration.warnings}};
}

json stereo_report_json(const StereoCalibration& calibration) {
  const StereoRig& rig = calibration.rig;
  const RigUncertainty& u = rig.uncertainty;
  json views = json::array();
  for (std::size_t i = 0; i < calibration.camera.view_names.size(); ++i) {
    views.push_back({{"name", calibration.camera.view_names[i]},
                     {"camera_rms_px", calibration.fit.camera_view_rms_px[i]},
                     {"projector_rms_px", calibration.fit.projector_view_rms_px[i]},
                     {"dense_rms_px", calibration.fit.dense_view_rms_px[i]},
                     {"camera_corners_dropped", dropped_count(calibration.camera_dropped, i)},
                     {"projector_corners_dropped", dropped_count(calibration.projector_dropped, i)}});
  }
  cv::Vec3d om;
  cv::Rodrigues(rig.proj_from_cam_rotation, om);
  return {{"rms_px", rig.rms},
          {"rms_all_corners_px", calibration.rms_all_px},
          {"gating", gating_json(calibration.gating_thresholds, calibration.gating)},
          {"residual_sigma_px", calibration.fit.residual_sigma_px},
          {"camera", intrinsics_json(rig.camera_matrix, rig.dist_coeffs, u.camera_intrinsics, u.camera_dist_coeffs)},
          {"projector", intrinsics_json(rig.projector_matrix, rig.projector_dist_coeffs, u.projector_intrinsics,
                                        u.projector_dist_coeffs)},
          {"om", {om[0], om[1], om[2]}},
          {"om_std", values(u.proj_from_cam_rotation_vector)},
          {"T_mm", values(rig.proj_from_cam_translation_mm)},
          {"T_std_mm", values(u.proj_from_cam_translation_mm)},
          {"baseline_mm", cv::norm(rig.proj_from_cam_translation_mm)},
          {"views", views},
          {"tilt_spread_deg", calibration.camera.tilt_spread_deg},
          {"coverage", {{"camera", calibration.camera.coverage}, {"projector", calibration.projector.coverage}}},
          {"warnings", calibration.warnings}};
}

json corners_json(const std::vector<StereoView>& views) {
  const auto points = [](const std::vector<cv::Point2f>& corners) {
    json out = json::array();
    for (const auto& p : corners) out.push_back({p.x, p.y});
    return out;
  };
  json out = json::array();
  for (const auto& view : views) {
    out.push_back({{"name", view.name},
                   {"camera_px", points(view.camera_corners)},
                   {"projector_px", points(view.projector_corners)}});
  }
  return {{"views", out}};
}

void write_camera_report(const fs::path& dir, const CameraCalibration& calibration,
                         const std::vector<BoardView>& views) {
  std::vector<std::vector<cv::Point2f>> corners;
  corners.reserve(views.size());
  for (const auto& view : views) corners.push_back(view.corners);
  write_image(dir / "errors.png", draw_error_chart(calibration.view_names, {"camera"}, {calibration.per_view_errors}));
  write_image(dir / "residuals_camera.png", draw_residuals(calibration.view_names, calibration.residuals_px, "camera"));
  write_image(dir / "coverage_camera.png",
              draw_coverage_map(corners, calibration.board, calibration.image_size, "camera"));
  write_file_atomically(dir / "report.json", camera_report_json(calibration).dump(2) + "\n");
}

void write_stereo_report(const fs::path& dir, const StereoCalibration& calibration,
                         const std::vector<StereoView>& views, const cv::Mat& camera_background,
                         const cv::Mat& projector_background) {
  const auto& names = calibration.camera.view_names;
  const StereoFit& fit = calibration.fit;
  write_image(dir / "errors.png",
              draw_error_chart(names, {"camera", "projector"}, {fit.camera_view_rms_px, fit.projector_view_rms_px}));
  write_image(dir / "residuals_camera.png", draw_residuals(names, fit.camera_residuals_px, "camera"));
  write_image(dir / "residuals_projector.png", draw_residuals(names, fit.projector_residuals_px, "projector"));
  write_image(
      dir / "residual_field_camera.png",
      draw_residual_field(field_background(camera_background, calibration.rig.camera_size), names,
                          corners_of(views, false), fit.camera_residuals_px, calibration.camera_dropped, "camera"));
  write_image(dir / "residual_field_projector.png",
              draw_residual_field(field_background(projector_background, calibration.rig.projector_size), names,
                                  corners_of(views, true), fit.projector_residuals_px, calibration.projector_dropped,
                                  "projector"));
  write_image(dir / "coverage_camera.png", draw_coverage_map(corners_of(views, false), calibration.rig.board,
                                                             calibration.rig.camera_size, "camera"));
  write_image(dir / "coverage_projector.png", draw_coverage_map(corners_of(views, true), calibration.rig.board,
                                                                calibration.rig.projector_size, "projector"));
  write_file_atomically(dir / "report.json", stereo_report_json(calibration).dump(2) + "\n");
  write_file_atomically(dir / "corners.json", corners_json(views).dump(1) + "\n");
}

}  // namespace rfrecon::calib
