// Accuracy of decoding and compression (C++ reference, identical to the kernels by transport_kernel_test) on a
// synthetic plane whose light transport is known: correspondences, kept entries and energy, and the dual image of a
// checkerboard against the board seen from the projector.
#include <cmath>

#include <gtest/gtest.h>

#include "host/capture/protocol.h"
#include "host/transport/graycode_accumulator.h"
#include "host/transport/spmv.h"
#include "tests/transport/synthetic_capture.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::transport {
namespace {

constexpr int kDotSpacing = 5;  // > the 5 x 5 footprint's radius 2 on each side, so dots never overlap
constexpr int kEntries = 8;

struct Fixture {
  testing::PlaneScene scene;
  CompressedTransport transport;
};

// 160x120 camera, 128x96 projector, 8-bit frames with 1 DN Gaussian noise.
const Fixture& fixture() {
  static const Fixture instance = [] {
    testing::SceneOptions options;
    options.camera_size = {160, 120};
    options.projector_size = {128, 96};
    options.checker_size = 16;
    options.blur_sigma = 0.4;  // a focused spot: ~0.3 px optical blur over a ~0.8 px camera pixel footprint
    Fixture f{testing::make_plane_scene(options), {}};
    const auto sequence = capture::make_protocol({options.projector_size, kDotSpacing});
    const auto linear = testing::linearize(testing::render_frames(f.scene, sequence, kDotSpacing, 1.0, 11));
    auto accumulator =
        make_reference_accumulator(testing::setup_for(linear, options.projector_size, kDotSpacing, kEntries));
    f.transport = testing::feed_all(*accumulator, sequence, linear);
    return f;
  }();
  return instance;
}

TEST(TransportAccuracyTest, GrayCodeDecodesLitPixelsToTheTrueProjectorPixel) {
  const auto& [scene, transport] = fixture();
  std::size_t lit = 0, exact = 0, valid = 0, shadow_flagged = 0, unlit = 0;
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    const cv::Vec2f truth = scene.correspondence.at<cv::Vec2f>(static_cast<int>(c));
    if (std::isnan(truth[0])) {
      ++unlit;
      shadow_flagged += (transport.flags[c] & kFlagShadow) != 0 ? 1 : 0;
      continue;
    }
    ++lit;
    const bool is_valid = (transport.flags[c] & kFlagValid) != 0;
    valid += is_valid ? 1 : 0;
    // Pixel centres at integer coordinates: the projector pixel containing the true point is its rounding.
    exact += is_valid && transport.pixel_x[c] == static_cast<std::uint32_t>(std::lround(truth[0])) &&
                     transport.pixel_y[c] == static_cast<std::uint32_t>(std::lround(truth[1]))
                 ? 1
                 : 0;
  }
  const double exact_fraction = static_cast<double>(exact) / static_cast<double>(lit);
  std::printf(
      "decode: %zu lit pixels, %.2f%% valid, %.2f%% exact to the projector pixel (%.3f%% of valid ones); "
      "%zu of %zu unlit flagged shadow\n",
      lit, 100.0 * valid / lit, 100.0 * exact_fraction, 100.0 * exact / valid, shadow_flagged, unlit);
  // OpenCV's semantic rejects (low contrast) pixels whose true point lies within a few hundredths of a pixel of a
  // projector pixel edge, where |pattern - inverse| <= white threshold; every pixel it keeps must decode exactly
  // (99.5% allows for noise flipping a bit just above the threshold).
  const double exact_of_valid = static_cast<double>(exact) / static_cast<double>(valid);
  EXPECT_GE(exact_of_valid, 0.995);
  // Rejections: ~2 x 0.03 px bands around every pixel edge in x and y on the dark squares, fewer on the light ones.
  EXPECT_GE(static_cast<double>(valid) / static_cast<double>(lit), 0.85);
  EXPECT_EQ(shadow_flagged, unlit) << "every unlit pixel must be flagged as shadow";
}

TEST(TransportAccuracyTest, KeptEntriesMatchRenderedTransportAndKeepItsEnergy) {
  const auto& [scene, transport] = fixture();
  const auto& truth = scene.transport;
  double kept_truth = 0.0, total_truth = 0.0, kept_measured = 0.0, measured = 0.0;
  double error_sq = 0.0, truth_sq = 0.0;
  std::size_t kept_count = 0;
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    if (!compressible(transport.flags[c])) continue;
    for (int k = 0; k < kEntries; ++k) {
      const int q = transport.indices[c * kEntries + k];
      if (q < 0) continue;
      const double expected = truth.coeff(static_cast<int>(c), q);
      kept_truth += expected;
      kept_measured += transport.weights[c * kEntries + k];
      error_sq += std::pow(transport.weights[c * kEntries + k] - expected, 2);
      truth_sq += expected * expected;
      ++kept_count;
    }
    measured += transport.direct_energy[c];
    for (Eigen::SparseMatrix<float, Eigen::RowMajor, int>::InnerIterator it(truth, static_cast<int>(c)); it; ++it) {
      total_truth += it.value();
    }
  }
  const double kept_of_measured = kept_measured / measured;
  const double kept_of_rendered = kept_truth / total_truth;
  const double relative_error = std::sqrt(error_sq / truth_sq);
  // Sensor model of the renderer: each entry is a dot reading minus a black reading, both with 1 DN Gaussian noise
  // and 1/sqrt(12) DN quantization, so its error variance is 2 (1 + 1/12) DN^2.
  const double predicted_error = std::sqrt(kept_count * 2.0 * (1.0 + 1.0 / 12.0) / (255.0 * 255.0) / truth_sq);
  std::printf(
      "compress: K = %d keeps %.3f%% of the measured window energy and %.3f%% of the rendered T's; kept entries' "
      "relative RMS error %.4f (sensor noise alone: %.4f)\n",
      kEntries, 100.0 * kept_of_measured, 100.0 * kept_of_rendered, relative_error, predicted_error);
  EXPECT_GE(kept_of_measured, 0.99);  // the spec at K = 8: truncation to K loses under 1%
  // Against the rendered T the entries at or below the noise threshold (2.5 DN) are lost too: corners of the spot
  // on the 0.3-albedo squares. 2.5% bounds that for this blur.
  EXPECT_GE(kept_of_rendered, 0.975);
  // No bias beyond sensor noise: within 25% of the noise-only prediction (entries just above the noise threshold
  // are kept only when their noise is positive, a small selection bias).
  EXPECT_LT(relative_error, 1.25 * predicted_error);
}

TEST(TransportAccuracyTest, SubPixelCorrespondenceIsTheTruePoint) {
  const auto& [scene, transport] = fixture();
  double error_sq = 0.0;
  std::size_t count = 0;
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    if (std::isnan(transport.correspondence[2 * c])) continue;
    const cv::Vec2f truth = scene.correspondence.at<cv::Vec2f>(static_cast<int>(c));
    error_sq += std::pow(transport.correspondence[2 * c] - truth[0], 2) +
                std::pow(transport.correspondence[2 * c + 1] - truth[1], 2);
    ++count;
  }
  const double rms = std::sqrt(error_sq / static_cast<double>(count));
  std::printf("correspondence: RMS %.4f projector px over %zu pixels\n", rms, count);
  // The centroid of a spot sampled by projector pixels is pulled towards pixel centres ("pixel locking", up to
  // ~0.1 px for a spot this narrow), plus noise: 0.1 px, a tenth of the Gray code's 1 px step.
  EXPECT_LT(rms, 0.1);
}

TEST(TransportAccuracyTest, DualImageOfCheckerboardIsTheBoardSeenFromTheProjector) {
  const auto& [scene, transport] = fixture();
  const std::vector<float> ones(transport.camera_pixels(), 1.0f);
  const auto dual = dual_reference(transport, ones);
  const Eigen::VectorXf truth = scene.transport.transpose() * Eigen::VectorXf::Ones(scene.transport.rows());
  // Compare inside the lit area, away from its border (where the camera's view ends mid-pixel).
  double error_sq = 0.0, truth_sq = 0.0, white_sum = 0.0, black_sum = 0.0;
  std::size_t white_count = 0, black_count = 0;
  for (int y = 8; y < scene.projector_size.height - 8; ++y) {
    for (int x = 8; x < scene.projector_size.width - 8; ++x) {
      const int q = y * scene.projector_size.width + x;
      error_sq += std::pow(dual[q] - truth[q], 2);
      truth_sq += std::pow(truth[q], 2);
      const bool square_edge = x % 16 == 0 || x % 16 == 15 || y % 16 == 0 || y % 16 == 15;
      if (square_edge) continue;
      if (scene.albedo.at<float>(y, x) > 0.5f) {
        white_sum += dual[q];
        ++white_count;
      } else {
        black_sum += dual[q];
        ++black_count;
      }
    }
  }
  const double relative_error = std::sqrt(error_sq / truth_sq);
  const double contrast = (white_sum / white_count) / (black_sum / black_count);
  std::printf("dual: relative RMS error %.4f against T^T 1 of the rendered T; white/black ratio %.3f (albedo 3)\n",
              relative_error, contrast);
  // The dual sums the kept entries: it misses the ~2.5% of the energy below the noise threshold (previous test)
  // plus entry noise averaged over the ~2 camera pixels per projector pixel.
  EXPECT_LT(relative_error, 0.035);
  EXPECT_NEAR(contrast, 0.9 / 0.3, 0.05 * 3.0);  // the board's albedo ratio, within 5%
}

}  // namespace
}  // namespace rfrecon::transport
