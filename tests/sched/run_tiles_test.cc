// run_tiles without kernels: each item delivered once, double-buffer protocol, failover, all-fail and other errors.
// Runs on the machine's OpenCL devices (contexts and queues only); two-device cases skip with fewer devices.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/sched/scheduler.h"
#include "tests/common/devices.h"

namespace rfrecon::sched {
namespace {

using rfrecon::testing::kNeedTwoDevices;

class RunTilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(devices_.empty());
    options_.faults = FaultPolicy();  // tests choose their faults, whatever the environment says
    options_.first_tile_items = 64;
    options_.max_tile_items = 256;  // many tiles per device
    options_.granularity = 16;
  }

  std::vector<cl::DeviceContext> devices_ = cl::open_devices("");
  Options options_;
};

constexpr std::size_t kItems = 10007;  // prime: the last tile is partial

// Each tile sleeps a little so every device gets several tiles.
void slow_down(const Tile& tile) { std::this_thread::sleep_for(std::chrono::microseconds(2 * tile.size())); }

TEST_F(RunTilesTest, EveryItemIsDeliveredExactlyOnce) {
  std::vector<std::atomic<int>> visits(kItems);
  const auto report = run_tiles(
      devices_, kItems,
      [&](Worker&, const Tile& tile) {
        slow_down(tile);
        for (std::size_t i = tile.begin; i < tile.end; ++i) ++visits[i];
      },
      options_);
  for (std::size_t i = 0; i < kItems; ++i) ASSERT_EQ(visits[i].load(), 1) << "item " << i;
  std::size_t items = 0;
  double shares = 0.0;
  for (const auto& device : report.devices) {
    items += device.items;
    shares += device.share;
    EXPECT_FALSE(device.failed);
  }
  EXPECT_EQ(items, kItems);
  EXPECT_NEAR(shares, 1.0, 1e-12);  // shares are items / total: they sum to one up to rounding
  EXPECT_TRUE(report.failures.empty());
}

TEST_F(RunTilesTest, EveryDeviceTakesTilesFromTheSharedQueue) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  const auto report = run_tiles(
      devices_, kItems, [](Worker&, const Tile& tile) { slow_down(tile); }, options_);
  for (const auto& device : report.devices) EXPECT_GT(device.tiles, 0u) << device.device;
}

TEST_F(RunTilesTest, ComputeSeesTheTileUploadedIntoItsSlot) {
  std::vector<std::array<std::size_t, 2>> uploaded(devices_.size(), {kItems, kItems});
  std::atomic<int> mismatches{0};
  std::atomic<int> overlapped{0};
  TileWork work;
  work.upload = [&](Worker& worker, const Tile& tile, int slot) { uploaded[worker.position()][slot] = tile.begin; };
  work.compute = [&](Worker& worker, const Tile& tile, int slot) {
    if (uploaded[worker.position()][slot] != tile.begin || worker.inputs_ready(slot).empty()) ++mismatches;
    // The other slot already holds the next tile's upload: the transfer overlapped this compute.
    if (uploaded[worker.position()][1 - slot] > tile.begin && uploaded[worker.position()][1 - slot] != kItems) {
      ++overlapped;
    }
    slow_down(tile);
  };
  run_tiles(devices_, kItems, work, options_);
  EXPECT_EQ(mismatches.load(), 0);
  EXPECT_GT(overlapped.load(), 0);
}

TEST_F(RunTilesTest, FailedDeviceTilesRunElsewhereAndTheFailureIsReported) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  options_.faults = FaultPolicy::parse("1:2");
  std::vector<std::atomic<int>> visits(kItems);
  const auto report = run_tiles(
      devices_, kItems,
      [&](Worker&, const Tile& tile) {
        slow_down(tile);
        for (std::size_t i = tile.begin; i < tile.end; ++i) ++visits[i];
      },
      options_);
  for (std::size_t i = 0; i < kItems; ++i) ASSERT_EQ(visits[i].load(), 1) << "item " << i;
  ASSERT_EQ(report.failures.size(), 1u);
  EXPECT_EQ(report.failures[0].device, 1u);
  EXPECT_GT(report.failures[0].tile_end, report.failures[0].tile_begin);  // the tile it held went back
  EXPECT_TRUE(report.devices[1].failed);
  EXPECT_EQ(report.devices[1].tiles, 1u);  // it delivered its first tile only
  EXPECT_EQ(report.devices[0].items + report.devices[1].items, kItems);
}

TEST_F(RunTilesTest, TileOfADeviceFailingMidwayIsRedoneWhole) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  std::vector<float> output(kItems, -1.0f);
  std::atomic<int> thrown{0};
  const auto report = run_tiles(
      devices_, kItems,
      [&](Worker& worker, const Tile& tile) {
        slow_down(tile);
        const bool fail = worker.position() == 1 && thrown.load() == 0;
        for (std::size_t i = tile.begin; i < tile.end; ++i) output[i] = fail ? 1e30f : 2.0f * static_cast<float>(i);
        if (fail) {
          ++thrown;
          RF_CL_CHECK_CODE(CL_OUT_OF_RESOURCES, "clEnqueueNDRangeKernel");
        }
      },
      options_);
  EXPECT_EQ(thrown.load(), 1);
  for (std::size_t i = 0; i < kItems; ++i) ASSERT_EQ(output[i], 2.0f * static_cast<float>(i)) << "item " << i;
  ASSERT_EQ(report.failures.size(), 1u);
  EXPECT_NE(report.failures[0].error.find("CL_OUT_OF_RESOURCES"), std::string::npos);
}

TEST_F(RunTilesTest, EveryDeviceFailingIsAClearOpenClError) {
  options_.faults = FaultPolicy::parse("*:1");
  try {
    run_tiles(
        devices_, kItems, [](Worker&, const Tile&) {}, options_);
    FAIL() << "no error";
  } catch (const AllDevicesFailed& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("every selected device failed"), std::string::npos) << message;
    for (std::size_t i = 0; i < devices_.size(); ++i) {
      EXPECT_NE(message.find("device " + std::to_string(i) + " ("), std::string::npos) << message;
    }
  }
}

TEST_F(RunTilesTest, NonDeviceErrorsStopTheRunAndPropagate) {
  EXPECT_THROW(
      run_tiles(
          devices_, kItems, [](Worker&, const Tile&) { throw std::logic_error("bug in a tile function"); }, options_),
      std::logic_error);
}

TEST_F(RunTilesTest, LaterTilesFollowTheMeasuredThroughput) {
  // 1 us per item and a 20 ms target: after the first tile (64 items), tiles reach the 256-item cap well before
  // the guided limit (untaken / (2 x devices)) brings them down at the end.
  options_.target_tile_seconds = 0.02;
  std::vector<std::size_t> sizes;
  std::mutex mutex;
  run_tiles(
      devices_, kItems,
      [&](Worker&, const Tile& tile) {
        std::this_thread::sleep_for(std::chrono::microseconds(tile.size()));
        const std::lock_guard lock(mutex);
        sizes.push_back(tile.size());
      },
      options_);
  EXPECT_EQ(sizes.front(), 64u);
  EXPECT_EQ(*std::max_element(sizes.begin(), sizes.end()), 256u);
}

// Guided self-scheduling halves the last tiles only while another device could take some: a device alone takes, after
// its first tile, tiles of target_tile_seconds of work and then the rest in one, not a tail of ever smaller tiles.
TEST_F(RunTilesTest, ADeviceAloneTakesTheRestInOneTile) {
  std::vector<cl::DeviceContext> one_device;
  one_device.push_back(std::move(devices_.front()));
  options_.max_tile_items = 0;
  options_.target_tile_seconds = 10.0;  // far more than the rest of the items take at 1 us each
  std::vector<std::size_t> sizes;
  run_tiles(
      one_device, kItems,
      [&](Worker&, const Tile& tile) {
        std::this_thread::sleep_for(std::chrono::microseconds(tile.size()));
        sizes.push_back(tile.size());
      },
      options_);
  ASSERT_EQ(sizes.size(), 2u);
  EXPECT_EQ(sizes[0], 64u);
  EXPECT_EQ(sizes[1], kItems - 64);
}

}  // namespace
}  // namespace rfrecon::sched
