// The transport stage (decode + compression into the compressed T) on two devices, one on the single work-item
// entries and one on the NDRange entries, as a CPU + FPGA run would be: the result is the one-device result within
// the kernel tests' tolerance. Needs two devices: run by transport_two_pocl_devices with POCL_DEVICES="pthread
// pthread"; skipped where only one device exists.

#include <gtest/gtest.h>

#include "host/capture/protocol.h"
#include "host/cl/device_selection.h"
#include "host/transport/compute_transport.h"
#include "tests/common/devices.h"
#include "tests/transport/same_transport.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon::transport {
namespace {

using testing::expect_same_transport;  // the tolerance of transport_kernel_test (tests/transport/same_transport.h)

TEST(TransportDevicesTest, SingleWorkItemDeviceAndNdRangeDeviceGiveTheOneDeviceTransport) {
  auto devices = cl::open_devices("all");
  if (devices.size() < 2) GTEST_SKIP() << rfrecon::testing::kNeedTwoDevices;
  devices.erase(devices.begin() + 2, devices.end());
  testing::SceneOptions options;
  options.camera_size = {48, 40};
  options.projector_size = {32, 24};
  const auto scene = testing::make_plane_scene(options);
  const auto sequence = capture::make_protocol({options.projector_size, 4});
  testing::TempDir dir("transport_devices");
  testing::write_capture(dir.path(), scene, sequence, 4, testing::render_frames(scene, sequence, 4, 1.0, 11));
  TransportSetup setup;
  setup.entries_per_pixel = 4;  // < 16 dot candidates: the compression also drops entries
  cl::ProgramCache programs;
  const auto run = [&](std::vector<cl::DeviceContext>& on, const cl::EntryChoice& entries) {
    return compute_transport_on_devices(dir.path(), capture::read_manifest(dir.path()), setup, on, programs, entries);
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

}  // namespace
}  // namespace rfrecon::transport
