// Residuals, per-view Jacobians and the Levenberg-Marquardt adjustment of the joint calibration problem.
#include "calib/joint_problem.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>

#include "calib/rectification.h"

namespace rfrecon::calib {

namespace {
cv::Matx33d device_matrix(const std::vector<double>& p, int block) {
  return {p[block], 0, p[block + 2], 0, p[block + 1], p[block + 3], 0, 0, 1};
}

cv::Mat device_dist(const std::vector<double>& p, int block, int dist_size) {
  cv::Mat coefficients(1, dist_size, CV_64F);
  std::copy_n(p.begin() + block + 4, dist_size, coefficients.begin<double>());
  return coefficients;
}

cv::Matx33d rotation(const std::vector<double>& p, int at) {
  cv::Matx33d r;
  cv::Rodrigues(cv::Vec3d(p[at], p[at + 1], p[at + 2]), r);
  return r;
}

double sum_of_squares(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v * v;
  return sum;
}
}  // namespace

JointColumns joint_columns(const JointLayout& layout, DistortionModel model) {
  JointColumns columns;
  const auto add = [&](int index, double step) {
    columns.index.push_back(index);
    columns.step.push_back(step);
  };
  for (const int block : {0, layout.device_block()}) {
    for (int i = 0; i < 4; ++i) add(block + i, 1e-4);
    for (const int i : estimated_distortion_indices(model)) add(block + 4 + i, 1e-7);
  }
  for (int i = 0; i < 3; ++i) add(layout.om() + i, 1e-8);
  for (int i = 0; i < 3; ++i) add(layout.t() + i, 1e-5);
  columns.globals = static_cast<int>(columns.index.size());
  for (int k = layout.pose(0); k < layout.size(); ++k) add(k, (k - layout.pose(0)) % 6 < 3 ? 1e-8 : 1e-5);
  return columns;
}

JointProblem::JointProblem(const std::vector<std::vector<cv::Point3f>>& object_points,
                           const std::vector<StereoCorners>& corners, JointLayout layout)
    : corners_(corners), layout_(layout) {
  for (const auto& view : object_points) object_points_.emplace_back(view.begin(), view.end());
}

std::vector<cv::Point2d> JointProblem::dense_rays(const std::vector<double>& p, int view) const {
  const StereoCorners& observed = corners_[view];
  std::vector<cv::Point2d> rays;
  if (observed.dense_camera.empty()) return rays;
  // In double: the Jacobian's differences are far below float's resolution.
  const std::vector<cv::Point2d> camera_points(observed.dense_camera.begin(), observed.dense_camera.end());
  cv::undistortPoints(camera_points, rays, device_matrix(p, 0), device_dist(p, 0, layout_.dist_size), cv::noArray(),
                      cv::noArray(), undistort_criteria());
  return rays;
}

void JointProblem::view_residuals(const std::vector<double>& p, int view, std::vector<double>& out) const {
  view_residuals(p, view, dense_rays(p, view), true, out);
}

void JointProblem::view_errors(const std::vector<double>& p, int view, std::vector<double>& out) const {
  view_residuals(p, view, dense_rays(p, view), false, out);
}

void JointProblem::view_residuals(const std::vector<double>& p, int view, const std::vector<cv::Point2d>& rays,
                                  bool weighted, std::vector<double>& out) const {
  const int pose = layout_.pose(view);
  const cv::Vec3d cam_from_board_rvec(p[pose], p[pose + 1], p[pose + 2]);
  const cv::Vec3d cam_from_board_tvec(p[pose + 3], p[pose + 4], p[pose + 5]);
  const cv::Matx33d proj_from_cam = rotation(p, layout_.om());
  const cv::Matx33d cam_from_board = rotation(p, pose);
  cv::Vec3d proj_from_board_rvec;
  cv::Rodrigues(proj_from_cam * cam_from_board, proj_from_board_rvec);
  const cv::Vec3d proj_from_board_tvec =
      proj_from_cam * cam_from_board_tvec + cv::Vec3d(p[layout_.t()], p[layout_.t() + 1], p[layout_.t() + 2]);
  const cv::Mat camera_dist = device_dist(p, 0, layout_.dist_size);
  const cv::Matx33d projector_matrix = device_matrix(p, layout_.device_block());
  const cv::Mat projector_dist = device_dist(p, layout_.device_block(), layout_.dist_size);
  std::vector<cv::Point2d> camera_px;
  std::vector<cv::Point2d> projector_px;
  cv::projectPoints(object_points_[view], cam_from_board_rvec, cam_from_board_tvec, device_matrix(p, 0), camera_dist,
                    camera_px);
  cv::projectPoints(object_points_[view], proj_from_board_rvec, proj_from_board_tvec, projector_matrix, projector_dist,
                    projector_px);
  const StereoCorners& observed = corners_[view];
  out.clear();
  const auto append = [&](const std::vector<cv::Point2d>& predicted, const std::vector<cv::Point2f>& measured,
                          const ObservationWeights& weights) {
    for (std::size_t i = 0; i < predicted.size(); ++i) {
      const double factor = weighted ? std::sqrt(weights.of(i)) : 1.0;
      out.push_back(factor * (predicted[i].x - measured[i].x));
      out.push_back(factor * (predicted[i].y - measured[i].y));
    }
  };
  append(camera_px, observed.camera, observed.camera_weights);
  append(projector_px, observed.projector, observed.projector_weights);
  if (observed.dense_camera.empty()) return;

  // Each dense camera pixel's ray meets the board's plane z = 0 at a board point, which the projector sees like a
  // corner.
  const cv::Vec3d normal(cam_from_board(0, 2), cam_from_board(1, 2), cam_from_board(2, 2));
  const double distance = normal.dot(cam_from_board_tvec);
  std::vector<cv::Point3d> board_points;
  board_points.reserve(rays.size());
  for (const auto& ray : rays) {
    const cv::Vec3d direction(ray.x, ray.y, 1.0);
    const cv::Vec3d on_board =
        cam_from_board.t() * (direction * (distance / normal.dot(direction)) - cam_from_board_tvec);
    board_points.emplace_back(on_board[0], on_board[1], on_board[2]);
  }
  std::vector<cv::Point2d> dense_px;
  cv::projectPoints(board_points, proj_from_board_rvec, proj_from_board_tvec, projector_matrix, projector_dist,
                    dense_px);
  append(dense_px, observed.dense_projector, observed.dense_weights);
}

std::vector<double> JointProblem::residuals(const std::vector<double>& p) const {
  std::vector<double> all;
  std::vector<double> view;
  for (int v = 0; v < layout_.views; ++v) {
    view_residuals(p, v, view);
    all.insert(all.end(), view.begin(), view.end());
  }
  return all;
}

cv::Mat JointProblem::view_jacobian(const std::vector<double>& p, int view, const std::vector<int>& index,
                                    const std::vector<double>& step) const {
  std::vector<double> q = p;
  std::vector<double> plus;
  std::vector<double> minus;
  // The dense rays change with the camera block only (its first device_block() entries): the other columns reuse
  // those at p instead of undistorting every dense pixel twice each.
  const std::vector<cv::Point2d> rays_at_p = dense_rays(p, view);
  const auto residuals_at = [&](int k, std::vector<double>& out) {
    if (k < layout_.device_block()) {
      view_residuals(q, view, out);
    } else {
      view_residuals(q, view, rays_at_p, true, out);
    }
  };
  cv::Mat j;
  for (std::size_t c = 0; c < index.size(); ++c) {
    const int k = index[c];
    q[k] = p[k] + step[c];
    residuals_at(k, plus);
    q[k] = p[k] - step[c];
    residuals_at(k, minus);
    q[k] = p[k];
    if (j.empty()) j = cv::Mat::zeros(static_cast<int>(plus.size()), static_cast<int>(index.size()), CV_64F);
    for (std::size_t r = 0; r < plus.size(); ++r) {
      j.at<double>(static_cast<int>(r), static_cast<int>(c)) = (plus[r] - minus[r]) / (2.0 * step[c]);
    }
  }
  return j;
}

void JointProblem::refine_pose(std::vector<double>& p, int view) const {
  const int pose = layout_.pose(view);
  const std::vector<int> index = {pose, pose + 1, pose + 2, pose + 3, pose + 4, pose + 5};
  const std::vector<double> step = {1e-7, 1e-7, 1e-7, 1e-5, 1e-5, 1e-5};
  std::vector<double> r;
  for (int iteration = 0; iteration < 10; ++iteration) {
    const cv::Mat j = view_jacobian(p, view, index, step);
    view_residuals(p, view, r);
    cv::Mat delta;
    if (!cv::solve(j.t() * j, -j.t() * cv::Mat(r), delta, cv::DECOMP_CHOLESKY)) return;
    for (int i = 0; i < 6; ++i) p[pose + i] += delta.at<double>(i);
    if (cv::norm(delta, cv::NORM_INF) < 1e-12) return;
  }
}

void JointProblem::normal_equations(const std::vector<double>& p, const JointColumns& columns, cv::Mat& jtj,
                                    cv::Mat& jtr) const {
  const int n = static_cast<int>(columns.index.size());
  jtj = cv::Mat::zeros(n, n, CV_64F);
  jtr = cv::Mat::zeros(n, 1, CV_64F);
  std::vector<double> r;
  for (int v = 0; v < layout_.views; ++v) {
    // This view's columns: the globals, then its own six; `at` maps them to the full system's rows.
    std::vector<int> at(static_cast<std::size_t>(columns.globals));
    for (int k = 0; k < columns.globals; ++k) at[k] = k;
    for (int i = 0; i < 6; ++i) at.push_back(columns.globals + 6 * v + i);
    std::vector<int> index;
    std::vector<double> step;
    for (const int k : at) {
      index.push_back(columns.index[k]);
      step.push_back(columns.step[k]);
    }
    const cv::Mat j = view_jacobian(p, v, index, step);
    view_residuals(p, v, r);
    cv::Mat block;
    cv::mulTransposed(j, block, true);
    const cv::Mat gradient = j.t() * cv::Mat(r);
    for (int row = 0; row < block.rows; ++row) {
      jtr.at<double>(at[row]) += gradient.at<double>(row);
      for (int col = 0; col < block.cols; ++col) jtj.at<double>(at[row], at[col]) += block.at<double>(row, col);
    }
  }
}

double JointProblem::adjust(std::vector<double>& p, const JointColumns& columns) const {
  const int n = static_cast<int>(columns.index.size());
  double cost = sum_of_squares(residuals(p));
  double damping = 1e-3;
  for (int iteration = 0; iteration < 50; ++iteration) {
    cv::Mat jtj;
    cv::Mat jtr;
    normal_equations(p, columns, jtj, jtr);
    bool improved = false;
    while (!improved && damping < 1e12) {
      cv::Mat damped = jtj.clone();
      for (int k = 0; k < n; ++k) damped.at<double>(k, k) *= 1.0 + damping;
      cv::Mat delta;
      if (!cv::solve(damped, -jtr, delta, cv::DECOMP_CHOLESKY)) {
        damping *= 10.0;
        continue;
      }
      std::vector<double> trial = p;
      for (int k = 0; k < n; ++k) trial[columns.index[k]] += delta.at<double>(k);
      const double trial_cost = sum_of_squares(residuals(trial));
      if (std::isfinite(trial_cost) && trial_cost < cost) {
        const double gain = (cost - trial_cost) / cost;
        p = trial;
        cost = trial_cost;
        damping = std::max(damping / 10.0, 1e-9);
        improved = true;
        if (gain < 1e-12) return cost;
      } else {
        damping *= 10.0;
      }
    }
    if (!improved) return cost;
  }
  return cost;
}

}  // namespace rfrecon::calib
