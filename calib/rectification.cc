// The rectifying rotations, the shared focal length and the extents of both rectified images.
#include "calib/rectification.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "host/core/errors.h"

namespace rfrecon::calib {

namespace {

// Below this the rig cannot triangulate (rig.yaml lengths are millimetres).
constexpr double kMinBaselineMm = 1e-2;
// sin of the smallest angle between the baseline and the mean viewing direction.
constexpr double kMinBaselineAngleSin = 0.1;

// Bounding box of a device's image border in a rectified frame at focal length f and principal point 0; `key` names
// the device's distortion coefficients, which fail when they send a border pixel to no finite point.
cv::Rect2d rectified_extent(const cv::Mat& K, const cv::Mat& dist, const cv::Matx33d& rect_from_device, cv::Size size,
                            double f, const char* key) {
  std::vector<cv::Point2d> border, rectified;
  for (int x = 0; x < size.width; ++x) {
    border.emplace_back(x, 0.0);
    border.emplace_back(x, size.height - 1.0);
  }
  for (int y = 0; y < size.height; ++y) {
    border.emplace_back(0.0, y);
    border.emplace_back(size.width - 1.0, y);
  }
  const cv::Matx33d unit_projection(f, 0, 0, 0, f, 0, 0, 0, 1);
  cv::undistortPoints(border, rectified, K, dist, cv::Mat(rect_from_device), unit_projection, undistort_criteria());
  double x0 = rectified[0].x, x1 = x0, y0 = rectified[0].y, y1 = y0;
  for (const auto& p : rectified) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      throw InputError(std::string("key '") + key +
                       "': the distortion model sends the image border to no finite point");
    }
    x0 = std::min(x0, p.x);
    x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y);
    y1 = std::max(y1, p.y);
  }
  return {x0, y0, x1 - x0, y1 - y0};
}

double largest_focal(const cv::Mat& K) { return std::max(K.at<double>(0, 0), K.at<double>(1, 1)); }

}  // namespace

cv::TermCriteria undistort_criteria() { return {cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-12}; }

RowRectification rectify_rig(const StereoRig& rig) {
  const auto fail = [](const std::string& key, const std::string& what) {
    throw InputError("key '" + key + "': " + what);
  };
  for (const auto& [K, key] :
       {std::pair{rig.camera_matrix, "camera_matrix"}, {rig.projector_matrix, "projector_matrix"}}) {
    if (!(K.at<double>(0, 0) > 0.0 && K.at<double>(1, 1) > 0.0)) fail(key, "focal lengths must be positive");
  }
  const cv::Matx33d proj_from_cam(rig.proj_from_cam_rotation);
  const cv::Vec3d proj_from_cam_t_mm(rig.proj_from_cam_translation_mm);
  const cv::Vec3d projector_centre = -(proj_from_cam.t() * proj_from_cam_t_mm);  // camera frame
  const double baseline = cv::norm(projector_centre);
  if (!(baseline >= kMinBaselineMm)) {
    fail("T", "the baseline is " + std::to_string(baseline) +
                  " mm, too short to triangulate (camera and projector "
                  "centres coincide)");
  }
  const cv::Vec3d e1 = projector_centre / baseline;
  const cv::Vec3d mean_axis = cv::normalize(cv::Vec3d(0, 0, 1) + proj_from_cam.t() * cv::Vec3d(0, 0, 1));
  if (cv::norm(mean_axis) == 0.0 || (proj_from_cam.t() * cv::Vec3d(0, 0, 1))[2] <= 0.0) {
    fail("R", "the projector faces away from the camera's viewing direction");
  }
  const cv::Vec3d across = mean_axis.cross(e1);
  if (!(cv::norm(across) >= kMinBaselineAngleSin)) {
    fail("T", "the baseline points along the viewing direction: epipolar lines cannot be made rows");
  }
  const cv::Vec3d e2 = cv::normalize(across), e3 = e1.cross(e2);
  RowRectification out;
  out.rect_from_cam = cv::Matx33d(e1[0], e1[1], e1[2], e2[0], e2[1], e2[2], e3[0], e3[1], e3[2]);
  out.rect_from_proj = out.rect_from_cam * proj_from_cam.t();
  out.baseline_mm = baseline;
  out.f_px = std::max(largest_focal(rig.camera_matrix), largest_focal(rig.projector_matrix));

  const cv::Rect2d camera_box =
      rectified_extent(rig.camera_matrix, rig.dist_coeffs, out.rect_from_cam, rig.camera_size, out.f_px, "dist_coeffs");
  const cv::Rect2d projector_box = rectified_extent(rig.projector_matrix, rig.projector_dist_coeffs, out.rect_from_proj,
                                                    rig.projector_size, out.f_px, "projector_dist_coeffs");
  if (!(std::max({camera_box.width, camera_box.height, projector_box.width}) < kMaxRectifiedSide)) {
    fail("R", "the rectified images would be larger than " + std::to_string(kMaxRectifiedSide) +
                  " pixels (devices at a grazing angle to each other?)");
  }
  // 2^24: offsets still exact to a pixel's 2^-29 in double, so the sizes below cannot cancel to nonsense.
  if (!(std::max({std::abs(camera_box.x), std::abs(camera_box.y), std::abs(projector_box.x)}) < double{1 << 24})) {
    throw InputError(
        "the rectified images would lie more than 2^24 pixels from their principal points (a principal "
        "point far outside its image?)");
  }
  // Whole pixels of margin so that the border pixels' centres fall inside the images.
  out.cx_cam_px = -std::floor(camera_box.x);
  out.cx_proj_px = -std::floor(projector_box.x);
  out.cy_px = -std::floor(camera_box.y);
  out.camera_size = {static_cast<int>(std::ceil(camera_box.br().x) + out.cx_cam_px) + 1,
                     static_cast<int>(std::ceil(camera_box.br().y) + out.cy_px) + 1};
  out.projector_size = {static_cast<int>(std::ceil(projector_box.br().x) + out.cx_proj_px) + 1, out.camera_size.height};
  const double f = out.f_px, b = out.baseline_mm;
  out.rect_cam_image_from_rect = (cv::Mat_<double>(3, 4) << f, 0, out.cx_cam_px, 0, 0, f, out.cy_px, 0, 0, 0, 1, 0);
  out.rect_proj_image_from_rect =
      (cv::Mat_<double>(3, 4) << f, 0, out.cx_proj_px, -f * b, 0, f, out.cy_px, 0, 0, 0, 1, 0);
  out.rect_from_disparity = (cv::Mat_<double>(4, 4) << 1, 0, 0, -out.cx_cam_px, 0, 1, 0, -out.cy_px, 0, 0, 0, f, 0, 0,
                             1.0 / b, -(out.cx_cam_px - out.cx_proj_px) / b);
  return out;
}

}  // namespace rfrecon::calib
