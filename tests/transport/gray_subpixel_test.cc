// Which pixels of Gray-code-only captures are decoded (host/transport/gray_decision.h) and their sub-pixel
// correspondences (host/transport/gray_subpixel.h), against a known smooth camera -> projector mapping with the
// code's gradient along camera x, along camera y and diagonal, with and without noise, sharp and blurred; single
// pixels built bit by bit; and the transport stage leaving dot-grid correspondences alone.
#include "host/transport/gray_subpixel.h"

#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "host/capture/protocol.h"
#include "host/transport/compute_transport.h"
#include "host/transport/gray_decision.h"
#include "host/transport/pixel_outcomes.h"
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

// Camera pixel (u, v) sees projector point map(u, v) through a Gaussian blur of `blur` projector px, on a surface
// whose reflectance varies from 0.35 to 0.85 across the image, plus ambient light 0.03 and Gaussian noise of `noise`.
Capture render(const ProjectorFromCamera& map, double noise, unsigned seed, double blur = 0.5) {
  Capture capture;
  capture.sequence = capture::make_protocol({kProjector, 0});
  capture.truth = cv::Mat(kCamera, CV_64FC2);
  std::vector<cv::Mat> light;
  for (const auto& pattern : capture.sequence) light.push_back(capture::render_pattern(pattern, {kProjector, 0}));
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
      const int reach = 2 + static_cast<int>(std::ceil(3.0 * blur));
      for (std::size_t f = 0; f < light.size(); ++f) {
        double lit = 0.0;
        for (int qy = std::max(y0 - reach, 0); qy <= std::min(y0 + reach, kProjector.height - 1); ++qy) {
          for (int qx = std::max(x0 - reach, 0); qx <= std::min(x0 + reach, kProjector.width - 1); ++qx) {
            if (light[f].at<unsigned char>(qy, qx) == 0) continue;
            lit += gaussian_mass(xy.x, blur, qx - 0.5, qx + 0.5) * gaussian_mass(xy.y, blur, qy - 0.5, qy + 0.5);
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

// The host's side of the transport stage on Gray-code-only frames held in memory (linear CV_32F), as
// compute_transport runs it: the decision (unless `decide` is false: the accumulators' flags alone), then the fit.
GrayDecisionCounts decide_and_refine(CompressedTransport& transport, const std::vector<capture::Pattern>& sequence,
                                     const std::vector<cv::Mat>& frames, bool decide = true) {
  std::array<cv::Mat, 2> white_black;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    if (sequence[i].kind == capture::pattern_kind::kWhite) white_black[0] = frames[i];
    if (sequence[i].kind == capture::pattern_kind::kBlack) white_black[1] = frames[i];
  }
  GrayDecision decision(white_black[0], white_black[1]);
  GraySubpixel subpixel(transport.setup.camera_size);
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const auto& pattern = sequence[i];
    if (pattern.kind != capture::pattern_kind::kGrayColumn && pattern.kind != capture::pattern_kind::kGrayRow) continue;
    if (pattern.inverse) continue;
    const GrayAxis axis = pattern.kind == capture::pattern_kind::kGrayColumn ? GrayAxis::kColumns : GrayAxis::kRows;
    // The inverse follows its pattern.
    decision.add_gray_pair(axis, gray_bit_mask(transport.setup, axis, pattern.bit), frames[i], frames[i + 1]);
    subpixel.add_gray_pair(axis, frames[i], frames[i + 1]);
  }
  const GrayDecisionCounts counts = decide ? decision.decide(transport) : GrayDecisionCounts{};
  subpixel.refine(transport);
  return counts;
}

Refined refine(const Capture& capture) {
  auto accumulator = make_reference_accumulator(testing::setup_for(capture.frames, kProjector, 0, 1));
  Refined r{testing::feed_all(*accumulator, capture.sequence, capture.frames)};
  decide_and_refine(r.transport, capture.sequence, capture.frames);
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
      const double ix = r.transport.pixel_x[c] - truth[0], iy = r.transport.pixel_y[c] - truth[1];
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

// The fraction of pixels at least 4 px from the image border that have a correspondence.
double interior_decoded_fraction(const CompressedTransport& transport, bool by_flags) {
  std::size_t interior = 0, decoded = 0;
  for (int v = 4; v < kCamera.height - 4; ++v) {
    for (int u = 4; u < kCamera.width - 4; ++u) {
      const std::size_t c = static_cast<std::size_t>(v) * kCamera.width + u;
      ++interior;
      decoded +=
          (by_flags ? (transport.flags[c] & kFlagValid) != 0 : !std::isnan(transport.correspondence[2 * c])) ? 1 : 0;
    }
  }
  return static_cast<double>(decoded) / static_cast<double>(interior);
}

// A projector blurred over 1.2 px (as on the real captures of ../shared/data/procam-graycode, where the finest bit
// keeps about a quarter of the contrast) with 1 DN of noise: the pixels a column or row boundary crosses have one bit
// whose pattern and inverse are nearly equal. OpenCV's rule (every bit above a fixed 5 DN) leaves them undecoded, a
// lattice (measured: 71 to 86 % of the interior decoded); deciding each bit against the pixel's own noise, with one
// undecided bit placed between its two adjacent codes, decodes all of them at the accuracy of the others.
TEST(GrayDecisionTest, BlurredBoundaryPixelsAreDecodedBetweenAdjacentCodes) {
  for (const auto& mapping : kMappings) {
    const Capture capture = render(mapping.map, 0.004, 11, 1.2);
    auto setup = testing::setup_for(capture.frames, kProjector, 0, 1);
    setup.thresholds.white = 5.0f / 255.0f;
    CompressedTransport fixed = testing::feed_all(*make_reference_accumulator(setup), capture.sequence, capture.frames);
    const double fixed_fraction = interior_decoded_fraction(fixed, true);

    CompressedTransport decided =
        testing::feed_all(*make_reference_accumulator(setup), capture.sequence, capture.frames);
    const GrayDecisionCounts counts = decide_and_refine(decided, capture.sequence, capture.frames);
    const double fraction = interior_decoded_fraction(decided, false);
    double sum = 0.0;
    std::size_t count = 0;
    for (int v = 4; v < kCamera.height - 4; ++v) {
      for (int u = 4; u < kCamera.width - 4; ++u) {
        const std::size_t c = static_cast<std::size_t>(v) * kCamera.width + u;
        const float x = decided.correspondence[2 * c], y = decided.correspondence[2 * c + 1];
        const cv::Vec2d truth = capture.truth.at<cv::Vec2d>(v, u);
        // Pixels seeing the projector's outermost pixel or beyond it take the border code, whatever the decoder.
        const bool inside = truth[0] >= 1.0 && truth[1] >= 1.0 && truth[0] <= kProjector.width - 2.0 &&
                            truth[1] <= kProjector.height - 2.0;
        if (std::isnan(x) || !inside) continue;
        sum += (x - truth[0]) * (x - truth[0]) + (y - truth[1]) * (y - truth[1]);
        ++count;
      }
    }
    const double rms_px = std::sqrt(sum / static_cast<double>(count));
    std::printf(
        "%s, blur 1.2 px: %.1f%% of interior pixels decoded (fixed 5 DN rule %.1f%%), %zu between codes, "
        "rms %.4f px\n",
        mapping.name, 100.0 * fraction, 100.0 * fixed_fraction, counts.between_codes, rms_px);
    EXPECT_LT(fixed_fraction, 0.9) << mapping.name << ": the fixed rule must show the lattice for this test to mean";
    EXPECT_GT(fraction, 0.99) << mapping.name;
    EXPECT_GT(counts.between_codes, 0u) << mapping.name;
    EXPECT_EQ(counts.decoded(),
              static_cast<std::size_t>(std::count_if(decided.flags.begin(), decided.flags.end(), [](std::uint8_t f) {
                return (f & kFlagValid) != 0 && (f & kFlagNoSignal) == 0;
              })));
    EXPECT_LT(rms_px, 0.1) << mapping.name;
  }
}

// Ten pixels of a 12 x 2 projector's capture (4 column bits: codes 12 to 15 lie past its edge), built bit by bit:
// white 0.5 and black 0.02 (pixel 8: 0.025, under the noise threshold), noiseless, column bits 0.2 apart but where
// stated, the row bit clear, a 0.002 floor so that the 2 % rule (0.0096) is the one that acts. Each pixel's decision,
// position, T entry and outcome follow by construction.
// Each outcome once, with the pixels rotated along the row by every shift: the decision takes four pixels at a time
// and the rest of a row one by one, so each pixel is decided both ways.
class GrayDecisionRotationTest : public ::testing::TestWithParam<int> {};

TEST_P(GrayDecisionRotationTest, OnePixelPerOutcome) {
  constexpr int kPixels = 10;
  // Built pixel c lies in camera column at(c).
  const auto at = [](std::size_t c) { return (c + static_cast<std::size_t>(GetParam())) % kPixels; };
  const cv::Size camera{kPixels, 1};
  const cv::Size projector{12, 2};
  TransportSetup setup;
  setup.camera_size = camera;
  setup.projector_size = projector;
  setup.entries_per_pixel = 1;
  setup.thresholds.white = 0.002f;
  setup.thresholds = resolve_thresholds(setup.thresholds, 8);
  CompressedTransport transport = make_empty_transport(setup);
  cv::Mat white(camera, CV_32F, cv::Scalar(0.5)), black(camera, CV_32F, cv::Scalar(0.02));
  white.at<float>(0, static_cast<int>(at(8))) = 0.025f;
  transport.flags[at(9)] = kFlagShadow;
  GrayDecision decision(white, black);
  const auto gray = [](std::uint32_t code) { return code ^ (code >> 1); };
  // The accumulators' code (each bit by its sign) and the masks of its undecided bits, with their pattern - inverse:
  // 1: column 5's least significant bit at +0.008 (lit fraction 0.508: column 5 lit, 4 dark); 2: column 8 with mask 2
  // undecided, whose flip gives column 11, not adjacent; 3: column 6 with two undecided bits; 5: column 12 with its
  // least significant bit undecided (flipped: 13), both past the edge; 6 and 7: column 11 and column 12 with mask 4
  // undecided (each other's flip): column 12 is never lit, so both lie on column 11.
  struct Built {
    std::uint32_t column;
    std::uint32_t undecided_masks;
    float difference;
  };
  const Built built[kPixels] = {{5, 0, 0},        {5, 1, 0.008f},   {8, 2, -0.0005f},  {6, 6, 0.0005f}, {13, 0, 0},
                                {12, 1, 0.0005f}, {11, 4, 0.0005f}, {12, 4, -0.0005f}, {5, 0, 0},       {5, 0, 0}};
  for (int bit = 0; bit < 4; ++bit) {
    const std::uint32_t mask = gray_bit_mask(setup, GrayAxis::kColumns, bit);
    cv::Mat pattern(camera, CV_32F), inverse(camera, CV_32F);
    for (std::size_t c = 0; c < kPixels; ++c) {
      const bool set = (gray(built[c].column) & mask) != 0;
      const float difference = (built[c].undecided_masks & mask) != 0 ? built[c].difference : (set ? 0.2f : -0.2f);
      const int u = static_cast<int>(at(c));
      const float middle = 0.5f * (white.at<float>(0, u) + black.at<float>(0, u));
      pattern.at<float>(0, u) = middle + 0.5f * difference;
      inverse.at<float>(0, u) = middle - 0.5f * difference;
    }
    decision.add_gray_pair(GrayAxis::kColumns, mask, pattern, inverse);
  }
  const cv::Mat mean = 0.5 * (white + black);
  decision.add_gray_pair(GrayAxis::kRows, gray_bit_mask(setup, GrayAxis::kRows, 0), mean - 0.1, mean + 0.1);
  for (std::size_t c = 0; c < kPixels; ++c) transport.pixel_x[at(c)] = built[c].column;

  const GrayDecisionCounts counts = decision.decide(transport);
  EXPECT_EQ(counts.lit, 9u);
  EXPECT_EQ(counts.decided, 3u);  // 0, 6, 7
  EXPECT_EQ(counts.between_codes, 1u);
  EXPECT_EQ(counts.undecided, 2u);
  EXPECT_EQ(counts.out_of_range, 2u);
  EXPECT_EQ(counts.no_signal, 1u);
  const PixelOutcome outcomes[kPixels] = {
      PixelOutcome::kDecoded,    PixelOutcome::kDecoded,    PixelOutcome::kUndecided, PixelOutcome::kUndecided,
      PixelOutcome::kOutOfRange, PixelOutcome::kOutOfRange, PixelOutcome::kDecoded,   PixelOutcome::kDecoded,
      PixelOutcome::kNoSignal,   PixelOutcome::kShadow};
  const float columns[kPixels] = {5.0f, 4.0f + (0.5f + 0.5f * 0.008f / 0.48f), NAN, NAN, NAN, NAN, 11.0f, 11.0f, NAN,
                                  NAN};
  const std::int32_t entries[kPixels] = {5, 5, -1, -1, -1, -1, 11, 11, -1, -1};
  for (std::size_t c = 0; c < kPixels; ++c) {
    const std::size_t u = at(c);
    EXPECT_EQ(pixel_outcome(transport, u), outcomes[c]) << "pixel " << c;
    if (std::isnan(columns[c])) {
      EXPECT_TRUE(std::isnan(transport.correspondence[2 * u])) << "pixel " << c;
    } else {
      EXPECT_NEAR(transport.correspondence[2 * u], columns[c], 1e-5f) << "pixel " << c;
      EXPECT_FLOAT_EQ(transport.correspondence[2 * u + 1], 0.0f) << "pixel " << c;
      EXPECT_NE(transport.flags[u] & kFlagValid, 0) << "pixel " << c;
    }
    EXPECT_EQ(transport.indices[u], entries[c]) << "pixel " << c;
  }
  for (const std::size_t c : {2u, 3u}) EXPECT_NE(transport.flags[at(c)] & kFlagLowContrast, 0) << "pixel " << c;
  for (const std::size_t c : {2u, 3u, 4u, 5u, 9u}) EXPECT_EQ(transport.flags[at(c)] & kFlagValid, 0) << "pixel " << c;
  // T's single entry per row and the direct energy: white - black.
  EXPECT_FLOAT_EQ(transport.weights[at(1)], 0.48f);
  EXPECT_FLOAT_EQ(transport.direct_energy[at(1)], 0.48f);
  EXPECT_FLOAT_EQ(transport.direct_energy[at(8)], 0.0f);
  EXPECT_NE(transport.flags[at(8)] & kFlagNoSignal, 0);
  EXPECT_NE(transport.flags[at(4)] & kFlagOutOfRange, 0);
}

INSTANTIATE_TEST_SUITE_P(Shifts, GrayDecisionRotationTest, ::testing::Range(0, 10));

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
    if (dot_spacing == 0) decide_and_refine(in_memory_, sequence, linear);
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
  CompressedTransport in_memory_;  // the same capture fed in memory (Gray-code-only: decided and refined)
};

TEST_F(GraySubpixelStageTest, DotGridCapturesKeepTheirCentroidsBitForBit) {
  const CompressedTransport got = staged(scene(), 5);
  EXPECT_EQ(got.k(), 4) << "a capture with dots keeps the K entries asked for";
  ASSERT_EQ(got.correspondence.size(), in_memory_.correspondence.size());
  EXPECT_EQ(0, std::memcmp(got.correspondence.data(), in_memory_.correspondence.data(),
                           got.correspondence.size() * sizeof(float)));
}

TEST_F(GraySubpixelStageTest, GrayCodeOnlyCapturesGetTheRefinedCorrespondences) {
  const CompressedTransport got = staged(scene(), 0);
  EXPECT_EQ(0, std::memcmp(got.correspondence.data(), in_memory_.correspondence.data(),
                           got.correspondence.size() * sizeof(float)));
  // One entry per pixel, not the K = 4 asked for: the decoded pixel's, the first of the in-memory transport's K.
  ASSERT_EQ(got.k(), 1);
  ASSERT_EQ(got.indices.size(), got.camera_pixels());
  std::size_t entries = 0;
  for (std::size_t c = 0; c < got.camera_pixels(); ++c) {
    EXPECT_EQ(got.indices[c], in_memory_.indices[c * in_memory_.k()]) << c;
    EXPECT_EQ(got.weights[c], in_memory_.weights[c * in_memory_.k()]) << c;
    for (int k = 1; k < in_memory_.k(); ++k) EXPECT_LT(in_memory_.indices[c * in_memory_.k() + k], 0) << c;
    entries += got.indices[c] >= 0 ? 1 : 0;
  }
  EXPECT_GT(entries, got.camera_pixels() / 2);
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
