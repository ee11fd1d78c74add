// The joint adjustment of a stereo calibration, and its residuals and covariance (calib/joint_problem.h).
#include "calib/stereo_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <opencv2/calib3d.hpp>

namespace rfrecon::calib {

namespace {
JointLayout layout_of(const std::vector<StereoCorners>& corners, DistortionModel model) {
  JointLayout layout;
  layout.dist_size = distortion_vector_size(model);
  layout.views = static_cast<int>(corners.size());
  return layout;
}

// The parameter vector of the rig, each board pose fitted to its view's observations with the rig held fixed.
std::vector<double> fitted_parameters(const StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                                      const std::vector<StereoCorners>& corners, const JointProblem& problem) {
  const JointLayout& layout = problem.layout();
  std::vector<double> p = rig_parameters(rig, layout.dist_size);
  for (int v = 0; v < layout.views; ++v) {
    cv::Vec3d rvec;
    cv::Vec3d tvec;
    cv::solvePnP(object_points[v], corners[v].camera, rig.camera_matrix, rig.dist_coeffs, rvec, tvec);
    for (int i = 0; i < 3; ++i) p.push_back(rvec[i]);
    for (int i = 0; i < 3; ++i) p.push_back(tvec[i]);
  }
  for (int v = 0; v < layout.views; ++v) problem.refine_pose(p, v);
  return p;
}

// The RMS length of the residuals that `weights` keeps.
double kept_rms(const std::vector<cv::Point2d>& residuals, const ObservationWeights& weights) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < residuals.size(); ++i) {
    if (!weights.kept(i)) continue;
    sum += residuals[i].dot(residuals[i]);
    ++count;
  }
  return count == 0 ? 0.0 : std::sqrt(sum / static_cast<double>(count));
}

// The standard deviations of parameters [first, first + count) of the full vector, 0 where not estimated.
cv::Mat std_block(const std::vector<int>& columns, const cv::Mat& variances, int first, int count) {
  cv::Mat out = cv::Mat::zeros(1, count, CV_64F);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c] >= first && columns[c] < first + count) {
      const double variance = variances.at<double>(static_cast<int>(c));
      out.at<double>(columns[c] - first) =
          variance >= 0.0 ? std::sqrt(variance) : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return out;
}

// The covariance of the global parameters [0, globals) of the full vector, 0 in the rows and columns of those not
// estimated, from the unit-diagonal inverse `scaled_inverse`; empty when that is (a singular problem).
cv::Mat global_covariance(const JointColumns& columns, const cv::Mat& scaled_inverse, const cv::Mat& scale,
                          double sigma_px, int globals) {
  if (scaled_inverse.empty()) return {};
  cv::Mat out = cv::Mat::zeros(globals, globals, CV_64F);
  for (std::size_t a = 0; a < columns.index.size(); ++a) {
    for (std::size_t b = 0; b < columns.index.size(); ++b) {
      if (columns.index[a] >= globals || columns.index[b] >= globals) continue;
      const int i = static_cast<int>(a), j = static_cast<int>(b);
      out.at<double>(columns.index[a], columns.index[b]) =
          scaled_inverse.at<double>(i, j) * scale.at<double>(i) * scale.at<double>(j) * sigma_px * sigma_px;
    }
  }
  return out;
}
}  // namespace

std::size_t reject_dense_outliers(const StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                                  std::vector<StereoCorners>& corners, DistortionModel model, double max_px) {
  std::vector<StereoCorners> corners_only;
  corners_only.reserve(corners.size());
  for (const auto& view : corners) {
    corners_only.push_back({view.camera, view.projector, {}, {}, view.camera_weights, view.projector_weights, {}});
  }
  const JointLayout layout = layout_of(corners, model);
  const std::vector<double> p =
      fitted_parameters(rig, object_points, corners_only, JointProblem(object_points, corners_only, layout));
  const JointProblem problem(object_points, corners, layout);
  std::size_t removed = 0;
  std::vector<double> residuals;
  for (int v = 0; v < layout.views; ++v) {
    problem.view_errors(p, v, residuals);
    StereoCorners& view = corners[v];
    const std::size_t first = 4 * view.camera.size();  // the dense residuals follow both devices' corners
    std::size_t kept = 0;
    for (std::size_t i = 0; i < view.dense_camera.size(); ++i) {
      if (std::hypot(residuals[first + 2 * i], residuals[first + 2 * i + 1]) <= max_px) {
        view.dense_camera[kept] = view.dense_camera[i];
        view.dense_projector[kept] = view.dense_projector[i];
        ++kept;
      }
    }
    removed += view.dense_camera.size() - kept;
    view.dense_camera.resize(kept);
    view.dense_projector.resize(kept);
  }
  return removed;
}

double adjust_stereo(StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                     const std::vector<StereoCorners>& corners, DistortionModel model) {
  const JointLayout layout = layout_of(corners, model);
  const JointProblem problem(object_points, corners, layout);
  std::vector<double> p = fitted_parameters(rig, object_points, corners, problem);
  const double cost = problem.adjust(p, joint_columns(layout, model));
  set_rig_parameters(rig, p, layout.dist_size);
  const std::size_t count = problem.residuals(p).size();
  return count > 0 ? std::sqrt(cost / static_cast<double>(count)) : 0.0;
}

StereoFit analyse_stereo_fit(const StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                             const std::vector<StereoCorners>& corners, DistortionModel model) {
  const JointLayout layout = layout_of(corners, model);
  const JointProblem problem(object_points, corners, layout);
  const std::vector<double> p = fitted_parameters(rig, object_points, corners, problem);
  const JointColumns columns = joint_columns(layout, model);

  StereoFit fit;
  // Weighted residuals; a dropped point's are 0 and not counted.
  const std::vector<double> residuals = problem.residuals(p);
  double sum_sq = 0.0;
  for (const double r : residuals) sum_sq += r * r;
  std::size_t counted = 0;
  for (const auto& view : corners) {
    for (const auto* weights : {&view.camera_weights, &view.projector_weights}) {
      for (std::size_t i = 0; i < view.camera.size(); ++i) counted += weights->kept(i) ? 2 : 0;
    }
    counted += 2 * view.dense_camera.size();
  }
  const double dof = static_cast<double>(counted) - static_cast<double>(columns.index.size());
  fit.residual_sigma_px = dof > 0 ? std::sqrt(sum_sq / dof) : std::numeric_limits<double>::quiet_NaN();
  cv::Mat jtj;
  cv::Mat jtr;
  problem.normal_equations(p, columns, jtj, jtr);
  // Scaled to a unit diagonal before inverting (focal lengths, distortion and angles differ by 1e6 in scale).
  const int n = jtj.rows;
  cv::Mat scale(n, 1, CV_64F);
  for (int c = 0; c < n; ++c) scale.at<double>(c) = 1.0 / std::sqrt(std::max(jtj.at<double>(c, c), 1e-300));
  const cv::Mat scaled = jtj.mul(scale * scale.t());
  cv::Mat covariance;
  cv::Mat variances(n, 1, CV_64F, std::numeric_limits<double>::quiet_NaN());
  if (dof > 0 && cv::invert(scaled, covariance, cv::DECOMP_CHOLESKY) != 0.0) {
    variances = covariance.diag().mul(scale.mul(scale)) * (fit.residual_sigma_px * fit.residual_sigma_px);
  } else {
    covariance.release();
  }
  RigUncertainty& u = fit.uncertainty;
  u.camera_intrinsics = std_block(columns.index, variances, 0, 4);
  u.camera_dist_coeffs = std_block(columns.index, variances, 4, layout.dist_size);
  u.projector_intrinsics = std_block(columns.index, variances, layout.device_block(), 4);
  u.projector_dist_coeffs = std_block(columns.index, variances, layout.device_block() + 4, layout.dist_size);
  u.proj_from_cam_rotation_vector = std_block(columns.index, variances, layout.om(), 3);
  u.proj_from_cam_translation_mm = std_block(columns.index, variances, layout.t(), 3);
  u.parameter_covariance = global_covariance(columns, covariance, scale, fit.residual_sigma_px, layout.pose(0));

  std::vector<double> view;
  for (int v = 0; v < layout.views; ++v) {
    const int pose = layout.pose(v);
    fit.board_rvecs.emplace_back(p[pose], p[pose + 1], p[pose + 2]);
    fit.board_tvecs.emplace_back(p[pose + 3], p[pose + 4], p[pose + 5]);
    problem.view_errors(p, v, view);
    // camera corners, projector corners, then the dense correspondences (view_residuals' order)
    const std::size_t corner_count = object_points[v].size();
    std::vector<cv::Point2d> by_part[3];
    for (std::size_t i = 0; i + 1 < view.size(); i += 2) {
      const std::size_t point = i / 2;
      const int part = point < corner_count ? 0 : (point < 2 * corner_count ? 1 : 2);
      by_part[part].emplace_back(view[i], view[i + 1]);
    }
    fit.camera_view_rms_px.push_back(kept_rms(by_part[0], corners[v].camera_weights));
    fit.projector_view_rms_px.push_back(kept_rms(by_part[1], corners[v].projector_weights));
    fit.dense_view_rms_px.push_back(kept_rms(by_part[2], corners[v].dense_weights));
    fit.dense_residuals_px.push_back(std::move(by_part[2]));
    fit.camera_residuals_px.push_back(std::move(by_part[0]));
    fit.projector_residuals_px.push_back(std::move(by_part[1]));
  }
  return fit;
}

}  // namespace rfrecon::calib
