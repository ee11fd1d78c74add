// Rig against rig, through triangulation of exact correspondences.
#include "calib/rig_comparison.h"

#include <cmath>

#include <opencv2/calib3d.hpp>

#include "calib/rectification.h"

namespace rfrecon::calib {

namespace {
double focal_error(const cv::Mat& estimated, const cv::Mat& truth) {
  return std::max(std::abs(estimated.at<double>(0, 0) / truth.at<double>(0, 0) - 1.0),
                  std::abs(estimated.at<double>(1, 1) / truth.at<double>(1, 1) - 1.0));
}

double principal_error(const cv::Mat& estimated, const cv::Mat& truth) {
  return std::hypot(estimated.at<double>(0, 2) - truth.at<double>(0, 2),
                    estimated.at<double>(1, 2) - truth.at<double>(1, 2));
}

// Normalised, undistorted image coordinates of `pixels` as rays (x, y, 1).
std::vector<cv::Vec3d> rays(const std::vector<cv::Point2d>& pixels, const cv::Mat& matrix, const cv::Mat& dist) {
  std::vector<cv::Point2d> normalised;
  cv::undistortPoints(pixels, normalised, matrix, dist, cv::noArray(), cv::noArray(), undistort_criteria());
  std::vector<cv::Vec3d> out;
  out.reserve(normalised.size());
  for (const auto& p : normalised) out.emplace_back(p.x, p.y, 1.0);
  return out;
}
}  // namespace

RigComparison compare_rigs(const StereoRig& estimated, const StereoRig& truth, double near_mm, double far_mm) {
  RigComparison c;
  c.camera_focal_error = focal_error(estimated.camera_matrix, truth.camera_matrix);
  c.camera_principal_error_px = principal_error(estimated.camera_matrix, truth.camera_matrix);
  c.projector_focal_error = focal_error(estimated.projector_matrix, truth.projector_matrix);
  c.projector_principal_error_px = principal_error(estimated.projector_matrix, truth.projector_matrix);
  c.baseline_error =
      cv::norm(estimated.proj_from_cam_translation_mm) / cv::norm(truth.proj_from_cam_translation_mm) - 1.0;
  cv::Vec3d angle;
  cv::Rodrigues(cv::Mat(estimated.proj_from_cam_rotation * truth.proj_from_cam_rotation.t()), angle);
  c.rotation_error_deg = cv::norm(angle) * 180.0 / CV_PI;

  constexpr int kGrid = 16;
  std::vector<cv::Point2d> camera_px;
  for (int j = 0; j < kGrid; ++j) {
    for (int i = 0; i < kGrid; ++i) {
      camera_px.emplace_back((i + 0.5) * truth.camera_size.width / kGrid, (j + 0.5) * truth.camera_size.height / kGrid);
    }
  }
  const auto true_rays = rays(camera_px, truth.camera_matrix, truth.dist_coeffs);
  std::vector<cv::Point3d> points_cam;
  std::vector<cv::Point2d> seen_px;
  for (const double depth : {near_mm, 0.5 * (near_mm + far_mm), far_mm}) {
    for (std::size_t k = 0; k < true_rays.size(); ++k) {
      points_cam.emplace_back(true_rays[k] * depth);
      seen_px.push_back(camera_px[k]);
    }
  }
  cv::Vec3d true_om;
  cv::Rodrigues(truth.proj_from_cam_rotation, true_om);
  std::vector<cv::Point2d> projector_px;
  cv::projectPoints(points_cam, true_om, truth.proj_from_cam_translation_mm, truth.projector_matrix,
                    truth.projector_dist_coeffs, projector_px);

  const auto camera_rays = rays(seen_px, estimated.camera_matrix, estimated.dist_coeffs);
  const auto projector_rays = rays(projector_px, estimated.projector_matrix, estimated.projector_dist_coeffs);
  const cv::Matx33d cam_from_proj = cv::Matx33d(estimated.proj_from_cam_rotation).t();
  const cv::Vec3d projector_centre = -(cam_from_proj * cv::Vec3d(estimated.proj_from_cam_translation_mm));
  double zz = 0.0;
  double tt = 0.0;
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < points_cam.size(); ++k) {
    const cv::Point2d& p = projector_px[k];
    if (p.x < 0 || p.y < 0 || p.x > truth.projector_size.width - 1 || p.y > truth.projector_size.height - 1) continue;
    // Midpoint of the closest points of the rays a s (camera) and o + b t (projector).
    const cv::Vec3d& a = camera_rays[k];
    const cv::Vec3d b = cam_from_proj * projector_rays[k];
    const cv::Vec3d& o = projector_centre;
    const double aa = a.dot(a), ab = a.dot(b), bb = b.dot(b), ao = a.dot(o), bo = b.dot(o);
    const double det = aa * bb - ab * ab;
    if (std::abs(det) < 1e-12) continue;
    const double s = (ao * bb - ab * bo) / det;
    const double t = (ab * ao - aa * bo) / det;
    const double z_est = 0.5 * ((a * s)[2] + (o + b * t)[2]);
    const double z_true = points_cam[k].z;
    zz += z_est * z_true;
    tt += z_true * z_true;
    sum_sq += (z_est / z_true - 1.0) * (z_est / z_true - 1.0);
    ++c.points;
  }
  if (c.points > 0) {
    c.depth_scale_error = zz / tt - 1.0;
    c.depth_rms_error = std::sqrt(sum_sq / c.points);
  }
  return c;
}

}  // namespace rfrecon::calib
