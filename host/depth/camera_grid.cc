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

// The ends of a point's tangent along one axis, its neighbours before and after it (null where outside the image):
// both where finite (a central difference), else the finite one and the point itself. False where neither is.
// Pointers into the points, so that the difference reads them there, not through copies on the stack.
bool tangent_ends(const cv::Vec3f*& before, const cv::Vec3f& centre, const cv::Vec3f*& after) {
  if (before != nullptr && !finite_point(*before)) before = nullptr;
  if (after != nullptr && !finite_point(*after)) after = nullptr;
  if (before == nullptr && after == nullptr) return false;
  if (before == nullptr) before = &centre;
  if (after == nullptr) after = &centre;
  return true;
}
}  // namespace

cv::Mat sample_rectified_depth(const std::vector<float>& z_rect, const RectifiedRows& rows, const cv::Mat& rect_cam,
                               float jump_relative) {
  // Every pixel written by the loop (tiles: the rectification turns the image), NaN where there is no depth: no serial
  // fill of the image first.
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
  for_each_pixel_in_tiles(rect_cam.rows, rect_cam.cols,
                          [&](int y, int x) { z_grid.at<float>(y, x) = depth_at(rect_cam.at<cv::Vec2f>(y, x)); });
  return z_grid;
}

outputs::Reconstruction camera_frame_maps(const cv::Mat& z_rect_mm, const cv::Mat& rect_cam, const RfRectifiedRig& rig,
                                          const cv::Mat& rect_from_cam) {
  const cv::Size size = z_rect_mm.size();
  outputs::Reconstruction maps;
  // Depth, points and normals: every pixel written by its row's loop (NaN where none), no serial fill first.
  maps.depth_mm = cv::Mat(size, CV_32F);
  maps.points_mm = cv::Mat(size, CV_32FC3);
  maps.normals = cv::Mat(size, CV_32FC3);
  maps.confidence = filled_on_every_core(size, CV_32F, cv::Scalar(0.0f));
  const cv::Vec3f no_point(kNoValue, kNoValue, kNoValue);
  cv::Matx33d cam_from_rect;
  cv::Mat(rect_from_cam.t()).copyTo(cam_from_rect);
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
    const cv::Vec3f* row = maps.points_mm.ptr<cv::Vec3f>(y);
    const cv::Vec3f* above = y > 0 ? maps.points_mm.ptr<cv::Vec3f>(y - 1) : nullptr;
    const cv::Vec3f* below = y + 1 < size.height ? maps.points_mm.ptr<cv::Vec3f>(y + 1) : nullptr;
    cv::Vec3f* normals = maps.normals.ptr<cv::Vec3f>(y);
    for (int x = 0; x < size.width; ++x) {
      const cv::Vec3f& point = row[x];
      normals[x] = no_point;
      if (!finite_point(point)) continue;
      const cv::Vec3f *left = x > 0 ? row + x - 1 : nullptr, *right = x + 1 < size.width ? row + x + 1 : nullptr;
      const cv::Vec3f *up = above != nullptr ? above + x : nullptr, *down = below != nullptr ? below + x : nullptr;
      if (!tangent_ends(left, point, right) || !tangent_ends(up, point, down)) continue;
      cv::Vec3f normal = (*right - *left).cross(*down - *up);
      const float length = static_cast<float>(cv::norm(normal));
      if (!(length > 0.0f)) continue;
      normal /= length;
      if (normal.dot(point) > 0.0f) normal = -normal;  // face the camera at the origin
      normals[x] = normal;
    }
  });
  return maps;
}

}  // namespace rfrecon::depth
