// The dot centroid's covariance from the camera noise, through the rectification to depth.
#include "host/depth/observation_sigma.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "host/core/parallel_rows.h"
#include "host/transport/dot_rows.h"

namespace rfrecon::depth {

namespace {
constexpr float kNoSigma = std::numeric_limits<float>::quiet_NaN();

// d(rectified projector column) / d(projector x, y) at the projector pixel nearest `point`, by central differences of
// the rectification's grid of projector pixel centres (with its pixel of margin).
cv::Vec2d column_gradient(const cv::Mat& proj_grid, double x, double y) {
  const int ix = std::clamp(static_cast<int>(std::lround(x)), 0, proj_grid.cols - 3) + 1;
  const int iy = std::clamp(static_cast<int>(std::lround(y)), 0, proj_grid.rows - 3) + 1;
  const auto u = [&](int gx, int gy) { return static_cast<double>(proj_grid.at<cv::Vec2f>(gy, gx)[0]); };
  return {0.5 * (u(ix + 1, iy) - u(ix - 1, iy)), 0.5 * (u(ix, iy + 1) - u(ix, iy - 1))};
}
}  // namespace

cv::Mat rectified_column_sigma_px(const transport::CompressedTransport& transport, const Rectification& rectification) {
  const capture::CameraNoise& noise = transport.camera_noise;
  if (!noise.known() || !transport::correspondences_are_centroids(transport.setup)) return {};
  const cv::Size size = transport.setup.camera_size;
  const int width = transport.setup.projector_size.width;
  const int k_max = transport.k();
  cv::Mat sigma(size, CV_32F);
  for_each_row(size.height, [&](int y) {
    for (int x = 0; x < size.width; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * size.width + x;
      sigma.at<float>(y, x) = kNoSigma;
      const double cx = transport.correspondence[2 * c], cy = transport.correspondence[2 * c + 1];
      if (std::isnan(cx)) continue;
      double sum = 0.0, xx = 0.0, xy = 0.0, yy = 0.0, dx_sum = 0.0, dy_sum = 0.0;
      for (int k = 0; k < k_max; ++k) {
        const std::size_t entry = c * static_cast<std::size_t>(k_max) + k;
        const int q = transport.indices[entry];
        if (q < 0) continue;
        const double w = transport.weights[entry];
        const int qx = q % width, qy = q / width;
        const double dx = qx - cx, dy = qy - cy;
        const double variance = noise.variance(w);
        sum += w;
        xx += dx * dx * variance;
        xy += dx * dy * variance;
        yy += dy * dy * variance;
        dx_sum += dx;
        dy_sum += dy;
      }
      if (!(sum > 0.0)) continue;
      const double black = noise.read_variance;  // the black frame's noise, common to every entry
      xx = (xx + dx_sum * dx_sum * black) / (sum * sum);
      xy = (xy + dx_sum * dy_sum * black) / (sum * sum);
      yy = (yy + dy_sum * dy_sum * black) / (sum * sum);
      const cv::Vec2d j = column_gradient(rectification.proj_grid, cx, cy);
      sigma.at<float>(y, x) =
          static_cast<float>(std::sqrt(j[0] * j[0] * xx + 2.0 * j[0] * j[1] * xy + j[1] * j[1] * yy));
    }
  });
  return sigma;
}

cv::Mat triangulated_depth_sigma(const cv::Mat& z_rect_mm, const cv::Mat& column_sigma_px, const RfRectifiedRig& rig) {
  cv::Mat sigma(z_rect_mm.size(), CV_32F);
  const float scale = 1.0f / (rig.f * std::abs(rig.b));
  for_each_row(z_rect_mm.rows, [&](int y) {
    for (int x = 0; x < z_rect_mm.cols; ++x) {
      const float z = z_rect_mm.at<float>(y, x);
      sigma.at<float>(y, x) = z * z * scale * column_sigma_px.at<float>(y, x);
    }
  });
  return sigma;
}

}  // namespace rfrecon::depth
