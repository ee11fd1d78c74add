// Per-pose transport, dual image and corner detection for projector-camera calibration.
#include "host/calibration/pose_observation.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "calib/board_detection.h"
#include "host/capture/manifest.h"
#include "host/sched/spmv_on_devices.h"
#include "host/transport/accumulator.h"
#include "host/transport/pipeline.h"
#include "host/transport/spmv.h"

namespace rfrecon::calibration {

namespace fs = std::filesystem;

namespace {
// The projector position of camera point `at`: the nearest known correspondence within a few pixels.
std::optional<cv::Point2f> correspondence_near(const cv::Mat& correspondence, cv::Point2f at) {
  constexpr int kRadius = 3;
  const int cx = static_cast<int>(std::lround(at.x));
  const int cy = static_cast<int>(std::lround(at.y));
  std::optional<cv::Point2f> best;
  float best_distance = 0.0f;
  for (int y = std::max(0, cy - kRadius); y <= std::min(correspondence.rows - 1, cy + kRadius); ++y) {
    for (int x = std::max(0, cx - kRadius); x <= std::min(correspondence.cols - 1, cx + kRadius); ++x) {
      const auto value = correspondence.at<cv::Vec2f>(y, x);
      if (!std::isfinite(value[0]) || !std::isfinite(value[1])) continue;
      const float distance = std::hypot(static_cast<float>(x) - at.x, static_cast<float>(y) - at.y);
      if (!best || distance < best_distance) {
        best = cv::Point2f(value[0], value[1]);
        best_distance = distance;
      }
    }
  }
  return best;
}

cv::Mat correspondence_image(const transport::CompressedTransport& transport) {
  const cv::Size size = transport.setup.camera_size;
  return cv::Mat(size, CV_32FC2, const_cast<float*>(transport.correspondence.data())).clone();
}
}  // namespace

bool align_corner_order(const std::vector<cv::Point2f>& camera_corners, const cv::Mat& correspondence,
                        std::vector<cv::Point2f>& projector_corners) {
  if (camera_corners.empty() || camera_corners.size() != projector_corners.size()) return false;
  const auto first = correspondence_near(correspondence, camera_corners.front());
  const auto last = correspondence_near(correspondence, camera_corners.back());
  if (!first || !last) return false;
  const auto distance = [](cv::Point2f a, cv::Point2f b) { return std::hypot(a.x - b.x, a.y - b.y); };
  const float as_given = distance(*first, projector_corners.front()) + distance(*last, projector_corners.back());
  const float reversed = distance(*first, projector_corners.back()) + distance(*last, projector_corners.front());
  if (reversed < as_given) std::reverse(projector_corners.begin(), projector_corners.end());
  return true;
}

PoseObservation observe_pose(const fs::path& pose_dir, const PoseSource& source, const calib::BoardSpec& board,
                             std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  PoseObservation pose;
  pose.name = pose_dir.filename().empty() ? pose_dir.parent_path().filename().string() : pose_dir.filename().string();
  const auto manifest = transport::open_capture(pose_dir, source.layout, source.projector_size);
  transport::TransportSetup setup;
  setup.thresholds = source.thresholds;
  setup.entries_per_pixel = 8;
  const auto run = transport::compute_transport_on_devices(pose_dir, manifest, setup, devices, programs,
                                                           transport::KernelEntry::kNdRange);
  pose.schedule = run.schedule;
  const auto& transport = run.transport;

  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    if (manifest.frames[i].pattern.kind == capture::PatternKind::kWhite) {
      auto with_size = manifest;
      with_size.camera_size = transport.setup.camera_size;
      pose.camera_image = capture::load_frame(pose_dir, with_size, i);
    }
  }
  const std::vector<float> ones(transport.camera_pixels(), 1.0f);
  const auto transposed = transport::transpose(transport);
  auto product = sched::dual_on_devices(devices, programs, transport::KernelEntry::kNdRange, transposed, ones);
  pose.schedule.push_back(product.report);
  const std::vector<float>& dual = product.image;
  const cv::Mat dual_image(transport.setup.projector_size, CV_32F, const_cast<float*>(dual.data()));
  cv::Mat reached(transport.setup.projector_size, CV_8U);
  for (int q = 0; q < static_cast<int>(reached.total()); ++q) {
    reached.data[q] = transposed.row_start[q + 1] > transposed.row_start[q] ? 255 : 0;
  }
  pose.dual_image = calib::fill_dual_image_holes(dual_image, reached);

  pose.camera_corners = calib::find_board_corners(pose.camera_image, board);
  if (pose.camera_corners.empty()) {
    pose.problem = "board not found in the camera image (white frame)";
    return pose;
  }
  pose.projector_corners = calib::find_board_corners(pose.dual_image, board);
  if (pose.projector_corners.empty()) {
    pose.problem = "board not found in the dual image T^T 1 (is the board lit by the projector?)";
    return pose;
  }
  if (!align_corner_order(pose.camera_corners, correspondence_image(transport), pose.projector_corners)) {
    pose.problem = "no projector correspondence near the board's corners: cannot match camera and projector corners";
  }
  return pose;
}

}  // namespace rfrecon::calibration
