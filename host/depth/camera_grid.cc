// Rectified depth to camera-grid depth, points and normals, rows on every core.
#include "host/depth/camera_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "host/core/parallel_rows.h"

namespace rfrecon::depth {

namespace {
constexpr float kNoValue = std::numeric_limits<float>::quiet_NaN();

bool finite_point(const cv::Vec3f& p) { return std::isfinite(p[0]); }

// The difference of the neighbours of (x, y) along one axis: central where both exist, else one-sided.
bool difference(const cv::Mat& points, int x, int y, int dx, int dy, cv::Vec3f& out) {
  const auto at = [&](int xx, int yy, cv::Vec3f& p) {
    if (xx < 0 || yy < 0 || xx >= points.cols || yy >= points.rows) return false;
    p = points.at<cv::Vec3f>(yy, xx);
    return finite_point(p);
  };
  cv::Vec3f before, after;
  const cv::Vec3f centre = points.at<cv::Vec3f>(y, x);
  const bool has_before = at(x - dx, y - dy, before), has_after = at(x + dx, y + dy, after);
  if (has_before && has_after) {
    out = after - before;
  } else if (has_after) {
    out = after - centre;
  } else if (has_before) {
    out = centre - before;
  } else {
    return false;
  }
  return true;
}
}  // namespace

cv::Mat sample_rectified_depth(const std::vector<float>& z_rect, const RectifiedRows& rows, const cv::Mat& rect_cam,
                               float jump_relative) {
  // Every pixel written by its row's loop, NaN where there is no depth: no serial fill of the image first.
  cv::Mat z_grid(rect_cam.size(), CV_32F);
  const auto z_at = [&](int u, int v) { return z_rect[static_cast<std::size_t>(v) * rows.width + u]; };
  const auto depth_at = [&](const cv::Vec2f& position) {
    const float u = position[0], v = position[1];
    if (!(u >= 0.0f && v >= 0.0f && u <= static_cast<float>(rows.width - 1) &&
          v <= static_cast<float>(rows.height - 1))) {
      return kNoValue;
    }
    const int u0 = std::min(static_cast<int>(u), rows.width - 2), v0 = std::min(static_cast<int>(v), rows.height - 2);
    const float z[4] = {z_at(u0, v0), z_at(u0 + 1, v0), z_at(u0, v0 + 1), z_at(u0 + 1, v0 + 1)};
    const auto [low, high] = std::minmax_element(z, z + 4);
    if (!(*low > 0.0f) || !(*high <= *low * (1.0f + jump_relative))) return kNoValue;  // also rejects NaN
    const float tu = u - static_cast<float>(u0), tv = v - static_cast<float>(v0);
    const float top = (1.0f - tu) / z[0] + tu / z[1], bottom = (1.0f - tu) / z[2] + tu / z[3];
    return 1.0f / ((1.0f - tv) * top + tv * bottom);
  };
  for_each_row(rect_cam.rows, [&](int y) {
    for (int x = 0; x < rect_cam.cols; ++x) z_grid.at<float>(y, x) = depth_at(rect_cam.at<cv::Vec2f>(y, x));
  });
  return z_grid;
}

outputs::Reconstruction camera_frame_maps(const cv::Mat& z_rect_mm, const cv::Mat& rect_cam, const RfRectifiedRig& rig,
                                          const cv::Mat& R1) {
  const cv::Size size = z_rect_mm.size();
  outputs::Reconstruction maps;
  // Depth, points and normals: every pixel written by its row's loop (NaN where none), no serial fill first.
  maps.depth_mm = cv::Mat(size, CV_32F);
  maps.points_mm = cv::Mat(size, CV_32FC3);
  maps.normals = cv::Mat(size, CV_32FC3);
  maps.confidence = cv::Mat(size, CV_32F, cv::Scalar(0.0f));
  const cv::Vec3f no_point(kNoValue, kNoValue, kNoValue);
  cv::Matx33d cam_from_rect;
  cv::Mat(R1.t()).copyTo(cam_from_rect);
  for_each_row(size.height, [&](int y) {
    for (int x = 0; x < size.width; ++x) {
      const float z = z_rect_mm.at<float>(y, x);
      maps.points_mm.at<cv::Vec3f>(y, x) = no_point;
      maps.depth_mm.at<float>(y, x) = kNoValue;
      if (!(z > 0.0f)) continue;
      const cv::Vec2f& position = rect_cam.at<cv::Vec2f>(y, x);
      const cv::Vec3d X_rect(z * (position[0] - rig.cx_cam) / rig.f, z * (position[1] - rig.cy) / rig.f, z);
      const cv::Vec3d X_cam = cam_from_rect * X_rect;
      maps.points_mm.at<cv::Vec3f>(y, x) = cv::Vec3f(X_cam);
      maps.depth_mm.at<float>(y, x) = static_cast<float>(X_cam[2]);
    }
  });
  for_each_row(size.height, [&](int y) {
    for (int x = 0; x < size.width; ++x) {
      const cv::Vec3f point = maps.points_mm.at<cv::Vec3f>(y, x);
      maps.normals.at<cv::Vec3f>(y, x) = no_point;
      cv::Vec3f along_x, along_y;
      if (!finite_point(point) || !difference(maps.points_mm, x, y, 1, 0, along_x) ||
          !difference(maps.points_mm, x, y, 0, 1, along_y)) {
        continue;
      }
      cv::Vec3f normal = along_x.cross(along_y);
      const float length = static_cast<float>(cv::norm(normal));
      if (!(length > 0.0f)) continue;
      normal /= length;
      if (normal.dot(point) > 0.0f) normal = -normal;  // face the camera at the origin
      maps.normals.at<cv::Vec3f>(y, x) = normal;
    }
  });
  return maps;
}

}  // namespace rfrecon::depth
