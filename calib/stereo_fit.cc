// Joint residuals, pose refinement and covariance of a stereo calibration, with a numerical Jacobian.
#include "calib/stereo_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/calib3d.hpp>

namespace rfrecon::calib {

namespace {
// Intrinsics as fx, fy, cx, cy followed by the full distortion vector of the model.
std::vector<double> device_parameters(const cv::Mat& matrix, const cv::Mat& dist, int dist_size) {
  std::vector<double> p = {matrix.at<double>(0, 0), matrix.at<double>(1, 1), matrix.at<double>(0, 2),
                           matrix.at<double>(1, 2)};
  for (int i = 0; i < dist_size; ++i) p.push_back(i < static_cast<int>(dist.total()) ? dist.at<double>(i) : 0.0);
  return p;
}

// The parameter vector of the joint problem: camera, projector (4 + dist_size each), om, T, then (rvec, tvec) per
// view; and which of its entries are estimated.
struct Layout {
  int dist_size = 5;
  int views = 0;
  int device_block() const { return 4 + dist_size; }
  int om() const { return 2 * device_block(); }
  int t() const { return om() + 3; }
  int pose(int view) const { return t() + 3 + 6 * view; }
  int size() const { return pose(views); }
};

class JointProblem {
 public:
  JointProblem(const std::vector<std::vector<cv::Point3f>>& object_points, const std::vector<StereoCorners>& corners,
               Layout layout)
      : corners_(corners), layout_(layout) {
    for (const auto& view : object_points) object_points_.emplace_back(view.begin(), view.end());
  }

  // Residuals (projected - detected) of view `view` for both devices, x and y interleaved, camera first.
  void view_residuals(const std::vector<double>& p, int view, std::vector<double>& out) const {
    const auto matrix = [&](int block) {
      return cv::Matx33d(p[block], 0, p[block + 2], 0, p[block + 1], p[block + 3], 0, 0, 1);
    };
    const auto dist = [&](int block) {
      cv::Mat coefficients(1, layout_.dist_size, CV_64F);
      std::copy_n(p.begin() + block + 4, layout_.dist_size, coefficients.begin<double>());
      return coefficients;
    };
    const int pose = layout_.pose(view);
    const cv::Vec3d rvec(p[pose], p[pose + 1], p[pose + 2]);
    const cv::Vec3d tvec(p[pose + 3], p[pose + 4], p[pose + 5]);
    cv::Matx33d proj_from_cam;
    cv::Rodrigues(cv::Vec3d(p[layout_.om()], p[layout_.om() + 1], p[layout_.om() + 2]), proj_from_cam);
    cv::Matx33d cam_from_board;
    cv::Rodrigues(rvec, cam_from_board);
    cv::Vec3d proj_rvec;
    cv::Rodrigues(proj_from_cam * cam_from_board, proj_rvec);
    const cv::Vec3d proj_tvec =
        proj_from_cam * tvec + cv::Vec3d(p[layout_.t()], p[layout_.t() + 1], p[layout_.t() + 2]);
    std::vector<cv::Point2d> camera_px;
    std::vector<cv::Point2d> projector_px;
    cv::projectPoints(object_points_[view], rvec, tvec, matrix(0), dist(0), camera_px);
    cv::projectPoints(object_points_[view], proj_rvec, proj_tvec, matrix(layout_.device_block()),
                      dist(layout_.device_block()), projector_px);
    out.clear();
    for (std::size_t i = 0; i < camera_px.size(); ++i) {
      out.push_back(camera_px[i].x - corners_[view].camera[i].x);
      out.push_back(camera_px[i].y - corners_[view].camera[i].y);
    }
    for (std::size_t i = 0; i < projector_px.size(); ++i) {
      out.push_back(projector_px[i].x - corners_[view].projector[i].x);
      out.push_back(projector_px[i].y - corners_[view].projector[i].y);
    }
  }

  std::vector<double> residuals(const std::vector<double>& p) const {
    std::vector<double> all;
    std::vector<double> view;
    for (int v = 0; v < layout_.views; ++v) {
      view_residuals(p, v, view);
      all.insert(all.end(), view.begin(), view.end());
    }
    return all;
  }

  // Central-difference Jacobian of `residual(p)` over the parameters `columns`: one row per residual.
  template <typename Residual>
  static cv::Mat jacobian(std::vector<double> p, const std::vector<int>& columns, const std::vector<double>& steps,
                          Residual&& residual) {
    cv::Mat j;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const int k = columns[c];
      const double original = p[k];
      p[k] = original + steps[c];
      const std::vector<double> plus = residual(p);
      p[k] = original - steps[c];
      const std::vector<double> minus = residual(p);
      p[k] = original;
      if (j.empty()) j = cv::Mat::zeros(static_cast<int>(plus.size()), static_cast<int>(columns.size()), CV_64F);
      for (std::size_t r = 0; r < plus.size(); ++r) {
        j.at<double>(static_cast<int>(r), static_cast<int>(c)) = (plus[r] - minus[r]) / (2.0 * steps[c]);
      }
    }
    return j;
  }

  // Gauss-Newton on one view's pose with everything else fixed.
  void refine_pose(std::vector<double>& p, int view) const {
    const int pose = layout_.pose(view);
    const std::vector<int> columns = {pose, pose + 1, pose + 2, pose + 3, pose + 4, pose + 5};
    const std::vector<double> steps = {1e-7, 1e-7, 1e-7, 1e-5, 1e-5, 1e-5};
    const auto residual = [&](const std::vector<double>& q) {
      std::vector<double> r;
      view_residuals(q, view, r);
      return r;
    };
    for (int iteration = 0; iteration < 10; ++iteration) {
      const cv::Mat j = jacobian(p, columns, steps, residual);
      const cv::Mat r(residual(p), true);
      cv::Mat delta;
      if (!cv::solve(j.t() * j, -j.t() * r, delta, cv::DECOMP_CHOLESKY)) return;
      for (int i = 0; i < 6; ++i) p[columns[i]] += delta.at<double>(i);
      if (cv::norm(delta, cv::NORM_INF) < 1e-12) return;
    }
  }

 private:
  std::vector<std::vector<cv::Point3d>> object_points_;  // double, so projectPoints works in double
  const std::vector<StereoCorners>& corners_;
  Layout layout_;
};

double rms(const std::vector<cv::Point2d>& residuals) {
  double sum = 0.0;
  for (const auto& r : residuals) sum += r.dot(r);
  return residuals.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(residuals.size()));
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
}  // namespace

StereoFit analyse_stereo_fit(const StereoRig& rig, const std::vector<std::vector<cv::Point3f>>& object_points,
                             const std::vector<StereoCorners>& corners, DistortionModel model) {
  Layout layout;
  layout.dist_size = distortion_vector_size(model);
  layout.views = static_cast<int>(corners.size());
  std::vector<double> p = device_parameters(rig.camera_matrix, rig.dist_coeffs, layout.dist_size);
  const auto projector = device_parameters(rig.projector_matrix, rig.projector_dist_coeffs, layout.dist_size);
  p.insert(p.end(), projector.begin(), projector.end());
  cv::Vec3d om;
  cv::Rodrigues(rig.R, om);
  for (int i = 0; i < 3; ++i) p.push_back(om[i]);
  for (int i = 0; i < 3; ++i) p.push_back(rig.T.at<double>(i));
  for (int v = 0; v < layout.views; ++v) {
    cv::Vec3d rvec;
    cv::Vec3d tvec;
    cv::solvePnP(object_points[v], corners[v].camera, rig.camera_matrix, rig.dist_coeffs, rvec, tvec);
    for (int i = 0; i < 3; ++i) p.push_back(rvec[i]);
    for (int i = 0; i < 3; ++i) p.push_back(tvec[i]);
  }
  const JointProblem problem(object_points, corners, layout);
  for (int v = 0; v < layout.views; ++v) problem.refine_pose(p, v);

  // The estimated parameters and their difference steps.
  std::vector<int> columns;
  std::vector<double> steps;
  for (const int block : {0, layout.device_block()}) {
    for (int i = 0; i < 4; ++i) {
      columns.push_back(block + i);
      steps.push_back(1e-4);
    }
    for (const int i : estimated_distortion_indices(model)) {
      columns.push_back(block + 4 + i);
      steps.push_back(1e-7);
    }
  }
  for (int i = 0; i < 3; ++i) {
    columns.push_back(layout.om() + i);
    steps.push_back(1e-8);
  }
  for (int i = 0; i < 3; ++i) {
    columns.push_back(layout.t() + i);
    steps.push_back(1e-5);
  }
  for (int k = layout.pose(0); k < layout.size(); ++k) {
    columns.push_back(k);
    steps.push_back((k - layout.pose(0)) % 6 < 3 ? 1e-8 : 1e-5);
  }

  StereoFit fit;
  const std::vector<double> residuals = problem.residuals(p);
  const cv::Mat j =
      JointProblem::jacobian(p, columns, steps, [&](const std::vector<double>& q) { return problem.residuals(q); });
  double sum_sq = 0.0;
  for (const double r : residuals) sum_sq += r * r;
  const double dof = static_cast<double>(residuals.size()) - static_cast<double>(columns.size());
  fit.residual_sigma_px = dof > 0 ? std::sqrt(sum_sq / dof) : std::numeric_limits<double>::quiet_NaN();
  // Columns scaled to unit norm before inverting (focal lengths, distortion and angles differ by 1e6 in scale).
  cv::Mat scale(1, j.cols, CV_64F);
  for (int c = 0; c < j.cols; ++c) scale.at<double>(c) = 1.0 / std::max(cv::norm(j.col(c)), 1e-300);
  const cv::Mat scaled = j.mul(cv::repeat(scale, j.rows, 1));
  cv::Mat covariance;
  cv::Mat variances(j.cols, 1, CV_64F, std::numeric_limits<double>::quiet_NaN());
  if (dof > 0 && cv::invert(scaled.t() * scaled, covariance, cv::DECOMP_CHOLESKY) != 0.0) {
    const cv::Mat scale_sq = scale.t().mul(scale.t());
    variances = covariance.diag().mul(scale_sq) * (fit.residual_sigma_px * fit.residual_sigma_px);
  }
  RigUncertainty& u = fit.uncertainty;
  u.camera_intrinsics = std_block(columns, variances, 0, 4);
  u.camera_dist_coeffs = std_block(columns, variances, 4, layout.dist_size);
  u.projector_intrinsics = std_block(columns, variances, layout.device_block(), 4);
  u.projector_dist_coeffs = std_block(columns, variances, layout.device_block() + 4, layout.dist_size);
  u.om = std_block(columns, variances, layout.om(), 3);
  u.T = std_block(columns, variances, layout.t(), 3);

  std::size_t next = 0;
  for (int v = 0; v < layout.views; ++v) {
    const int pose = layout.pose(v);
    fit.board_rvecs.emplace_back(p[pose], p[pose + 1], p[pose + 2]);
    fit.board_tvecs.emplace_back(p[pose + 3], p[pose + 4], p[pose + 5]);
    for (auto* device : {&fit.camera_residuals_px, &fit.projector_residuals_px}) {
      std::vector<cv::Point2d> view;
      for (std::size_t i = 0; i < object_points[v].size(); ++i, next += 2) {
        view.emplace_back(residuals[next], residuals[next + 1]);
      }
      device->push_back(std::move(view));
    }
    fit.camera_view_rms_px.push_back(rms(fit.camera_residuals_px.back()));
    fit.projector_view_rms_px.push_back(rms(fit.projector_residuals_px.back()));
  }
  return fit;
}

}  // namespace rfrecon::calib
