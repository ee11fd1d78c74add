// Synthetic plane scene and capture rendering for the transport tests.
#include "tests/transport/synthetic_capture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <opencv2/imgcodecs.hpp>

namespace rfrecon::transport::testing {

namespace fs = std::filesystem;

namespace {
// Integral of a unit Gaussian of `sigma` centred at `mean` over [lo, hi].
double gaussian_mass(double mean, double sigma, double lo, double hi) {
  const double scale = 1.0 / (sigma * std::sqrt(2.0));
  return 0.5 * (std::erf((hi - mean) * scale) - std::erf((lo - mean) * scale));
}
}  // namespace

PlaneScene make_plane_scene(const SceneOptions& options) {
  PlaneScene scene;
  scene.camera_size = options.camera_size;
  scene.projector_size = options.projector_size;
  scene.ambient = options.ambient;
  const cv::Size cam = options.camera_size;
  const cv::Size proj = options.projector_size;
  scene.albedo = cv::Mat(proj, CV_32F, cv::Scalar(0.8));
  if (options.checker_size > 0) {
    for (int y = 0; y < proj.height; ++y) {
      for (int x = 0; x < proj.width; ++x) {
        const bool white = ((x / options.checker_size) + (y / options.checker_size)) % 2 == 0;
        scene.albedo.at<float>(y, x) = white ? 0.9f : 0.3f;
      }
    }
  }
  // Map the camera onto the projector with a slight rotation and a scale below one projector pixel per camera pixel.
  const double a = 0.96 * (proj.width - 3) / cam.width, b = 0.04 * (proj.width - 3) / cam.height;
  const double d = -0.03 * (proj.height - 3) / cam.width, e = 0.97 * (proj.height - 3) / cam.height;
  const double c0 = 0.6, f0 = 1.7;
  scene.correspondence = cv::Mat(cam, CV_32FC2, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()));
  std::vector<Eigen::Triplet<float, int>> entries;
  for (int v = 0; v < cam.height; ++v) {
    for (int u = options.shadow_columns; u < cam.width; ++u) {
      const double x = a * u + b * v + c0;
      const double y = d * u + e * v + f0;
      scene.correspondence.at<cv::Vec2f>(v, u) = {static_cast<float>(x), static_cast<float>(y)};
      const int x0 = static_cast<int>(std::lround(x));
      const int y0 = static_cast<int>(std::lround(y));
      const float albedo =
          scene.albedo.at<float>(std::clamp(y0, 0, proj.height - 1), std::clamp(x0, 0, proj.width - 1));
      for (int qy = y0 - 2; qy <= y0 + 2; ++qy) {
        for (int qx = x0 - 2; qx <= x0 + 2; ++qx) {
          if (qx < 0 || qy < 0 || qx >= proj.width || qy >= proj.height) continue;
          const double mass = gaussian_mass(x, options.blur_sigma, qx - 0.5, qx + 0.5) *
                              gaussian_mass(y, options.blur_sigma, qy - 0.5, qy + 0.5);
          if (mass > 1e-6)
            entries.emplace_back(v * cam.width + u, qy * proj.width + qx, static_cast<float>(albedo * mass));
        }
      }
    }
  }
  scene.transport.resize(cam.area(), proj.area());
  scene.transport.setFromTriplets(entries.begin(), entries.end());
  return scene;
}

std::vector<cv::Mat> render_frames(const PlaneScene& scene, const std::vector<capture::Pattern>& sequence,
                                   int dot_spacing, double noise_dn, unsigned seed) {
  return render_frames(scene, sequence, capture::ProtocolOptions{scene.projector_size, dot_spacing}, noise_dn, seed);
}

std::vector<cv::Mat> render_frames(const PlaneScene& scene, const std::vector<capture::Pattern>& sequence,
                                   const capture::ProtocolOptions& options, double noise_dn, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_dn);
  std::vector<cv::Mat> frames;
  for (const auto& pattern : sequence) {
    const cv::Mat projected = capture::render_pattern(pattern, options);
    Eigen::VectorXf light(scene.projector_size.area());
    for (int i = 0; i < light.size(); ++i) light[i] = projected.ptr<unsigned char>()[i] / 255.0f;
    const Eigen::VectorXf image = scene.transport * light;
    cv::Mat frame(scene.camera_size, CV_8U);
    for (int i = 0; i < image.size(); ++i) {
      const double reading = 255.0 * (image[i] + scene.ambient) + noise(random);
      frame.ptr<unsigned char>()[i] = cv::saturate_cast<unsigned char>(reading);
    }
    frames.push_back(frame);
  }
  return frames;
}

capture::CaptureManifest write_capture(const fs::path& dir, const PlaneScene& scene,
                                       const std::vector<capture::Pattern>& sequence, int dot_spacing,
                                       const std::vector<cv::Mat>& frames) {
  fs::create_directories(dir);
  capture::CaptureManifest manifest;
  manifest.projector_size = scene.projector_size;
  manifest.camera_size = scene.camera_size;
  manifest.dot_spacing = dot_spacing;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const std::string file = "frame_" + std::to_string(1000 + i) + ".png";
    cv::imwrite((dir / file).string(), frames[i]);
    manifest.frames.push_back({sequence[i], file});
  }
  capture::write_manifest(manifest, dir);
  return manifest;
}

}  // namespace rfrecon::transport::testing
