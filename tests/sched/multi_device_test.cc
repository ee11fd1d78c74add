// Kernels through the scheduler: several devices give the single-device result bit for bit (each output pixel is
// computed by one work-item, the same arithmetic in the same order, wherever its tile runs), with and without a
// failing or hung device. Tiny sizes: CI reruns these under oclgrind, which has one device (two-device cases skip).
#include <cstdlib>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "host/capture/protocol.h"
#include "host/cl/device_selection.h"
#include "host/transport/compute_transport.h"
#include "host/transport/spmv_on_devices.h"
#include "tests/common/devices.h"
#include "tests/sched/test_support.h"
#include "tests/transport/synthetic_capture.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::sched {
namespace {

using rfrecon::testing::kNeedTwoDevices;

using transport::KernelEntry;
namespace testing = transport::testing;

// Byte equality, so that NaN correspondences compare equal to NaN and -0 differs from +0.
template <typename T>
void expect_identical(const std::vector<T>& got, const std::vector<T>& expected, const char* what) {
  ASSERT_EQ(got.size(), expected.size()) << what;
  EXPECT_EQ(std::memcmp(got.data(), expected.data(), got.size() * sizeof(T)), 0) << what << " differs";
}

void expect_identical(const transport::CompressedTransport& got, const transport::CompressedTransport& expected) {
  expect_identical(got.indices, expected.indices, "indices");
  expect_identical(got.weights, expected.weights, "weights");
  expect_identical(got.correspondence, expected.correspondence, "correspondence");
  expect_identical(got.pixel_x, expected.pixel_x, "pixel_x");
  expect_identical(got.pixel_y, expected.pixel_y, "pixel_y");
  expect_identical(got.flags, expected.flags, "flags");
  expect_identical(got.direct_energy, expected.direct_energy, "direct_energy");
}

using rfrecon::testing::hangs_untimed;
using rfrecon::testing::kHangsUntimed;
using rfrecon::testing::ScopedEnv;

struct Capture {
  int dot_spacing = 3;
  testing::PlaneScene scene;
  std::vector<capture::Pattern> sequence;
  std::vector<cv::Mat> frames;
};

Capture tiny_capture(int dot_spacing = 3) {
  testing::SceneOptions options;
  options.camera_size = {24, 20};
  options.projector_size = {16, 12};
  Capture capture{dot_spacing, testing::make_plane_scene(options), {}, {}};
  capture.sequence = capture::make_protocol({options.projector_size, dot_spacing});
  capture.frames = testing::render_frames(capture.scene, capture.sequence, dot_spacing, 1.0, 7);
  return capture;
}

class MultiDeviceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(devices_.empty());
    ::unsetenv(kInjectFaultEnv);
    options_.faults = FaultPolicy();
    options_.granularity = 16;
    options_.first_tile_items = 32;
    options_.max_tile_items = 64;  // several tiles on the 480 camera / 192 projector pixels
  }

  transport::CompressedTransport reference_transport() {
    const auto linear = testing::linearize(capture_.frames);
    auto accumulator = transport::make_reference_accumulator(
        testing::setup_for(linear, capture_.scene.projector_size, capture_.dot_spacing, 4));
    return testing::feed_all(*accumulator, capture_.sequence, linear);
  }

  // The dual product on every device with `faults` injected, checked against one device. Kernels built beforehand
  // and one-pixel tiles (192 of them, each a kernel launch and a read): both devices start at once and each gets a
  // first tile long before the other could have taken them all, even on a loaded machine. Should one device still
  // take every tile first (then nothing fails and the image must still be right), a few runs give the other its tile.
  transport::ProductRun dual_with_fault(const char* faults) {
    const auto t = reference_transport();
    const auto transposed = transport::transpose(t);
    const std::vector<float> light_c(t.camera_pixels(), 1.0f);
    for (auto& device : devices_) programs_.get(device, "transport/spmv.cl");
    options_.granularity = 1;
    options_.first_tile_items = 1;
    options_.max_tile_items = 1;
    options_.faults = FaultPolicy::parse(faults);
    const auto expected = transport::dual_opencl(devices_[0], programs_, KernelEntry::kNdRange, transposed, light_c);
    transport::ProductRun dual;
    for (int attempt = 0; attempt < 5 && dual.report.failures.empty(); ++attempt) {
      dual = dual_on_devices(devices_, programs_, KernelEntry::kNdRange, transposed, light_c, options_);
      expect_identical(dual.image, expected, "dual");
    }
    return dual;
  }

  Capture capture_ = tiny_capture();
  cl::ProgramCache programs_;
  std::vector<cl::DeviceContext> devices_ = cl::open_devices("");
  Options options_;
};

TEST_F(MultiDeviceTest, PoclExposesTwoDevicesWhenAsked) {
  const char* pocl = std::getenv("POCL_DEVICES");
  if (pocl == nullptr || std::string(pocl) != "pthread pthread") GTEST_SKIP() << "POCL_DEVICES is not two pthread";
  std::size_t pocl_devices = 0;
  for (const auto& device : devices_) pocl_devices += device.info().platform_name.find("Portable") == 0 ? 1 : 0;
  EXPECT_EQ(pocl_devices, 2u);
}

TEST_F(MultiDeviceTest, PrimalAndDualEqualTheSingleDeviceProducts) {
  const auto t = reference_transport();
  const auto transposed = transport::transpose(t);
  std::mt19937 random(5);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<float> light_p(t.projector_pixels());
  std::vector<float> light_c(t.camera_pixels());
  for (auto& value : light_p) value = uniform(random);
  for (auto& value : light_c) value = uniform(random);
  for (const auto entry : {KernelEntry::kNdRange, KernelEntry::kSingleWorkItem}) {
    SCOPED_TRACE(entry == KernelEntry::kNdRange ? "ndrange" : "single");
    const auto primal = primal_on_devices(devices_, programs_, entry, t, light_p, options_);
    const auto dual = dual_on_devices(devices_, programs_, entry, transposed, light_c, options_);
    expect_identical(primal.image, transport::primal_opencl(devices_[0], programs_, entry, t, light_p), "primal");
    expect_identical(dual.image, transport::dual_opencl(devices_[0], programs_, entry, transposed, light_c), "dual");
    EXPECT_EQ(primal.report.items, t.camera_pixels());
    EXPECT_EQ(dual.report.stage, "dual");
  }
}

TEST_F(MultiDeviceTest, DualSurvivesAFailingDevice) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  const auto dual = dual_with_fault("0:1");
  ASSERT_EQ(dual.report.failures.size(), 1u);
  EXPECT_TRUE(dual.report.devices[0].failed);
  EXPECT_FALSE(dual.report.failures[0].timed_out);
}

TEST_F(MultiDeviceTest, DualSurvivesAHungDevice) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  options_.tile_timeout_s = 0.5;
  const auto dual = dual_with_fault("hang:1:1");
  ASSERT_EQ(dual.report.failures.size(), 1u);
  EXPECT_TRUE(dual.report.devices[1].failed);
  EXPECT_TRUE(dual.report.failures[0].timed_out);
}

class TransportOnDevicesTest : public MultiDeviceTest {
 protected:
  // Dot spacing 12: 144 dot frames, 9 launches of the default RF_FRAME_BATCH (16), 11 steps in all.
  void SetUp() override {
    MultiDeviceTest::SetUp();
    capture_ = tiny_capture(12);
    testing::write_capture(dir_.path(), capture_.scene, capture_.sequence, capture_.dot_spacing, capture_.frames);
    setup_.entries_per_pixel = 4;
  }

  transport::TransportRun on_devices() {
    return transport::compute_transport_on_devices(dir_.path(), capture::read_manifest(dir_.path()), setup_, devices_,
                                                   programs_, KernelEntry::kNdRange);
  }
  transport::CompressedTransport on_first_device() {
    return transport::compute_transport(dir_.path(), capture::read_manifest(dir_.path()), setup_,
                                        [&](const transport::TransportSetup& s) {
                                          return make_device_accumulator(s, devices_[0], programs_,
                                                                         KernelEntry::kNdRange);
                                        })
        .transport;
  }

  // Device 1 fails or hangs (`faults`) at its 8th block step: it owns 1 to 7 of the 8 blocks, so that is in a later
  // step than the first and within the 11 steps, and the replay has frames to re-read: the transport is still the
  // single-device one, and the failure is reported.
  // Before a short tile timeout: a kernel build slower than it (a loaded machine) would be taken as a hang, and its
  // thread, still building, would outlive the objects of the stage (docs/scheduler.md, "What it cannot fence").
  void build_kernels() {
    for (auto& device : devices_) {
      programs_.get(device, "transport/decode.cl");
      programs_.get(device, "transport/compress.cl", transport::transport_build_options(setup_.entries_per_pixel));
    }
  }

  void expect_blocks_replayed_after(const char* faults, bool timed_out) {
    build_kernels();
    const ScopedEnv injected(kInjectFaultEnv, faults);
    const auto run = on_devices();
    expect_identical(run.transport, on_first_device());
    std::vector<DeviceFailure> failures;
    std::size_t replayed = 0;
    for (const auto& stage : run.schedule) {
      failures.insert(failures.end(), stage.failures.begin(), stage.failures.end());
      replayed += stage.devices[0].replayed_items;
    }
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0].device, 1u);
    EXPECT_EQ(failures[0].timed_out, timed_out);
    EXPECT_GT(replayed, 0u);
  }

  testing::TempDir dir_{"sched_transport"};
  transport::TransportSetup setup_;
};

// Each block gets one call per kernel launch (RF_FRAME_BATCH frames), not one per frame: a stage's block steps are
// its launches times the blocks.
std::size_t launches(const std::vector<capture::Pattern>& sequence, const std::string& stage) {
  std::size_t frames = 0;
  for (const auto& pattern : sequence) {
    const bool gray =
        pattern.kind == capture::pattern_kind::kGrayColumn || pattern.kind == capture::pattern_kind::kGrayRow;
    if (stage == "decode" ? gray : pattern.kind == capture::pattern_kind::kDot) ++frames;
  }
  return stage == "finalize" ? 1 : (frames + RF_FRAME_BATCH - 1) / RF_FRAME_BATCH;
}

TEST_F(TransportOnDevicesTest, EqualsTheSingleDeviceTransport) {
  const auto run = on_devices();
  expect_identical(run.transport, on_first_device());
  ASSERT_EQ(run.schedule.size(), 3u);
  EXPECT_EQ(run.schedule.front().stage, "decode");
  const std::size_t blocks = devices_.size() == 1 ? 1 : transport::kBlocksPerDevice * devices_.size();
  for (const auto& stage : run.schedule) {
    std::size_t rows_done = 0, block_steps = 0;
    for (const auto& device : stage.devices) {
      rows_done += device.items;
      block_steps += device.tiles;
    }
    EXPECT_EQ(rows_done, stage.items);
    EXPECT_EQ(block_steps, blocks * launches(capture_.sequence, stage.stage)) << stage.stage;
    EXPECT_TRUE(stage.failures.empty());
  }
}

TEST_F(TransportOnDevicesTest, FailedDeviceBlocksAreReplayedElsewhere) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  expect_blocks_replayed_after("1:8", false);
}

TEST_F(TransportOnDevicesTest, HungDeviceBlocksAreReplayedElsewhere) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  const ScopedEnv timeout(kTileTimeoutEnv, "0.5");
  expect_blocks_replayed_after("hang:1:8", true);
}

TEST_F(TransportOnDevicesTest, EveryDeviceFailingIsAClearOpenClError) {
  const ScopedEnv faults(kInjectFaultEnv, "*:2");
  EXPECT_THROW(on_devices(), AllDevicesFailed);
}

TEST_F(TransportOnDevicesTest, EveryDeviceHangingIsAClearOpenClError) {
  if (hangs_untimed(devices_)) GTEST_SKIP() << kHangsUntimed;
  build_kernels();
  const ScopedEnv timeout(kTileTimeoutEnv, "0.5");
  const ScopedEnv faults(kInjectFaultEnv, "hang:*:2");
  EXPECT_THROW(on_devices(), AllDevicesFailed);
}

}  // namespace
}  // namespace rfrecon::sched
