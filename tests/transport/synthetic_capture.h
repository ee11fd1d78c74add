// Test inputs for the transport stage: a camera viewing a plane lit by the projector, with a known light transport
// T (camera pixel footprint = Gaussian blur spot around a known projector point), rendered through the capture
// protocol with 8-bit quantization and noise.
#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/SparseCore>
#include <opencv2/core.hpp>

#include "host/capture/manifest.h"
#include "host/capture/protocol.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::transport::testing {

using rfrecon::testing::TempDir;

struct PlaneScene {
  cv::Size camera_size;
  cv::Size projector_size;
  Eigen::SparseMatrix<float, Eigen::RowMajor, int> transport;  // rows camera y*W+x, cols projector y*Wp+x
  cv::Mat correspondence;  // CV_32FC2: true projector (x, y) of each camera pixel centre (NaN where unlit)
  cv::Mat albedo;          // CV_32F per projector pixel: the scene's reflectance seen from the projector
  float ambient = 0.0f;    // linear light added to every frame
};

struct SceneOptions {
  cv::Size camera_size{40, 32};
  cv::Size projector_size{24, 20};
  double blur_sigma = 0.4;  // projector pixels
  float ambient = 0.03f;    // linear units
  int checker_size = 0;     // >0: albedo is a checkerboard of this many projector pixels (0.9 / 0.3), else 0.8
  int shadow_columns = 3;   // camera columns on the left that the projector does not light
};

// Camera pixel (u, v) sees projector point (a u + b v + c, d u + e v + f), an affine map whose image covers most of
// the projector; T[c, q] = albedo(point) * integral over projector pixel q of a Gaussian of blur_sigma around the
// point (support 5 x 5 pixels). Pixel centres are at integer coordinates in both images.
PlaneScene make_plane_scene(const SceneOptions& options);

// The camera frames of `sequence`: reading = clamp(T L + ambient + noise) quantized to 8 bits, L in [0, 1].
std::vector<cv::Mat> render_frames(const PlaneScene& scene, const std::vector<capture::Pattern>& sequence,
                                   int dot_spacing, double noise_dn, unsigned seed);
// The same for the patterns of any family: `options` as capture::render_pattern takes them.
std::vector<cv::Mat> render_frames(const PlaneScene& scene, const std::vector<capture::Pattern>& sequence,
                                   const capture::ProtocolOptions& options, double noise_dn, unsigned seed);

// Writes frames and manifest (8-bit, linear, black level 0) into `dir`; returns the manifest.
capture::CaptureManifest write_capture(const std::filesystem::path& dir, const PlaneScene& scene,
                                       const std::vector<capture::Pattern>& sequence, int dot_spacing,
                                       const std::vector<cv::Mat>& frames);

}  // namespace rfrecon::transport::testing
