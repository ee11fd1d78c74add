// The transport stage on the synthetic rig (sim/): a tilted Lambertian plane rendered with its exact T, captured
// with the full protocol in 8 bits, decoded and compressed, and compared with the rig's ground truth.
#include <cmath>

#include <gtest/gtest.h>

#include "host/transport/compute_transport.h"
#include "host/transport/spmv.h"
#include "sim/frames.h"
#include "sim/render.h"
#include "tests/sim/test_scenes.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon::transport {
namespace {

constexpr int kDotSpacing = 5;
constexpr int kEntries = 8;

struct SimFixture {
  sim::Transport truth;
  CompressedTransport transport;
};

const SimFixture& sim_fixture() {
  static const SimFixture instance = [] {
    sim::Scene scene = sim::testing::make_scene(
        sim::testing::small_rig({sim::testing::tilted_plane({{"brdf", "lambert"}, {"diffuse", 0.6}})}));
    scene.capture.dot_spacing = kDotSpacing;
    scene.capture.bit_depth = 8;
    scene.capture.black_level = 4.0;
    scene.capture.ambient = 0.02;
    SimFixture f{sim::render_transport(scene), {}};
    testing::TempDir dir("sim");
    sim::write_capture(f.truth.T, scene.capture, scene.camera.size, scene.projector.size, 1, 2, dir.path());
    TransportSetup setup;
    setup.entries_per_pixel = kEntries;
    f.transport = compute_transport(dir.path(), capture::read_manifest(dir.path()), setup, [](const TransportSetup& s) {
                    return make_reference_accumulator(s);
                  }).transport;
    return f;
  }();
  return instance;
}

TEST(SimTransportTest, DecodedCorrespondencesMatchTheRigsTruth) {
  const auto& [truth, transport] = sim_fixture();
  std::size_t lit = 0, valid = 0, exact = 0;
  for (int c = 0; c < static_cast<int>(transport.camera_pixels()); ++c) {
    const cv::Vec2f xy = truth.truth.correspondence.at<cv::Vec2f>(c);
    const bool in_projector = xy[0] > -0.5f && xy[1] > -0.5f && xy[0] < transport.setup.projector_size.width - 0.5f &&
                              xy[1] < transport.setup.projector_size.height - 0.5f;
    if (std::isnan(xy[0]) || truth.truth.shadow.at<unsigned char>(c) != 0 || !in_projector) continue;
    ++lit;
    if ((transport.flags[c] & kFlagValid) == 0) continue;
    ++valid;
    exact += transport.pixel_x[c] == static_cast<std::uint32_t>(std::lround(xy[0])) &&
                     transport.pixel_y[c] == static_cast<std::uint32_t>(std::lround(xy[1]))
                 ? 1
                 : 0;
  }
  ASSERT_GT(lit, transport.camera_pixels() / 4) << "the plane must fill a good part of the view";
  std::printf(
      "sim decode: %zu lit pixels, %.2f%% valid, %.2f%% of lit and %.3f%% of valid exact to the projector "
      "pixel\n",
      lit, 100.0 * valid / lit, 100.0 * exact / lit, 100.0 * exact / valid);
  // OpenCV's semantic: every pixel it keeps decodes to the projector pixel containing the true point; 0.5% for
  // noise flipping a bit just above the white threshold.
  EXPECT_GE(static_cast<double>(exact) / valid, 0.995);
}

TEST(SimTransportTest, CompressedTransportMatchesTheRigsT) {
  const auto& [truth, transport] = sim_fixture();
  double kept_measured = 0.0, measured = 0.0, error_sq = 0.0, truth_sq = 0.0;
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    if (std::isnan(transport.correspondence[2 * c])) continue;
    for (int k = 0; k < kEntries; ++k) {
      const int q = transport.indices[c * kEntries + k];
      if (q < 0) continue;
      const double expected = truth.T.coeff(static_cast<int>(c), q);
      kept_measured += transport.weights[c * kEntries + k];
      error_sq += std::pow(transport.weights[c * kEntries + k] - expected, 2);
      truth_sq += expected * expected;
    }
    measured += transport.direct_energy[c];
  }
  const double relative_error = std::sqrt(error_sq / truth_sq);
  std::printf("sim compress: K = %d keeps %.3f%% of the measured energy; kept entries' relative RMS error %.4f\n",
              kEntries, 100.0 * kept_measured / measured, relative_error);
  EXPECT_GE(kept_measured / measured, 0.99);  // the spec at K = 8
  // 8-bit readings with shot and read noise on entries of tens of DN: a few percent.
  EXPECT_LT(relative_error, 0.08);
}

TEST(SimTransportTest, DualImageMatchesTheRigsDual) {
  const auto& [truth, transport] = sim_fixture();
  const auto dual = dual_reference(transport, std::vector<float>(transport.camera_pixels(), 1.0f));
  const Eigen::VectorXf expected = truth.T.transpose() * Eigen::VectorXf::Ones(truth.T.rows());
  double error_sq = 0.0, truth_sq = 0.0;
  for (std::size_t q = 0; q < dual.size(); ++q) {
    error_sq += std::pow(dual[q] - expected[static_cast<int>(q)], 2);
    truth_sq += std::pow(expected[static_cast<int>(q)], 2);
  }
  const double relative_error = std::sqrt(error_sq / truth_sq);
  std::printf("sim dual: relative RMS error %.4f against T^T 1 of the rig's T\n", relative_error);
  // Lost: entries under the noise threshold, pixels at the plane's border, noise. 5% keeps the image usable for
  // corner detection (sub-pixel corners need the board's contrast, not its absolute level).
  EXPECT_LT(relative_error, 0.05);
}

}  // namespace
}  // namespace rfrecon::transport
