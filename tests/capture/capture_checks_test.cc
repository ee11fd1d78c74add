// The capture checks on rendered captures of the small test rig (a tilted matte plane, 80x60 camera): a clean render
// passes, a gamma 2.2 render declared linear is caught with the right gamma, a saturated render with its share,
// swapped frames as out of order; 10- and 12-bit data in 16-bit files decode under both layouts. Also the real
// captures of ../shared/data/procam-graycode (skipped when absent).
#include "host/capture/capture_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "host/capture/graycode_patterns.h"
#include "host/capture/phase_patterns.h"
#include "host/core/errors.h"
#include "host/transport/compute_transport.h"
#include "tests/capture/rendered_capture.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::capture {
namespace {

namespace fs = std::filesystem;

CaptureManifest render(const fs::path& dir, const std::function<void(sim::Scene&)>& adjust) {
  return rfrecon::testing::render_capture(dir, adjust);
}

bool has_finding(const CaptureCheckResult& result, const std::string& check) {
  return std::any_of(result.findings.begin(), result.findings.end(),
                     [&](const CheckFinding& finding) { return finding.check == check; });
}

std::string findings_text(const CaptureCheckResult& result) {
  std::string text;
  for (const auto& finding : result.findings) text += finding.check + ": " + finding.message + "\n";
  return text;
}

TEST(CaptureChecksTest, CleanRenderPasses) {
  rfrecon::testing::TempDir dir("checks_clean");
  const auto manifest = render(dir.path(), [](sim::Scene&) {});
  const auto result = check_capture(dir.path(), manifest);
  EXPECT_TRUE(result.findings.empty()) << findings_text(result);
  EXPECT_GT(result.lit_pixels, result.sampled_pixels / 4) << "the plane must fill a good part of the view";
  // Linear frames add up: dots to white within 5 %, the estimated gamma within 5 % of 1.
  EXPECT_NEAR(result.dot_sum_ratio, 1.0, 0.05);
  EXPECT_NEAR(result.pair_sum_ratio, 1.0, 0.02);
  EXPECT_NEAR(result.response_gamma, 1.0, 0.05);
  // The render's noise at mid scale: shot noise sqrt(0.5 / 20000) = 0.005 and 0.5 DN of 1007 read noise, so one
  // frame's sigma lies between the read noise alone (0.0005) and shot plus read noise at full scale (0.0071).
  EXPECT_GT(result.noise_sigma, 0.0005);
  EXPECT_LT(result.noise_sigma, 0.0071);
}

TEST(CaptureChecksTest, GammaDeclaredLinearIsCaughtWithItsGamma) {
  rfrecon::testing::TempDir dir("checks_gamma");
  auto manifest = render(dir.path(), [](sim::Scene& scene) { scene.capture.response_gamma = 2.2; });
  ASSERT_EQ(manifest.camera_response.rfind("gamma:", 0), 0u) << "the renderer declares its response";
  // Declared as it is: no finding.
  const auto declared = check_capture(dir.path(), manifest);
  EXPECT_TRUE(declared.findings.empty()) << findings_text(declared);
  // Declared linear, as a user who left the camera's gamma on: the response check names gamma 2.2 within 5 %.
  manifest.camera_response = "linear";
  write_manifest(manifest, dir.path());
  const auto result = check_capture(dir.path(), manifest);
  ASSERT_TRUE(has_finding(result, "response")) << findings_text(result);
  EXPECT_FALSE(has_finding(result, "saturation")) << findings_text(result);
  EXPECT_NEAR(result.response_gamma, 2.2, 0.11);
  // Readings^(1/2.2) of the dots that share a pixel's light sum to more than white's: beyond the linearity
  // tolerance of 10 %, on the median pixel.
  EXPECT_GT(result.dot_sum_ratio, 1.1);

  // The transport stage runs the same checks on the frames it reads.
  transport::TransportSetup setup;
  const auto run = transport::compute_transport(
      dir.path(), read_manifest(dir.path()), setup,
      [](const transport::TransportSetup& s) { return transport::make_reference_accumulator(s); });
  EXPECT_TRUE(has_finding(run.checks, "response")) << findings_text(run.checks);
  EXPECT_NEAR(run.checks.response_gamma, 2.2, 0.11);
}

// Gray-code-only captures (the real ones are) have the pairs' identity alone: the same estimate within 5 %.
TEST(CaptureChecksTest, GammaIsEstimatedFromGrayPairsAlone) {
  rfrecon::testing::TempDir dir("checks_gamma_gray");
  auto manifest = render(dir.path(), [](sim::Scene& scene) {
    scene.capture.response_gamma = 2.2;
    scene.capture.dot_spacing = 0;
  });
  manifest.camera_response = "linear";
  const auto result = check_capture(dir.path(), manifest);
  ASSERT_TRUE(has_finding(result, "response")) << findings_text(result);
  EXPECT_NEAR(result.response_gamma, 2.2, 0.11);
}

// Phase captures: the N steps of each period add up to N / 2 (white + black), an identity every lit pixel under a
// visible sinusoid gives; with longer periods (no order code) it is the only one. Linear: no finding, gamma 1 within
// 5 %; gamma 2.2 declared linear: caught, within 5 %.
TEST(CaptureChecksTest, GammaIsEstimatedFromPhaseSteps) {
  for (const int ratio : {0, 4}) {
    SCOPED_TRACE("phase_ratio " + std::to_string(ratio));
    for (const double gamma : {1.0, 2.2}) {
      rfrecon::testing::TempDir dir("checks_gamma_phase");
      auto manifest = render(dir.path(), [&](sim::Scene& scene) {
        scene.capture.response_gamma = gamma;
        scene.capture.dot_spacing = 0;
        scene.capture.family = "phase";
        scene.capture.parameters = {{kPhaseRatio, ratio}};
      });
      manifest.camera_response = "linear";
      const auto result = check_capture(dir.path(), manifest);
      EXPECT_EQ(has_finding(result, "response"), gamma != 1.0) << findings_text(result);
      EXPECT_NEAR(result.response_gamma, gamma, 0.05 * gamma);
      EXPECT_GE(result.response_samples, 50U);
    }
  }
}

TEST(CaptureChecksTest, SaturatedRenderIsCaughtWithItsShare) {
  rfrecon::testing::TempDir dir("checks_saturated");
  const auto manifest = render(dir.path(), [](sim::Scene& scene) { scene.intensity *= 6.0; });
  const auto result = check_capture(dir.path(), manifest);
  ASSERT_TRUE(has_finding(result, "saturation")) << findings_text(result);
  EXPECT_FALSE(has_finding(result, "response")) << "saturated pixels are left out of the response estimate\n"
                                                << findings_text(result);
  // Every pattern frame is at most as bright as white, so the share is white's share of pixels at the top code;
  // the 80x60 camera is sampled whole (stride 1), up to a pattern frame that noise lifts to the top.
  std::size_t white = 0;
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    if (manifest.frames[i].pattern.kind == pattern_kind::kWhite) white = i;
  }
  const cv::Mat raw = cv::imread((dir.path() / manifest.frames[white].file).string(), cv::IMREAD_ANYDEPTH);
  const double top_share =
      static_cast<double>(cv::countNonZero(raw == (1 << manifest.bit_depth) - 1)) / static_cast<double>(raw.total());
  ASSERT_GT(top_share, 0.05) << "the render must saturate";
  EXPECT_GE(result.saturated_share, top_share);
  EXPECT_LE(result.saturated_share, top_share + 0.01);
}

TEST(CaptureChecksTest, SwappedFramesAreOutOfOrder) {
  rfrecon::testing::TempDir dir("checks_order");
  const auto manifest = render(dir.path(), [](sim::Scene&) {});
  const auto swap_files = [&](const char* a_kind, int a_bit, const char* b_kind, int b_bit) {
    CaptureManifest swapped = manifest;
    const auto find = [&](const char* kind, int bit) {
      return std::find_if(swapped.frames.begin(), swapped.frames.end(), [&](const Frame& frame) {
        return frame.pattern.kind == kind && (bit < 0 || (frame.pattern.bit == bit && !frame.pattern.inverse));
      });
    };
    std::swap(find(a_kind, a_bit)->file, find(b_kind, b_bit)->file);
    return check_capture(dir.path(), swapped);
  };
  const auto white_black = swap_files(pattern_kind::kWhite, -1, pattern_kind::kBlack, -1);
  EXPECT_TRUE(has_finding(white_black, "frame_order")) << findings_text(white_black);
  const auto column_row = swap_files(pattern_kind::kGrayColumn, 0, pattern_kind::kGrayRow, 0);
  EXPECT_TRUE(has_finding(column_row, "frame_order")) << findings_text(column_row);
}

// The capture's frames copied as an OpenCV script saves them: Gray pairs, white, black, named in that order.
void copy_as_opencv_layout(const CaptureManifest& manifest, const fs::path& from, const fs::path& to) {
  const auto sequence = opencv_graycode_protocol(manifest.projector_size);
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const auto frame = std::find_if(manifest.frames.begin(), manifest.frames.end(), [&](const Frame& f) {
      return f.pattern.kind == sequence[i].kind && f.pattern.bit == sequence[i].bit &&
             f.pattern.inverse == sequence[i].inverse;
    });
    ASSERT_NE(frame, manifest.frames.end());
    char name[32];
    std::snprintf(name, sizeof name, "frame_%03zu.png", i);
    fs::copy_file(from / frame->file, to / name);
  }
}

TEST(CaptureChecksTest, TenAndTwelveBitDataInSixteenBitFilesDecodeUnderBothLayouts) {
  const auto decode = [](const fs::path& capture_dir, const CaptureManifest& capture) {
    return transport::compute_transport(
        capture_dir, capture, transport::TransportSetup{},
        [](const transport::TransportSetup& s) { return transport::make_reference_accumulator(s); });
  };
  const auto decoded = [](const transport::TransportRun& run) {
    return std::count_if(run.transport.flags.begin(), run.transport.flags.end(),
                         [](std::uint8_t flags) { return (flags & transport::kFlagValid) != 0; });
  };
  for (const int bits : {10, 12}) {
    SCOPED_TRACE(std::to_string(bits) + "-bit data");
    rfrecon::testing::TempDir dir("checks_" + std::to_string(bits) + "bit");
    rfrecon::testing::TempDir opencv_dir("checks_" + std::to_string(bits) + "bit_opencv");
    const auto manifest = render(dir.path(), [&](sim::Scene& scene) {
      scene.capture.bit_depth = bits;
      scene.capture.dot_spacing = 0;
    });
    ASSERT_NO_FATAL_FAILURE(copy_as_opencv_layout(manifest, dir.path(), opencv_dir.path()));
    const auto opencv = manifest_from_opencv_layout(opencv_dir.path(), manifest.projector_size, bits);
    EXPECT_EQ(opencv.bit_depth, bits);
    EXPECT_THROW(manifest_from_opencv_layout(opencv_dir.path(), manifest.projector_size, 8), InputError);

    // The same frames at the same bit depth: the same decoded pixels, a good part of the view, and no finding.
    const auto from_manifest = decode(dir.path(), manifest);
    const auto from_opencv = decode(opencv_dir.path(), opencv);
    EXPECT_GT(decoded(from_manifest), static_cast<long>(from_manifest.transport.camera_pixels() / 4));
    EXPECT_EQ(from_opencv.transport.pixel_x, from_manifest.transport.pixel_x);
    EXPECT_EQ(from_opencv.transport.pixel_y, from_manifest.transport.pixel_y);
    EXPECT_EQ(from_opencv.transport.flags, from_manifest.transport.flags);
    EXPECT_TRUE(from_opencv.checks.findings.empty()) << findings_text(from_opencv.checks);

    // Read as 16-bit data, the same files draw the bit-depth finding naming the right depth.
    const auto as_sixteen = manifest_from_opencv_layout(opencv_dir.path(), manifest.projector_size);
    const auto checked = check_capture(opencv_dir.path(), as_sixteen);
    ASSERT_TRUE(has_finding(checked, "bit_depth")) << findings_text(checked);
    EXPECT_NE(findings_text(checked).find("--bit-depth " + std::to_string(bits)), std::string::npos)
        << findings_text(checked);
  }
}

TEST(CaptureChecksTest, RealCapturesAddUp) {
  const fs::path data = fs::path(RFRECON_SOURCE_DIR) / ".." / "shared" / "data" / "procam-graycode";
  if (!fs::is_directory(data)) GTEST_SKIP() << data << " is absent";
  for (int pose = 0; pose < 4; ++pose) {
    const fs::path dir = data / ("capture_" + std::to_string(pose));
    const auto result = check_capture(dir, manifest_from_opencv_layout(dir, {1024, 768}));
    std::printf(
        "capture_%d: lit %zu of %zu, saturated %.4f, pair sum %.3f, gamma %.3f (%zu samples), black 1%% %.1f "
        "DN, white 99%% %.3f, noise %.4f, range %.0f\n%s",
        pose, result.lit_pixels, result.sampled_pixels, result.saturated_share, result.pair_sum_ratio,
        result.response_gamma, result.response_samples, result.black_frame_dn, result.white_level, result.noise_sigma,
        result.dynamic_range, findings_text(result).c_str());
    // A linear 8-bit camera: pattern + inverse = white + black within 5 %.
    EXPECT_NEAR(result.pair_sum_ratio, 1.0, 0.05) << dir;
  }
}

}  // namespace
}  // namespace rfrecon::capture
