// The transport kernels (decode, compress, primal and dual SpMV) against their C++ references, through both entries,
// and the streaming pipeline against the all-at-once reference. Tiny sizes: CI reruns these under oclgrind.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host/capture/protocol.h"
#include "host/cl/binary_manifest.h"
#include "host/cl/device_selection.h"
#include "host/core/errors.h"
#include "host/transport/compute_transport.h"
#include "host/transport/spmv.h"
#include "kernels/common/lanes.h"
#include "kernels/transport/compression.h"
#include "kernels/transport/gray_decode.h"
#include "tests/transport/same_transport.h"
#include "tests/transport/synthetic_capture.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::transport {
namespace {

using testing::expect_same_transport;
using testing::tiny_capture;

constexpr KernelEntry kEntries[] = {KernelEntry::kNdRange, KernelEntry::kSingleWorkItem};

class TransportKernelTest : public ::testing::Test {
 protected:
  // Decode and compression of the tiny capture with dot spacing s and K entries, both entries on every device,
  // equal the C++ reference (same_transport.h). camera_width > 0 crops the frames to that many columns.
  void expect_kernels_match_reference(int spacing, int k, int camera_width = 0);
  cl::ProgramCache programs_;
  std::vector<cl::DeviceContext> devices_ = cl::open_devices("");
};

TEST_F(TransportKernelTest, DecodeAndCompressMatchReferenceWithDotGrid) {
  // K = 4 < s^2 candidates, so the insertion network also drops entries. s = 3: one partial batch of 9 frames;
  // s = 5: 25 frames, full batches of RF_FRAME_BATCH and a partial one unless it divides 25.
  for (const int spacing : {3, 5}) {
    SCOPED_TRACE("dot spacing " + std::to_string(spacing));
    expect_kernels_match_reference(spacing, 4);
  }
}

TEST_F(TransportKernelTest, PixelsPastTheLastWholeGroupOfLanesMatchReference) {
  // 23 x 20 camera pixels: 460 = 57 groups of RF_LANES (8) and 4 more, which the NDRange compression takes one by one.
  static_assert(460 % RF_LANES != 0, "the test needs a partial group of lanes");
  expect_kernels_match_reference(5, 4, 23);
}

TEST_F(TransportKernelTest, AnotherKThanTheParametersHeadersAlsoMatches) {
  expect_kernels_match_reference(5, RF_K + 2);
}

TEST_F(TransportKernelTest, SpacingsOutsideTheKernelsAreRefusedNamingThem) {
  auto setup = testing::setup_for(testing::linearize(tiny_capture(3).frames), {16, 12}, RF_MAX_DOT_SPACING + 1, 4);
  try {
    (void)make_device_accumulator(setup, devices_.front(), programs_, KernelEntry::kNdRange);
    ADD_FAILURE() << "a dot spacing beyond RF_DOT_SPACINGS was accepted";
  } catch (const ProcessingError& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("dot spacing " + std::to_string(RF_MAX_DOT_SPACING + 1)));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("RF_DOT_SPACINGS"));
  }
}

void TransportKernelTest::expect_kernels_match_reference(int spacing, int k, int camera_width) {
  auto capture = tiny_capture(spacing);
  if (camera_width > 0) {
    for (auto& frame : capture.frames) frame = frame.colRange(0, camera_width).clone();
  }
  const auto linear = testing::linearize(capture.frames);
  const auto setup = testing::setup_for(linear, capture.scene.projector_size, spacing, k);
  auto reference = make_reference_accumulator(setup);
  const auto expected = testing::feed_all(*reference, capture.sequence, linear);
  std::size_t valid = 0;
  for (const auto flags : expected.flags) valid += (flags & kFlagValid) != 0 ? 1 : 0;
  ASSERT_GT(valid, expected.camera_pixels() / 2) << "the test scene must light most pixels";
  ASSERT_FALSE(devices_.empty());
  for (auto& device : devices_) {
    for (const auto entry : kEntries) {
      SCOPED_TRACE(cl::describe(device.info()) + (entry == KernelEntry::kNdRange ? " ndrange" : " single"));
      auto accumulator = make_device_accumulator(setup, device, programs_, entry);
      expect_same_transport(testing::feed_all(*accumulator, capture.sequence, linear), expected);
    }
  }
}

// Raw camera samples, 8-bit and 10-bit in 16-bit words with a black level, made linear in the kernels: the same
// transport, to the bit, as the reference given the host's linear frames (capture::linearize_samples), on both
// entries (the single work-item one linearises on the host), and as the reference given the raw frames.
TEST_F(TransportKernelTest, RawSamplesMadeLinearInTheKernelsMatchReferenceExactly) {
  const auto capture = tiny_capture(5);
  struct Camera {
    int depth;
    double black_level;
    double full_scale;
  };
  for (const Camera camera : {Camera{CV_8U, 0.0, 255.0}, Camera{CV_8U, 12.0, 255.0}, Camera{CV_16U, 64.0, 1023.0}}) {
    SCOPED_TRACE(cv::depthToString(camera.depth) + std::string(" black level ") + std::to_string(camera.black_level));
    const capture::SampleMap map{static_cast<float>(camera.black_level),
                                 static_cast<float>(1.0 / (camera.full_scale - camera.black_level))};
    std::vector<cv::Mat> raw;
    std::vector<cv::Mat> linear;
    for (const auto& frame : capture.frames) {  // 8-bit readings rescaled to the camera's range above its black level
      cv::Mat samples;
      frame.convertTo(samples, camera.depth, (camera.full_scale - camera.black_level) / 255.0, camera.black_level);
      raw.push_back(samples);
      linear.push_back(capture::linearize_samples(samples, map));
    }
    auto setup = testing::setup_for(linear, capture.scene.projector_size, 5, 4);
    auto reference = make_reference_accumulator(setup);
    const auto expected = testing::feed_all(*reference, capture.sequence, linear);
    setup.frame_depth = camera.depth;
    setup.samples = map;
    expect_same_transport(testing::feed_all(*make_reference_accumulator(setup), capture.sequence, raw, linear),
                          expected);
    for (auto& device : devices_) {
      for (const auto entry : kEntries) {
        SCOPED_TRACE(cl::describe(device.info()) + (entry == KernelEntry::kNdRange ? " ndrange" : " single"));
        auto accumulator = make_device_accumulator(setup, device, programs_, entry);
        expect_same_transport(testing::feed_all(*accumulator, capture.sequence, raw, linear), expected);
      }
    }
  }
}

// A board binary fixes the kernels' parameters and refuses any other build option (cl::check_options_match_manifest):
// the single work-item programs of a raw 16-bit capture ask for none, so boards take such captures (the host makes the
// frames linear for them); the NDRange programs are built for the raw samples.
TEST(TransportProgramsTest, OnlyNdRangeProgramsAreBuiltForRawSamples) {
  TransportSetup setup;
  setup.frame_depth = CV_16U;
  cl::BinaryManifest board;
  board.file = "board.aocx.json";
  board.parameters = cl::host_kernel_parameters();
  for (const auto& request : transport_programs(setup, KernelEntry::kSingleWorkItem)) {
    EXPECT_NO_THROW(cl::check_options_match_manifest(board, request.options)) << request.kernel_path;
  }
  for (const auto& request : transport_programs(setup, KernelEntry::kNdRange)) {
    EXPECT_THAT(request.options, ::testing::HasSubstr("-DRF_SAMPLE=ushort")) << request.kernel_path;
  }
}

// The divider-free remainder of a window's start by the dot spacing equals x % s for every spacing the kernels
// accept on CPUs (2 to 64) over every start of a projector up to 2^16 pixels wide, and near 2^22, the bound it states.
TEST(CompressionHelpersTest, RemainderBySpacingIsExact) {
  for (int s = 2; s <= 64; ++s) {
    for (int x = 0; x < (1 << 16); ++x) ASSERT_EQ(rf_mod_spacing(x, s), x % s) << "x " << x << " s " << s;
    for (int x = (1 << 22) - 4096; x < (1 << 22); ++x)
      ASSERT_EQ(rf_mod_spacing(x, s), x % s) << "x " << x << " s " << s;
  }
}

// The compression's divider-free row of a projector index equals the integer quotient for every projector width the
// host accepts (up to 16384) over all indices of a projector of 2^24 pixels: stepped through, with every index near
// a multiple of the width, where a float estimate would round across the row boundary.
TEST(CompressionHelpersTest, RowOfAnIndexIsTheExactQuotient) {
  for (const int width : {1, 2, 3, 7, 640, 1023, 1024, 1280, 1920, 4095, 4096, 16383, 16384}) {
    const float inverse = 1.0f / static_cast<float>(width);
    const int pixels = (1 << 24) / width * width;
    for (int row = 0; row < pixels / width; row += 1 + row / 64) {
      for (const int column : {0, 1, width / 2, width - 2, width - 1}) {
        const int q = row * width + std::max(0, std::min(column, width - 1));
        ASSERT_EQ(rf_row_of(q, width, inverse), q / width) << "q " << q << " width " << width;
      }
    }
  }
}

TEST_F(TransportKernelTest, GrayCodeOnlyGivesOneEntryPerRowLikeReference) {
  const auto capture = tiny_capture(0);
  const auto linear = testing::linearize(capture.frames);
  const auto setup = testing::setup_for(linear, capture.scene.projector_size, 0, 2);
  auto reference = make_reference_accumulator(setup);
  const auto expected = testing::feed_all(*reference, capture.sequence, linear);
  for (std::size_t c = 0; c < expected.camera_pixels(); ++c) {
    EXPECT_EQ(expected.indices[2 * c + 1], -1) << "Gray code only fills one slot per row";
  }
  for (auto& device : devices_) {
    for (const auto entry : kEntries) {
      auto accumulator = make_device_accumulator(setup, device, programs_, entry);
      expect_same_transport(testing::feed_all(*accumulator, capture.sequence, linear), expected);
    }
  }
}

// Gray pairs are decoded RF_GRAY_PAIR_BATCH per launch: over one full batch and a partial one, the codes and flags
// equal the reference's (one pair at a time) bit for bit, on both entries.
TEST_F(TransportKernelTest, GrayPairsOverAFullAndAPartialBatchMatchReference) {
  const auto capture = testing::tiny_gray_capture_over_batches();
  if (!capture) GTEST_SKIP() << "RF_GRAY_PAIR_BATCH " << RF_GRAY_PAIR_BATCH << " has no tiny partial batch";
  const auto pairs = std::count_if(capture->sequence.begin(), capture->sequence.end(), [](const auto& pattern) {
    return pattern.kind != capture::pattern_kind::kWhite && pattern.kind != capture::pattern_kind::kBlack &&
           !pattern.inverse;
  });
  ASSERT_GT(pairs, RF_GRAY_PAIR_BATCH);
  ASSERT_NE(pairs % RF_GRAY_PAIR_BATCH, 0);
  const auto linear = testing::linearize(capture->frames);
  const auto setup = testing::setup_for(linear, capture->scene.projector_size, 0, 2);
  auto reference = make_reference_accumulator(setup);
  const auto expected = testing::feed_all(*reference, capture->sequence, linear);
  std::size_t valid = 0;
  for (const auto flags : expected.flags) valid += (flags & kFlagValid) != 0 ? 1 : 0;
  ASSERT_GT(valid, 0u) << "the capture must decode some pixels";
  for (auto& device : devices_) {
    for (const auto entry : kEntries) {
      SCOPED_TRACE(cl::describe(device.info()) + (entry == KernelEntry::kNdRange ? " ndrange" : " single"));
      auto accumulator = make_device_accumulator(setup, device, programs_, entry);
      const auto got = testing::feed_all(*accumulator, capture->sequence, linear);
      EXPECT_EQ(got.pixel_x, expected.pixel_x);
      EXPECT_EQ(got.pixel_y, expected.pixel_y);
      EXPECT_EQ(got.flags, expected.flags);
      expect_same_transport(got, expected);
    }
  }
}

TEST_F(TransportKernelTest, StreamingFromDiskEqualsAllFramesInMemory) {
  const auto capture = tiny_capture(3);
  testing::TempDir dir("streaming");
  const auto manifest = testing::write_capture(dir.path(), capture.scene, capture.sequence, 3, capture.frames);
  const auto linear = testing::linearize(capture.frames);
  const auto setup = testing::setup_for(linear, capture.scene.projector_size, 3, 4);
  auto reference = make_reference_accumulator(setup);
  const auto expected = testing::feed_all(*reference, capture.sequence, linear);
  auto& device = devices_.front();
  const auto run = compute_transport(dir.path(), capture::read_manifest(dir.path()), setup, [&](const auto& s) {
    return make_device_accumulator(s, device, programs_, KernelEntry::kNdRange);
  });
  expect_same_transport(run.transport, expected);
}

// A camera SDK's frames through a callback, read ahead by one or by three threads, give the files' transport bit for
// bit; no reader is a usage error.
TEST_F(TransportKernelTest, FramesFromACallbackOnAnyReaderCountEqualFramesFromFiles) {
  const auto capture = tiny_capture(3);
  testing::TempDir dir("callback_frames");
  const auto manifest = testing::write_capture(dir.path(), capture.scene, capture.sequence, 3, capture.frames);
  const auto setup = testing::setup_for(testing::linearize(capture.frames), capture.scene.projector_size, 3, 4);
  const auto from_files =
      compute_transport_on_devices(dir.path(), manifest, setup, devices_, programs_, KernelEntry::kNdRange, 1);
  std::vector<std::size_t> asked;
  const auto camera = capture::FrameSource::from_callback(
      [&](std::size_t i) {
        asked.push_back(i);
        return capture.frames.at(i);
      },
      "camera SDK");
  for (const int readers : {1, 3}) {
    asked.clear();
    const auto from_camera =
        compute_transport_on_devices(camera, manifest, setup, devices_, programs_, KernelEntry::kNdRange, readers);
    expect_same_transport(from_camera.transport, from_files.transport);
    if (readers == 1) {  // one reader asks in the order of consumption, which is the standard protocol's order
      std::vector<std::size_t> in_order(manifest.frames.size());
      std::iota(in_order.begin(), in_order.end(), std::size_t{0});
      EXPECT_EQ(asked, in_order);
    }
    std::sort(asked.begin(), asked.end());
    EXPECT_EQ(asked.size(), manifest.frames.size()) << "every frame asked for once, readers " << readers;
    EXPECT_TRUE(std::adjacent_find(asked.begin(), asked.end()) == asked.end());
  }
  EXPECT_THROW(compute_transport_on_devices(camera, manifest, setup, devices_, programs_, KernelEntry::kNdRange, 0),
               UsageError);
  auto incomplete = manifest;  // a manifest built in a program is checked as one read from a file
  incomplete.frames.pop_back();
  try {
    (void)compute_transport_on_devices(camera, incomplete, setup, devices_, programs_, KernelEntry::kNdRange);
    ADD_FAILURE() << "an incomplete protocol was accepted";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("camera SDK: incomplete dot grid"));
  }
}

// Gray-code-only captures: the sub-pixel correspondences are computed on the host from the same frames on both
// paths, so they are equal exactly (NaN where none).
TEST_F(TransportKernelTest, GrayCodeOnlyCorrespondencesOnDevicesEqualReferenceExactly) {
  const auto capture = tiny_capture(0);
  testing::TempDir dir("gray_devices");
  testing::write_capture(dir.path(), capture.scene, capture.sequence, 0, capture.frames);
  const auto setup = testing::setup_for(testing::linearize(capture.frames), capture.scene.projector_size, 0, 2);
  const auto reference = compute_transport(dir.path(), capture::read_manifest(dir.path()), setup,
                                           [](const auto& s) { return make_reference_accumulator(s); });
  const auto on_devices = compute_transport_on_devices(dir.path(), capture::read_manifest(dir.path()), setup, devices_,
                                                       programs_, KernelEntry::kNdRange);
  const auto& expected = reference.transport.correspondence;
  const auto& got = on_devices.transport.correspondence;
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    // The kernels' NaN may differ from the host's in its bits.
    if (std::isnan(expected[i])) {
      EXPECT_TRUE(std::isnan(got[i])) << i;
    } else {
      EXPECT_EQ(got[i], expected[i]) << i;
    }
  }
  std::size_t fractional = 0;
  for (const float xy : expected) fractional += !std::isnan(xy) && xy != std::round(xy) ? 1 : 0;
  EXPECT_GT(fractional, 0u) << "the tiny capture must have refined correspondences";
}

TEST_F(TransportKernelTest, PrimalAndDualMatchReferenceAndDenseProduct) {
  const auto transport = testing::tiny_reference_transport(3, 4);
  const auto [light_p, light_c] = testing::random_lights(transport);

  // Dense double-precision products: the references must equal them to float rounding (1e-5 relative of a sum of
  // at most K or a few dozen positive terms of similar size).
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(transport.camera_pixels(), transport.projector_pixels());
  for (std::size_t slot = 0; slot < transport.indices.size(); ++slot) {
    if (transport.indices[slot] >= 0) dense(slot / transport.k(), transport.indices[slot]) += transport.weights[slot];
  }
  const Eigen::VectorXd primal_dense =
      dense * Eigen::Map<const Eigen::VectorXf>(light_p.data(), light_p.size()).cast<double>();
  const Eigen::VectorXd dual_dense =
      dense.transpose() * Eigen::Map<const Eigen::VectorXf>(light_c.data(), light_c.size()).cast<double>();
  const auto primal = primal_reference(transport, light_p);
  const auto dual = dual_reference(transport, light_c);
  for (std::size_t c = 0; c < primal.size(); ++c) EXPECT_NEAR(primal[c], primal_dense[c], 1e-5 * primal_dense[c]);
  for (std::size_t q = 0; q < dual.size(); ++q) EXPECT_NEAR(dual[q], dual_dense[q], 1e-5 * dual_dense[q]);
  EXPECT_GT(dual_dense.maxCoeff(), 0.1) << "the dual image must not be empty";

  // The kernels sum in the references' order with contraction off: bit for bit.
  const auto transposed = transpose(transport);
  for (auto& device : devices_) {
    for (const auto entry : kEntries) {
      EXPECT_EQ(primal_opencl(device, programs_, entry, transport, light_p), primal);
      EXPECT_EQ(dual_opencl(device, programs_, entry, transposed, light_c), dual);
    }
  }
}

}  // namespace
}  // namespace rfrecon::transport
