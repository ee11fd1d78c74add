// Sub-pixel correspondences of Gray-code-only captures (host/transport/gray_subpixel.h) against a known smooth
// camera -> projector mapping with the code's gradient along camera x, along camera y and diagonal, with and without
// noise; and the transport stage leaving dot-grid correspondences alone.
#include "host/transport/gray_subpixel.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "host/capture/protocol.h"
#include "host/transport/compute_transport.h"
#include "tests/transport/synthetic_capture.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::transport {
namespace {

const cv::Size kCamera{80, 72};
const cv::Size kProjector{64, 64};

using ProjectorFromCamera = std::function<cv::Point2d(double u, double v)>;

double gaussian_mass(double mean, double sigma, double lo, double hi) {
  const double scale = 1.0 / (sigma * std::sqrt(2.0));
  return 0.5 * (std::erf((hi - mean) * scale) - std::erf((lo - mean) * scale));
}

struct Capture {
  std::vector<capture::Pattern> sequence;
  std::vector<cv::Mat> frames;  // linear CV_32F
  cv::Mat truth;                // CV_64FC2 projector (x, y) of each camera pixel centre
};

// Camera pixel (u, v) sees projector point map(u, v) through a Gaussian blur of 0.5 projector px, on a surface whose
// reflectance varies from 0.35 to 0.85 across the image, plus ambient light 0.03 and Gaussian noise of `noise`.
Capture render(const ProjectorFromCamera& map, double noise, unsigned seed) {
  Capture capture;
  capture.sequence = capture::make_protocol({kProjector, 0});
  capture.truth = cv::Mat(kCamera, CV_64FC2);
  std::vector<cv::Mat> light;
  for (const auto& pattern : capture.sequence) light.push_back(capture::render_pattern(pattern, kProjector, 0));
  std::mt19937 random(seed);
  std::normal_distribution<float> gaussian(0.0f, static_cast<float>(noise));
  for (std::size_t f = 0; f < light.size(); ++f) capture.frames.emplace_back(kCamera, CV_32F);
  for (int v = 0; v < kCamera.height; ++v) {
    for (int u = 0; u < kCamera.width; ++u) {
      const cv::Point2d xy = map(u, v);
      capture.truth.at<cv::Vec2d>(v, u) = {xy.x, xy.y};
      const double albedo = 0.6 + 0.25 * std::sin(u / 7.0) * std::cos(v / 5.0);
      const int x0 = static_cast<int>(std::lround(xy.x));
      const int y0 = static_cast<int>(std::lround(xy.y));
      for (std::size_t f = 0; f < light.size(); ++f) {
        double lit = 0.0;
        for (int qy = std::max(y0 - 2, 0); qy <= std::min(y0 + 2, kProjector.height - 1); ++qy) {
          for (int qx = std::max(x0 - 2, 0); qx <= std::min(x0 + 2, kProjector.width - 1); ++qx) {
            if (light[f].at<unsigned char>(qy, qx) == 0) continue;
            lit += gaussian_mass(xy.x, 0.5, qx - 0.5, qx + 0.5) * gaussian_mass(xy.y, 0.5, qy - 0.5, qy + 0.5);
          }
        }
        capture.frames[f].at<float>(v, u) = static_cast<float>(0.03 + albedo * lit) + gaussian(random);
      }
    }
  }
  return capture;
}

struct Refined {
  CompressedTransport transport;
  double rms_px = 0.0;            // correspondence error (both axes) over refined pixels, projector px
  double integer_rms_px = 0.0;    // the integer codes' error over the same pixels
  double refined_fraction = 0.0;  // of the valid pixels at least 4 px from the image border, both axes refined
};

Refined refine(const Capture& capture) {
  auto accumulator = make_reference_accumulator(testing::setup_for(capture.frames, kProjector, 0, 1));
  Refined r{testing::feed_all(*accumulator, capture.sequence, capture.frames)};
  GraySubpixel subpixel(kCamera);
  for (std::size_t i = 0; i < capture.sequence.size(); ++i) {
    const auto& pattern = capture.sequence[i];
    if (pattern.kind != capture::PatternKind::kGrayColumn && pattern.kind != capture::PatternKind::kGrayRow) continue;
    if (pattern.inverse) continue;
    const GrayAxis axis = pattern.kind == capture::PatternKind::kGrayColumn ? GrayAxis::kColumns : GrayAxis::kRows;
    subpixel.add_gray_pair(axis, capture.frames[i], capture.frames[i + 1]);  // the inverse follows its pattern
  }
  subpixel.refine(r.transport);
  double sum = 0.0, integer_sum = 0.0;
  std::size_t count = 0, interior = 0, refined = 0;
  for (int v = 0; v < kCamera.height; ++v) {
    for (int u = 0; u < kCamera.width; ++u) {
      const std::size_t c = static_cast<std::size_t>(v) * kCamera.width + u;
      if ((r.transport.flags[c] & kFlagValid) == 0) continue;
      const float x = r.transport.correspondence[2 * c];
      const float y = r.transport.correspondence[2 * c + 1];
      const bool both = x != std::round(x) && y != std::round(y);
      const bool inside = u >= 4 && v >= 4 && u < kCamera.width - 4 && v < kCamera.height - 4;
      interior += inside ? 1 : 0;
      refined += inside && both ? 1 : 0;
      if (!both) continue;
      const cv::Vec2d truth = capture.truth.at<cv::Vec2d>(v, u);
      sum += (x - truth[0]) * (x - truth[0]) + (y - truth[1]) * (y - truth[1]);
      const double ix = r.transport.gray_x[c] - truth[0], iy = r.transport.gray_y[c] - truth[1];
      integer_sum += ix * ix + iy * iy;
      ++count;
    }
  }
  r.rms_px = std::sqrt(sum / static_cast<double>(count));
  r.integer_rms_px = std::sqrt(integer_sum / static_cast<double>(count));
  r.refined_fraction = static_cast<double>(refined) / static_cast<double>(interior);
  return r;
}

// Smooth, slightly curved mappings of the 80 x 72 camera onto the middle of the 64 x 64 projector, about 0.7
// projector px per camera px (the projector's code changes by at most one between neighbouring camera pixels).
struct Mapping {
  const char* name;
  ProjectorFromCamera map;
};

const Mapping kMappings[] = {
    {"columns along camera x",
     [](double u, double v) {
       const double du = u - 40.0, dv = v - 36.0;
       return cv::Point2d(32.3 + 0.7 * du + 0.05 * dv + 0.002 * du * du, 31.8 + 0.03 * du + 0.72 * dv);
     }},
    {"columns along camera y (projector above the camera)",
     [](double u, double v) {
       const double du = u - 40.0, dv = v - 36.0;
       return cv::Point2d(32.1 + 0.72 * dv - 0.04 * du, 31.6 + 0.68 * du + 0.002 * dv * dv);
     }},
    {"diagonal",
     [](double u, double v) {
       const double du = u - 40.0, dv = v - 36.0;
       return cv::Point2d(32.2 + 0.5 * (du + dv) + 0.001 * du * dv, 31.7 + 0.5 * (dv - du));
     }},
};

// Noise-free, what remains is the linear interpolation of the contrast between pixels (an S-shaped profile) and the
// plane's curvature error: measured RMS 0.009-0.024 projector px (both axes together) against 0.38-0.39 px of the
// integer codes (0.41 px = sqrt(2 / 12) for a uniform +-0.5 px error per axis; low contrast rejects the worst).
// Tolerance 0.05 px: twice the worst case measured.
TEST(GraySubpixelTest, NoiseFreeMappingsAreRecoveredFarBelowTheIntegerQuantisation) {
  for (const auto& mapping : kMappings) {
    const Refined r = refine(render(mapping.map, 0.0, 1));
    std::printf("%s: rms %.4f px (integer codes %.4f px), %.1f%% of interior pixels refined\n", mapping.name, r.rms_px,
                r.integer_rms_px, 100.0 * r.refined_fraction);
    EXPECT_LT(r.rms_px, 0.05) << mapping.name;
    EXPECT_GT(r.integer_rms_px, 0.35) << mapping.name;
    EXPECT_GT(r.refined_fraction, 0.95) << mapping.name;
  }
}

// 0.004 linear ~ 1 DN of an 8-bit camera per frame on a ~0.6 signal: measured RMS 0.009-0.020 px (the fit averages
// some 20 boundary points); the same tolerance.
TEST(GraySubpixelTest, NoisyMappingsStayFarBelowTheIntegerQuantisation) {
  for (const auto& mapping : kMappings) {
    const Refined r = refine(render(mapping.map, 0.004, 7));
    std::printf("%s, noise 0.004: rms %.4f px (integer codes %.4f px), %.1f%% of interior pixels refined\n",
                mapping.name, r.rms_px, r.integer_rms_px, 100.0 * r.refined_fraction);
    EXPECT_LT(r.rms_px, 0.05) << mapping.name;
    EXPECT_GT(r.refined_fraction, 0.95) << mapping.name;
  }
}

// The transport stage on a capture written to disk: Gray-code-only captures get the refined correspondences,
// captures with the dot grid keep their dot centroids bit for bit.
class GraySubpixelStageTest : public ::testing::Test {
 protected:
  CompressedTransport staged(const testing::PlaneScene& scene, int dot_spacing) {
    const auto sequence = capture::make_protocol({scene.projector_size, dot_spacing});
    const auto frames = testing::render_frames(scene, sequence, dot_spacing, 1.0, 5);
    testing::write_capture(dir_.path(), scene, sequence, dot_spacing, frames);
    const auto linear = testing::linearize(frames);
    const auto setup = testing::setup_for(linear, scene.projector_size, dot_spacing, 4);
    auto reference = make_reference_accumulator(setup);
    in_memory_ = testing::feed_all(*reference, sequence, linear);
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const auto kind = sequence[i].kind;
      if ((kind != capture::PatternKind::kGrayColumn && kind != capture::PatternKind::kGrayRow) ||
          sequence[i].inverse) {
        continue;
      }
      gray_.add_gray_pair(kind == capture::PatternKind::kGrayColumn ? GrayAxis::kColumns : GrayAxis::kRows, linear[i],
                          linear[i + 1]);
    }
    return compute_transport(dir_.path(), capture::read_manifest(dir_.path()), setup,
                             [](const TransportSetup& s) { return make_reference_accumulator(s); })
        .transport;
  }

  static testing::PlaneScene scene() {
    testing::SceneOptions options;
    options.camera_size = {64, 48};
    options.projector_size = {48, 40};
    return testing::make_plane_scene(options);
  }

  testing::TempDir dir_{"gray_subpixel_stage"};
  CompressedTransport in_memory_;
  GraySubpixel gray_{{64, 48}};
};

TEST_F(GraySubpixelStageTest, DotGridCapturesKeepTheirCentroidsBitForBit) {
  const CompressedTransport got = staged(scene(), 5);
  ASSERT_EQ(got.correspondence.size(), in_memory_.correspondence.size());
  EXPECT_EQ(0, std::memcmp(got.correspondence.data(), in_memory_.correspondence.data(),
                           got.correspondence.size() * sizeof(float)));
}

TEST_F(GraySubpixelStageTest, GrayCodeOnlyCapturesGetTheRefinedCorrespondences) {
  const CompressedTransport got = staged(scene(), 0);
  gray_.refine(in_memory_);
  EXPECT_EQ(0, std::memcmp(got.correspondence.data(), in_memory_.correspondence.data(),
                           got.correspondence.size() * sizeof(float)));
  std::size_t fractional = 0;
  for (const float xy : got.correspondence) fractional += !std::isnan(xy) && xy != std::round(xy) ? 1 : 0;
  EXPECT_GT(fractional, got.camera_pixels()) << "most valid pixels must be refined in both axes";
  // Against the scene's true correspondences (not the refinement's own output): well under the integer codes'
  // 0.41 px RMS quantisation.
  const cv::Mat truth = scene().correspondence;
  double sum = 0.0;
  std::size_t count = 0;
  for (int v = 0; v < truth.rows; ++v) {
    for (int u = 0; u < truth.cols; ++u) {
      const std::size_t c = static_cast<std::size_t>(v) * truth.cols + u;
      const cv::Vec2f t = truth.at<cv::Vec2f>(v, u);
      const float x = got.correspondence[2 * c], y = got.correspondence[2 * c + 1];
      if (std::isnan(x) || std::isnan(t[0]) || x == std::round(x) || y == std::round(y)) continue;
      sum += (x - t[0]) * (x - t[0]) + (y - t[1]) * (y - t[1]);
      ++count;
    }
  }
  ASSERT_GT(count, got.camera_pixels() / 2);
  const double rms_px = std::sqrt(sum / static_cast<double>(count));
  std::printf("Gray-code-only stage: RMS %.4f projector px against the truth over %zu refined pixels\n", rms_px, count);
  EXPECT_LT(rms_px, 0.1);
}

}  // namespace
}  // namespace rfrecon::transport
