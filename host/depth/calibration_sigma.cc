// The calibration's covariance propagated to depth through a perturbed triangulation on a grid of camera positions
// and depths.
#include "host/depth/calibration_sigma.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>

#include "calib/undistort_points.h"
#include "host/core/parallel_rows.h"

namespace rfrecon::depth {

namespace {

constexpr int kGridSteps = 16;   // camera positions per axis: kGridSteps + 1
constexpr int kDepthLevels = 9;  // inverse depths
constexpr int kNewtonSteps = 2;  // Gauss-Newton steps from the nominal depth

// The grid's camera positions and inverse depths.
struct Grid {
  std::vector<cv::Point2f> camera_px;  // (kGridSteps + 1)^2, row by row
  std::array<double, kDepthLevels> inverse_depth{};
  double u_step = 1.0, v_step = 1.0, w_first = 0.0, w_step = 0.0;
};

Grid grid_of(cv::Size camera_size, double z_min, double z_max) {
  Grid grid;
  grid.u_step = std::max(1, camera_size.width - 1) / static_cast<double>(kGridSteps);
  grid.v_step = std::max(1, camera_size.height - 1) / static_cast<double>(kGridSteps);
  for (int j = 0; j <= kGridSteps; ++j) {
    for (int i = 0; i <= kGridSteps; ++i) {
      grid.camera_px.emplace_back(static_cast<float>(i * grid.u_step), static_cast<float>(j * grid.v_step));
    }
  }
  grid.w_first = 1.0 / z_max;
  grid.w_step = (1.0 / z_min - 1.0 / z_max) / (kDepthLevels - 1);
  for (int l = 0; l < kDepthLevels; ++l) grid.inverse_depth[l] = grid.w_first + l * grid.w_step;
  return grid;
}

// Normalised camera rays of the grid's positions under `rig`.
std::vector<cv::Point2f> rays(const Grid& grid, const calib::StereoRig& rig) {
  return calib::undistort_points(grid.camera_px, rig.camera_matrix, rig.dist_coeffs, cv::Mat(), cv::Mat(),
                                 cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-12));
}

// The projector pixels of the camera-frame points under `rig`.
std::vector<cv::Point2d> project(const std::vector<cv::Point3d>& points, const calib::StereoRig& rig) {
  std::vector<cv::Point2d> pixels;
  cv::Vec3d om;
  cv::Rodrigues(rig.proj_from_cam_rotation, om);
  cv::projectPoints(points, om, rig.proj_from_cam_translation_mm, rig.projector_matrix, rig.projector_dist_coeffs,
                    pixels);
  return pixels;
}

// For every node (camera position, inverse depth): the depth at which `rig` triangulates the node's camera position
// with the projector pixel `projector_px`, along the epipolar line (Gauss-Newton on the depth alone).
std::vector<double> triangulated_depths(const Grid& grid, const calib::StereoRig& rig,
                                        const std::vector<cv::Point2d>& projector_px) {
  const std::vector<cv::Point2f> ray = rays(grid, rig);
  std::vector<double> z(projector_px.size());
  for (std::size_t n = 0; n < z.size(); ++n) z[n] = 1.0 / grid.inverse_depth[n / ray.size()];
  std::vector<cv::Point3d> points(3 * z.size());
  for (int step = 0; step < kNewtonSteps; ++step) {
    for (std::size_t n = 0; n < z.size(); ++n) {
      const cv::Point2f& r = ray[n % ray.size()];
      const double h = 1e-4 * z[n];
      for (int s = 0; s < 3; ++s) {
        const double depth = z[n] + (s - 1) * h;
        points[3 * n + s] = {depth * r.x, depth * r.y, depth};
      }
    }
    const std::vector<cv::Point2d> pixels = project(points, rig);
    for (std::size_t n = 0; n < z.size(); ++n) {
      const cv::Point2d slope = (pixels[3 * n + 2] - pixels[3 * n]) / (2e-4 * z[n]);
      const cv::Point2d residual = pixels[3 * n + 1] - projector_px[n];
      const double norm = slope.dot(slope);
      z[n] = norm > 0.0 ? z[n] - slope.dot(residual) / norm : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return z;
}

}  // namespace

std::vector<std::vector<double>> principal_steps(const cv::Mat& covariance) {
  const int g = covariance.rows;
  std::vector<int> free;
  for (int i = 0; i < g; ++i) {
    if (covariance.at<double>(i, i) > 0.0) free.push_back(i);
  }
  const int f = static_cast<int>(free.size());
  cv::Mat correlation(f, f, CV_64F);
  for (int a = 0; a < f; ++a) {
    for (int b = 0; b < f; ++b) {
      correlation.at<double>(a, b) =
          covariance.at<double>(free[a], free[b]) /
          std::sqrt(covariance.at<double>(free[a], free[a]) * covariance.at<double>(free[b], free[b]));
    }
  }
  cv::Mat eigenvalues, eigenvectors;
  cv::eigen(correlation, eigenvalues, eigenvectors);
  std::vector<std::vector<double>> steps;
  for (int k = 0; k < f; ++k) {
    const double lambda = eigenvalues.at<double>(k);
    if (!(lambda > 0.0)) continue;
    std::vector<double> step(static_cast<std::size_t>(g), 0.0);
    for (int a = 0; a < f; ++a) {
      step[free[a]] = eigenvectors.at<double>(k, a) * std::sqrt(lambda * covariance.at<double>(free[a], free[a]));
    }
    steps.push_back(std::move(step));
  }
  return steps;
}

cv::Mat rig_parameter_covariance(const calib::StereoRig& rig) {
  const calib::RigUncertainty& u = rig.uncertainty;
  if (u.empty()) return {};
  if (!u.parameter_covariance.empty()) return u.parameter_covariance;
  std::vector<double> sigma;
  for (const cv::Mat* part :
       {&u.camera_intrinsics, &u.camera_dist_coeffs, &u.projector_intrinsics, &u.projector_dist_coeffs,
        &u.proj_from_cam_rotation_vector, &u.proj_from_cam_translation_mm}) {
    for (std::size_t i = 0; i < part->total(); ++i) sigma.push_back(part->at<double>(static_cast<int>(i)));
  }
  const int g = calib::rig_parameter_count(rig);
  if (static_cast<int>(sigma.size()) != g) return {};
  cv::Mat covariance = cv::Mat::zeros(g, g, CV_64F);
  for (int i = 0; i < g; ++i) covariance.at<double>(i, i) = std::isfinite(sigma[i]) ? sigma[i] * sigma[i] : 0.0;
  return covariance;
}

cv::Mat calibration_depth_sigma(const calib::StereoRig& rig, const cv::Mat& covariance, const cv::Mat& depth_mm) {
  const int g = calib::rig_parameter_count(rig);
  if (covariance.rows != g || covariance.cols != g || covariance.type() != CV_64F) {
    throw std::invalid_argument("calibration_depth_sigma: the covariance must be " + std::to_string(g) + " x " +
                                std::to_string(g) + " CV_64F");
  }
  cv::Mat sigma(depth_mm.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  double z_min = 0.0, z_max = 0.0;
  cv::minMaxIdx(depth_mm, &z_min, &z_max, nullptr, nullptr, depth_mm == depth_mm);
  if (!(z_min > 0.0)) return sigma;

  const Grid grid = grid_of(depth_mm.size(), z_min, z_max);
  const std::vector<cv::Point2f> ray = rays(grid, rig);
  std::vector<cv::Point3d> nodes;
  for (const double w : grid.inverse_depth) {
    for (const cv::Point2f& r : ray) nodes.emplace_back(r.x / w, r.y / w, 1.0 / w);
  }
  const std::vector<cv::Point2d> projector_px = project(nodes, rig);
  const int dist_size = static_cast<int>(rig.dist_coeffs.total());
  const std::vector<double> nominal = calib::rig_parameters(rig, dist_size);
  // (sigma / z)^2 at each node: what the grid interpolates (exact between nodes for a scale error, sigma ~ z).
  std::vector<double> variance(nodes.size(), 0.0);
  // Forward differences: one sigma moves a depth by 1e-4 of itself or less, where the second order is negligible.
  for (const std::vector<double>& step : principal_steps(covariance)) {
    std::vector<double> moved = nominal;
    for (int i = 0; i < g; ++i) moved[i] += step[i];
    calib::StereoRig moved_rig = rig;
    calib::set_rig_parameters(moved_rig, moved, dist_size);
    const std::vector<double> depths = triangulated_depths(grid, moved_rig, projector_px);
    for (std::size_t n = 0; n < nodes.size(); ++n) {
      const double relative_change = (depths[n] - nodes[n].z) / nodes[n].z;
      variance[n] += relative_change * relative_change;
    }
  }

  const int side = kGridSteps + 1;
  const auto node = [&](int i, int j, int l) { return variance[(static_cast<std::size_t>(l) * side + j) * side + i]; };
  for_each_row(depth_mm.rows, [&](int y) {
    const double fv = std::min(y / grid.v_step, kGridSteps - 1e-9);
    const int j = static_cast<int>(fv);
    for (int x = 0; x < depth_mm.cols; ++x) {
      const float z = depth_mm.at<float>(y, x);
      if (!(z > 0.0f)) continue;
      const double fu = std::min(x / grid.u_step, kGridSteps - 1e-9);
      const double fw =
          grid.w_step > 0.0 ? std::clamp((1.0 / z - grid.w_first) / grid.w_step, 0.0, kDepthLevels - 1 - 1e-9) : 0.0;
      const int i = static_cast<int>(fu), l = static_cast<int>(fw);
      const double tu = fu - i, tv = fv - j, tw = fw - l;
      double sum = 0.0;
      for (int corner = 0; corner < 8; ++corner) {
        const int di = corner & 1, dj = (corner >> 1) & 1, dl = corner >> 2;
        const double weight = (di ? tu : 1 - tu) * (dj ? tv : 1 - tv) * (dl ? tw : 1 - tw);
        if (weight > 0.0) sum += weight * node(i + di, j + dj, std::min(l + dl, kDepthLevels - 1));
      }
      sigma.at<float>(y, x) = static_cast<float>(z * std::sqrt(sum));
    }
  });
  return sigma;
}

}  // namespace rfrecon::depth
