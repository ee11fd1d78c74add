// Writes and reads the reconstruction output directory; renders its previews.
#include "host/outputs/reconstruction_files.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/percentile.h"
#include "host/core/ply.h"

namespace rfrecon::outputs {

namespace fs = std::filesystem;

namespace {
void check_maps(const Reconstruction& r) {
  const cv::Size size = r.depth_mm.size();
  const auto check = [&](const cv::Mat& map, int type, const char* name) {
    if (map.type() != type || map.size() != size || map.empty()) {
      throw std::invalid_argument(std::string("write_reconstruction: ") + name + " must be " + cv::typeToString(type) +
                                  " of the depth map's size " + size_text(size));
    }
  };
  check(r.depth_mm, CV_32FC1, "depth_mm");
  check(r.points_mm, CV_32FC3, "points_mm");
  check(r.normals, CV_32FC3, "normals");
  check(r.confidence, CV_32FC1, "confidence");
}

// 255 where the depth is finite.
cv::Mat valid_mask(const cv::Mat& depth_mm) { return depth_mm == depth_mm; }

}  // namespace

cv::Mat depth_preview(const cv::Mat& depth_mm) {
  cv::Mat preview = cv::Mat::zeros(depth_mm.size(), CV_8UC3);
  const double low = finite_percentile(depth_mm, 0.01);
  if (std::isnan(low)) return preview;
  const double high = std::max(static_cast<double>(finite_percentile(depth_mm, 0.99)), low + 1e-6);
  cv::Mat scaled;
  depth_mm.convertTo(scaled, CV_8U, 255.0 / (high - low), -255.0 * low / (high - low));  // saturates outside
  cv::Mat coloured;
  cv::applyColorMap(scaled, coloured, cv::COLORMAP_TURBO);
  coloured.copyTo(preview, valid_mask(depth_mm));
  return preview;
}

cv::Mat normals_preview(const cv::Mat& normals, const cv::Mat& depth_mm) {
  cv::Mat preview = cv::Mat::zeros(normals.size(), CV_8UC3);
  for (int y = 0; y < normals.rows; ++y) {
    for (int x = 0; x < normals.cols; ++x) {
      const cv::Vec3f& n = normals.at<cv::Vec3f>(y, x);
      if (!std::isfinite(depth_mm.at<float>(y, x)) || !(std::isfinite(n[0] + n[1] + n[2]))) continue;
      const auto channel = [](float component) { return cv::saturate_cast<uchar>(127.5f * (component + 1.0f)); };
      preview.at<cv::Vec3b>(y, x) = {channel(n[2]), channel(n[1]), channel(n[0])};  // BGR
    }
  }
  return preview;
}

cv::Mat confidence_preview(const cv::Mat& confidence, const cv::Mat& depth_mm) {
  cv::Mat grey;
  confidence.convertTo(grey, CV_8U, 255.0);
  cv::Mat preview = cv::Mat::zeros(confidence.size(), CV_8UC3);
  cv::Mat grey_bgr;
  cv::cvtColor(grey, grey_bgr, cv::COLOR_GRAY2BGR);
  grey_bgr.copyTo(preview, valid_mask(depth_mm));
  return preview;
}

void write_reconstruction(const Reconstruction& reconstruction, const nlohmann::json& summary, const fs::path& out_dir,
                          bool force) {
  check_maps(reconstruction);
  std::error_code ec;
  if (fs::exists(out_dir, ec)) {
    if (!fs::is_directory(out_dir, ec)) throw InputError(out_dir.string() + ": exists and is not a directory");
    if (!force && !fs::is_empty(out_dir, ec)) {
      throw InputError("output directory " + out_dir.string() + " exists and is not empty (use --force)");
    }
  }
  StagingDirectory staging(out_dir, force);
  const fs::path dir = staging.path();
  const Reconstruction& r = reconstruction;
  write_image(dir / "depth.tiff", r.depth_mm);
  write_image(dir / "normals.tiff", r.normals);
  write_image(dir / "confidence.tiff", r.confidence);
  write_point_cloud_ply(dir / "points.ply", "rfrecon reconstruction, camera frame, mm; quality = confidence",
                        r.points_mm, r.normals, {{"quality", r.confidence}});
  write_image(dir / "depth.png", depth_preview(r.depth_mm));
  write_image(dir / "normals.png", normals_preview(r.normals, r.depth_mm));
  write_image(dir / "confidence.png", confidence_preview(r.confidence, r.depth_mm));
  write_file_atomically(dir / "summary.json", summary.dump(2) + "\n");
  staging.commit();
}

Reconstruction read_reconstruction(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string() + ": not a reconstruction directory");
  Reconstruction r;
  r.depth_mm = read_image(dir / "depth.tiff", CV_32FC1);
  r.normals = read_image(dir / "normals.tiff", CV_32FC3);
  r.confidence = read_image(dir / "confidence.tiff", CV_32FC1);
  for (const auto& [map, name] : {std::pair{&r.normals, "normals.tiff"}, std::pair{&r.confidence, "confidence.tiff"}}) {
    if (map->size() != r.depth_mm.size()) {
      throw InputError((dir / name).string() + ": " + size_text(map->size()) + ", expected " +
                       size_text(r.depth_mm.size()) + " (the size of depth.tiff)");
    }
  }
  return r;
}

}  // namespace rfrecon::outputs
