// Writes and reads the reconstruction output directory; renders its previews and the point cloud's colours.
#include "host/outputs/reconstruction_files.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/percentile.h"
#include "host/core/ply.h"
#include "host/outputs/legend.h"

namespace rfrecon::outputs {

namespace fs = std::filesystem;

namespace {
// The depth's standard deviations and their files (the PLY's property is the file's stem).
template <typename R>  // Reconstruction or const Reconstruction
std::array<std::pair<decltype(&std::declval<R&>().depth_sigma_mm), const char*>, 3> sigma_maps(R& r) {
  return {{{&r.depth_sigma_mm, "depth_sigma.tiff"},
           {&r.depth_sigma_calibration_mm, "depth_sigma_calibration.tiff"},
           {&r.depth_sigma_observation_mm, "depth_sigma_observation.tiff"}}};
}

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
  if (!r.white.empty()) check(r.white, CV_32FC1, "white");
  for (const auto& [map, name] : sigma_maps(r)) {
    if (!map->empty()) check(*map, CV_32FC1, name);
  }
}

// OpenCV's TIFF codec stores a 3-channel image's channels in reverse (BGR in memory, RGB in the file): these reverse
// them around it, so that channel 0 in memory is the file's first sample (x), as any other TIFF reader sees it.
void write_xyz_tiff(const fs::path& file, const cv::Mat& xyz) {
  cv::Mat reversed;
  cv::cvtColor(xyz, reversed, cv::COLOR_RGB2BGR);
  write_image(file, reversed);
}

cv::Mat read_xyz_tiff(const fs::path& file) {
  cv::Mat xyz;
  cv::cvtColor(read_image(file, CV_32FC3), xyz, cv::COLOR_BGR2RGB);
  return xyz;
}

// The normals' legend key: a sphere facing the camera, coloured as normals_preview colours its normals.
cv::Mat normals_key() {
  constexpr int kSide = 101;
  constexpr float kRadius = 50.0f;
  cv::Mat normals(kSide, kSide, CV_32FC3, cv::Scalar::all(NAN));
  cv::Mat depth(kSide, kSide, CV_32F, cv::Scalar(NAN));
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const float nx = (x - kRadius) / kRadius, ny = (y - kRadius) / kRadius, r2 = nx * nx + ny * ny;
      if (r2 > 1.0f) continue;
      normals.at<cv::Vec3f>(y, x) = {nx, ny, -std::sqrt(1.0f - r2)};
      depth.at<float>(y, x) = 1.0f;
    }
  }
  return normals_preview(normals, depth);
}

// 255 where the depth is finite.
cv::Mat valid_mask(const cv::Mat& depth_mm) { return depth_mm == depth_mm; }

// `map` through COLORMAP_TURBO from `low` (blue) to `high` (red), saturating outside; black where it is not finite.
cv::Mat turbo_preview(const cv::Mat& map, double low, double high) {
  cv::Mat preview = cv::Mat::zeros(map.size(), CV_8UC3), scaled, coloured;
  map.convertTo(scaled, CV_8U, 255.0 / (high - low), -255.0 * low / (high - low));
  cv::applyColorMap(scaled, coloured, cv::COLORMAP_TURBO);
  coloured.copyTo(preview, valid_mask(map));
  return preview;
}

void write_previews(const fs::path& dir, const Reconstruction& r) {
  const auto [low, high] = depth_preview_range(r.depth_mm);
  Legend depth{"depth z (mm)", colour_bar_key(cv::COLORMAP_TURBO), {}, {"1st to 99th percentile", "black: no depth"}};
  if (!std::isnan(low)) depth.ticks = bar_ticks(low, high, high - low < 10.0 ? 2 : 1);
  write_image(dir / "depth.png", with_legend(depth_preview(r.depth_mm), depth));
  const Legend normals{
      "normal (unit vector)", normals_key(), {}, {"RGB = 255 (n + 1) / 2", "x right, y down", "black: no depth"}};
  write_image(dir / "normals.png", with_legend(normals_preview(r.normals, r.depth_mm), normals));
  const Legend confidence{"confidence (0 to 1)", grey_bar_key(), bar_ticks(0.0, 1.0, 1), {"black: no depth"}};
  write_image(dir / "confidence.png", with_legend(confidence_preview(r.confidence, r.depth_mm), confidence));
  const double sigma_high = r.depth_sigma_mm.empty() ? 0.0 : finite_percentile(r.depth_sigma_mm, 0.99);
  if (sigma_high > 0.0) {  // also rejects NaN: no sigma known anywhere
    const Legend sigma{"depth sigma (mm)",
                       colour_bar_key(cv::COLORMAP_TURBO),
                       bar_ticks(0.0, sigma_high, sigma_high < 0.1 ? 4 : 2, ">= "),
                       {"0 to 99th percentile", "black: no depth or", "sigma unknown"}};
    write_image(dir / "depth_sigma.png", with_legend(turbo_preview(r.depth_sigma_mm, 0.0, sigma_high), sigma));
  }
}

}  // namespace

std::pair<double, double> depth_preview_range(const cv::Mat& depth_mm) {
  const double low = finite_percentile(depth_mm, 0.01);
  if (std::isnan(low)) return {low, low};
  return {low, std::max(static_cast<double>(finite_percentile(depth_mm, 0.99)), low + 1e-6)};
}

cv::Mat depth_preview(const cv::Mat& depth_mm) {
  const auto [low, high] = depth_preview_range(depth_mm);
  if (std::isnan(low)) return cv::Mat::zeros(depth_mm.size(), CV_8UC3);
  return turbo_preview(depth_mm, low, high);
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

cv::Mat white_colours_rgb(const cv::Mat& white) {
  cv::Mat colours(white.size(), CV_8UC3);
  for (int y = 0; y < white.rows; ++y) {
    for (int x = 0; x < white.cols; ++x) {
      const float linear = std::clamp(white.at<float>(y, x), 0.0f, 1.0f);
      const float encoded =
          linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;  // sRGB
      const uchar level = cv::saturate_cast<uchar>(255.0f * encoded);
      colours.at<cv::Vec3b>(y, x) = {level, level, level};
    }
  }
  return colours;
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
  write_xyz_tiff(dir / "points.tiff", r.points_mm);
  write_xyz_tiff(dir / "normals.tiff", r.normals);
  write_image(dir / "confidence.tiff", r.confidence);
  std::vector<PlyScalarMap> scalars = {{"quality", r.confidence}};
  for (const auto& [map, name] : sigma_maps(r)) {
    if (map->empty()) continue;
    write_image(dir / name, *map);
    scalars.push_back({fs::path(name).stem().string(), *map});
  }
  write_point_cloud_ply(dir / "points.ply",
                        std::string("rfrecon reconstruction, camera frame, mm; quality = confidence") +
                            (r.white.empty() ? "" : "; colour = white frame, sRGB") +
                            (scalars.size() > 1 ? "; depth_sigma* = one standard deviation of z, mm" : ""),
                        r.points_mm, r.normals, scalars, r.white.empty() ? cv::Mat() : white_colours_rgb(r.white));
  write_previews(dir, r);
  write_file_atomically(dir / "summary.json", summary.dump(2) + "\n");
  staging.commit();
}

Reconstruction read_reconstruction(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string() + ": not a reconstruction directory");
  Reconstruction r;
  r.depth_mm = read_image(dir / "depth.tiff", CV_32FC1);
  r.points_mm = read_xyz_tiff(dir / "points.tiff");
  r.normals = read_xyz_tiff(dir / "normals.tiff");
  r.confidence = read_image(dir / "confidence.tiff", CV_32FC1);
  for (const auto& [map, name] : {std::pair{&r.points_mm, "points.tiff"}, std::pair{&r.normals, "normals.tiff"},
                                  std::pair{&r.confidence, "confidence.tiff"}}) {
    if (map->size() != r.depth_mm.size()) {
      throw InputError((dir / name).string() + ": " + size_text(map->size()) + ", expected " +
                       size_text(r.depth_mm.size()) + " (the size of depth.tiff)");
    }
  }
  for (const auto& [map, name] : sigma_maps(r)) {
    if (!fs::exists(dir / name, ec)) continue;  // a reconstruction of an rfrecon before them has none
    *map = read_image(dir / name, CV_32FC1);
    if (map->size() != r.depth_mm.size()) {
      throw InputError((dir / name).string() + ": " + size_text(map->size()) + ", expected " +
                       size_text(r.depth_mm.size()) + " (the size of depth.tiff)");
    }
  }
  return r;
}

}  // namespace rfrecon::outputs
