// The transport stage (decode + compression into the compressed T) on two devices, one on the single work-item
// entries and one on the NDRange entries, as a CPU + FPGA run would be: the result is the one-device result within
// the kernel tests' tolerance. Needs two devices: run by transport_two_pocl_devices with POCL_DEVICES="pthread
// pthread"; skipped where only one device exists. And an earlier transport's memory reused, on one device and on two.

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "host/capture/protocol.h"
#include "host/cl/device_selection.h"
#include "host/transport/compute_transport.h"
#include "kernels/common/params.h"
#include "tests/common/devices.h"
#include "tests/transport/same_transport.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon::transport {
namespace {

using testing::expect_same_transport;  // the tolerance of transport_kernel_test (tests/transport/same_transport.h)

// A 48 x 40 camera's capture of a plane with 4 x 4 dots, written into dir.
void write_plane_capture(const std::filesystem::path& dir) {
  testing::SceneOptions options;
  options.camera_size = {48, 40};
  options.projector_size = {32, 24};
  const auto scene = testing::make_plane_scene(options);
  const auto sequence = capture::make_protocol({options.projector_size, 4});
  testing::write_capture(dir, scene, sequence, 4, testing::render_frames(scene, sequence, 4, 1.0, 11));
}

// K = 4 < 16 dot candidates: the compression also drops entries.
TransportSetup setup_with_k4() {
  TransportSetup setup;
  setup.entries_per_pixel = 4;
  return setup;
}

TEST(TransportDevicesTest, SingleWorkItemDeviceAndNdRangeDeviceGiveTheOneDeviceTransport) {
  auto devices = cl::open_devices("all");
  if (devices.size() < 2) GTEST_SKIP() << rfrecon::testing::kNeedTwoDevices;
  devices.erase(devices.begin() + 2, devices.end());
  testing::TempDir dir("transport_devices");
  write_plane_capture(dir.path());
  cl::ProgramCache programs;
  const auto run = [&](std::vector<cl::DeviceContext>& on, const cl::EntryChoice& entries) {
    return compute_transport_on_devices(dir.path(), capture::read_manifest(dir.path()), setup_with_k4(), on, programs,
                                        entries);
  };
  std::vector<cl::DeviceContext> one{devices.front()};
  const auto expected = run(one, cl::KernelEntry::kNdRange).transport;
  std::size_t valid = 0;
  for (const auto flags : expected.flags) valid += (flags & kFlagValid) != 0 ? 1 : 0;
  ASSERT_GT(valid, expected.camera_pixels() / 2) << "the test scene must light most pixels";

  // Which device takes which row block is first-touch, a race past each device's first block: the run is repeated
  // until both devices delivered rows in every stage; every run must match, and one must have used both devices.
  const cl::EntryChoice mixed({cl::KernelEntry::kSingleWorkItem, cl::KernelEntry::kNdRange});
  const auto both_delivered = [](const TransportRun& got) {
    for (const auto& stage : got.schedule) {
      for (const auto& device : stage.devices) {
        if (device.items == 0) return false;
      }
    }
    return !got.schedule.empty();
  };
  constexpr int kAttempts = 20;
  bool split = false;
  for (int attempt = 0; attempt < kAttempts && !split; ++attempt) {
    SCOPED_TRACE("attempt " + std::to_string(attempt));
    const auto got = run(devices, mixed);
    expect_same_transport(got.transport, expected);
    for (const auto& stage : got.schedule) {
      ASSERT_EQ(stage.devices.size(), 2u);
      EXPECT_EQ(stage.devices[0].entry, "single") << stage.stage;
      EXPECT_EQ(stage.devices[1].entry, "ndrange") << stage.stage;
      EXPECT_TRUE(stage.failures.empty()) << stage.stage;
    }
    if (::testing::Test::HasFailure()) break;
    split = both_delivered(got);
  }
  EXPECT_TRUE(split) << "no run of " << kAttempts << " gave rows to both devices";
}

// A scanner's loop hands each scan the transport of the one before: the result lies in that memory (one block's
// accumulator state on one device; the stacked blocks on two, in transport_two_pocl_devices) and equals the one
// computed in new memory, whatever the earlier transport held (the NDRange kernels' first batch overwrites every
// row, at the parameters' K and at another); a too small one grows.
TEST(TransportDevicesTest, AnEarlierTransportsMemoryIsReusedAndTheResultIsTheSame) {
  auto devices = cl::open_devices("all");
  devices.erase(devices.begin() + std::min<std::ptrdiff_t>(2, static_cast<std::ptrdiff_t>(devices.size())),
                devices.end());
  testing::TempDir dir("transport_storage");
  write_plane_capture(dir.path());
  cl::ProgramCache programs;
  for (const int k : {RF_K, 4}) {
    SCOPED_TRACE("K = " + std::to_string(k));
    TransportSetup setup;
    setup.entries_per_pixel = k;
    const auto run = [&](CompressedTransport storage) {
      return compute_transport_on_devices(dir.path(), capture::read_manifest(dir.path()), setup, devices, programs, {},
                                          kDefaultReaders, std::move(storage))
          .transport;
    };
    const CompressedTransport expected = run({});
    ASSERT_GT(std::count(expected.indices.begin(), expected.indices.end(), -1), 0)
        << "the test needs empty slots, to show that the earlier transport's entries are gone";

    CompressedTransport earlier = expected;  // the same sizes, other contents
    std::fill(earlier.indices.begin(), earlier.indices.end(), 7);
    std::fill(earlier.weights.begin(), earlier.weights.end(), 0.5f);
    std::fill(earlier.correspondence.begin(), earlier.correspondence.end(), 3.0f);
    std::fill(earlier.pixel_x.begin(), earlier.pixel_x.end(), 5U);
    std::fill(earlier.pixel_y.begin(), earlier.pixel_y.end(), 6U);
    std::fill(earlier.flags.begin(), earlier.flags.end(), std::uint8_t{0xFF});
    std::fill(earlier.direct_energy.begin(), earlier.direct_energy.end(), 9.0f);
    const std::int32_t* indices_memory = earlier.indices.data();
    const float* weights_memory = earlier.weights.data();
    const float* correspondence_memory = earlier.correspondence.data();
    const std::uint8_t* flags_memory = earlier.flags.data();
    const CompressedTransport got = run(std::move(earlier));
    expect_same_transport(got, expected);
    EXPECT_EQ(got.indices.data(), indices_memory);
    EXPECT_EQ(got.weights.data(), weights_memory);
    EXPECT_EQ(got.correspondence.data(), correspondence_memory);
    EXPECT_EQ(got.flags.data(), flags_memory);

    CompressedTransport small;
    small.indices.assign(10, 7);
    small.flags.assign(3, std::uint8_t{0xFF});
    expect_same_transport(run(std::move(small)), expected);
  }
}

}  // namespace
}  // namespace rfrecon::transport
