// Pattern frames from T with the camera noise model, and the capture directory they form.
#include "sim/frames.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <random>
#include <thread>

#include "host/capture/pattern_files.h"
#include "host/core/image_file.h"

namespace rfrecon::sim {

namespace fs = std::filesystem;

cv::Mat transport_image(const TransportMatrix& T, const cv::Mat& pattern, cv::Size camera_size) {
  CV_Assert(pattern.type() == CV_8UC1 && pattern.isContinuous() &&
            pattern.total() == static_cast<std::size_t>(T.cols()));
  CV_Assert(camera_size.area() == T.rows());
  Eigen::VectorXf light(T.cols());
  for (Eigen::Index i = 0; i < light.size(); ++i) light[i] = pattern.data[i] / 255.0f;
  cv::Mat image(camera_size, CV_32F);
  Eigen::Map<Eigen::VectorXf>(image.ptr<float>(), T.rows()) = T * light;
  return image;
}

cv::Mat camera_reading(const cv::Mat& linear, const CaptureSettings& s, std::uint64_t seed, std::size_t frame_index) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + frame_index * 0xBF58476D1CE4E5B9ULL + 1);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double full_scale = std::ldexp(1.0, s.bit_depth) - 1.0;
  const double span = full_scale - s.black_level;  // digital numbers between black and saturation
  cv::Mat raw(linear.size(), s.bit_depth == 8 ? CV_8U : CV_16U);
  for (int y = 0; y < linear.rows; ++y) {
    for (int x = 0; x < linear.cols; ++x) {
      double signal = std::max(0.0, static_cast<double>(linear.at<float>(y, x)) + s.ambient);
      // Shot noise: Gaussian approximation of Poisson(signal * full_well) electrons.
      if (s.full_well_electrons > 0.0) signal += std::sqrt(signal / s.full_well_electrons) * normal(rng);
      if (s.read_noise_dn > 0.0) signal += s.read_noise_dn / span * normal(rng);
      const double clamped = std::clamp(signal, 0.0, 1.0);
      const double response = s.response_gamma == 1.0 ? clamped : std::pow(clamped, 1.0 / s.response_gamma);
      const double dn = std::clamp(std::round(s.black_level + span * response), 0.0, full_scale);
      if (s.bit_depth == 8) {
        raw.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(dn);
      } else {
        raw.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(dn);
      }
    }
  }
  return raw;
}

capture::CaptureManifest make_manifest(const CaptureSettings& s, cv::Size camera_size, cv::Size projector_size) {
  capture::CaptureManifest manifest;
  manifest.family = s.family;
  manifest.parameters = s.parameters;
  manifest.projector_size = projector_size;
  manifest.camera_size = camera_size;
  manifest.dot_spacing = s.dot_spacing;
  manifest.bit_depth = s.bit_depth;
  manifest.black_level = s.black_level;
  char gamma[32];
  std::snprintf(gamma, sizeof gamma, "gamma:%.17g", s.response_gamma);
  manifest.camera_response = s.response_gamma == 1.0 ? "linear" : gamma;
  manifest.frames =
      capture::protocol_frames(capture::protocol_options(manifest), s.format == "tiff" ? ".tiff" : ".png");
  return manifest;
}

void write_capture(const TransportMatrix& T, const CaptureSettings& settings, cv::Size camera_size,
                   cv::Size projector_size, std::uint64_t seed, int threads, const fs::path& capture_dir,
                   Progress* progress) {
  const auto manifest = make_manifest(settings, camera_size, projector_size);
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&] {
    for (std::size_t i = next++; i < manifest.frames.size(); i = next++) {
      try {
        const auto& frame = manifest.frames[i];
        const cv::Mat pattern = capture::render_pattern(frame.pattern, capture::protocol_options(manifest));
        const cv::Mat raw = camera_reading(transport_image(T, pattern, camera_size), settings, seed, i);
        const fs::path path = capture_dir / frame.file;
        write_image(path, raw);
        if (progress != nullptr) progress->advance();
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = manifest.frames.size();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
  capture::write_manifest(manifest, capture_dir);
}

}  // namespace rfrecon::sim
