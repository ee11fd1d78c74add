// The tile timeout without kernels: a device whose tile never returns is dropped and its tiles run elsewhere,
// run_tiles and BlockRunner return without waiting for its thread, results it delivers late are refused, and every
// device hanging is AllDevicesFailed. Hung threads sleep for good; the binary must still exit.
#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include <gtest/gtest.h>

#include "host/cl/device_selection.h"
#include "host/core/errors.h"
#include "host/sched/block_runner.h"
#include "host/sched/scheduler.h"
#include "tests/common/devices.h"
#include "tests/sched/test_support.h"

namespace rfrecon::sched {
namespace {

using rfrecon::testing::hangs_untimed;
using rfrecon::testing::kHangsUntimed;
using rfrecon::testing::ScopedEnv;

using rfrecon::testing::kNeedTwoDevices;
constexpr double kTimeoutS = 0.5;            // far above the healthy calls here (sleeps of milliseconds)
constexpr std::size_t kTimeoutItems = 4099;  // prime: the last tile is partial

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

float expected(std::size_t item) { return 0.5f * static_cast<float>(item); }

// Results of each tile computed into the call's own memory, then delivered, as a kernel's read-back would be.
void compute_into(std::vector<float>& output, Worker& worker, const Tile& tile) {
  std::this_thread::sleep_for(std::chrono::microseconds(5 * tile.size()));  // several tiles per device
  std::vector<float> values;
  for (std::size_t i = tile.begin; i < tile.end; ++i) values.push_back(expected(i));
  worker.deliver(
      [&] { std::copy(values.begin(), values.end(), output.begin() + static_cast<std::ptrdiff_t>(tile.begin)); });
}

void expect_every_item(const std::vector<float>& output) {
  for (std::size_t i = 0; i < output.size(); ++i) ASSERT_EQ(output[i], expected(i)) << "item " << i;
}

void expect_timed_out(const DeviceFailure& failure, std::size_t device) {
  EXPECT_EQ(failure.device, device);
  EXPECT_TRUE(failure.timed_out);
  EXPECT_NE(failure.error.find(kTileTimeoutEnv), std::string::npos) << failure.error;
}

class TileTimeoutTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(devices_.empty());
    options_.faults = FaultPolicy();
    options_.tile_timeout_s = kTimeoutS;
    options_.first_tile_items = 64;
    options_.max_tile_items = 256;
    options_.granularity = 16;
  }

  std::vector<cl::DeviceContext> devices_ = cl::open_devices("");
  Options options_;
};

TEST(TileTimeoutEnvironmentTest, SecondsFromTheEnvironmentZeroDisablesAndBadValuesAreInputErrors) {
  {
    const ScopedEnv unset(kTileTimeoutEnv, nullptr);
    EXPECT_EQ(tile_timeout_from_environment(), kDefaultTileTimeoutS);
  }
  {
    const ScopedEnv timeout(kTileTimeoutEnv, "2.5");
    EXPECT_EQ(tile_timeout_from_environment(), 2.5);
    EXPECT_EQ(Options().tile_timeout_s, 2.5);
    EXPECT_EQ(BlockOptions().tile_timeout_s, 2.5);
  }
  {
    const ScopedEnv off(kTileTimeoutEnv, "0");
    EXPECT_EQ(tile_timeout_from_environment(), 0.0);
  }
  for (const char* bad : {"", "-1", "abc", "1s", "nan", "inf"}) {
    SCOPED_TRACE(bad);
    const ScopedEnv timeout(kTileTimeoutEnv, bad);
    try {
      tile_timeout_from_environment();
      FAIL() << "accepted";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(kTileTimeoutEnv), std::string::npos);
    }
  }
}

TEST_F(TileTimeoutTest, HungDeviceIsDroppedAndItsTilesRunElsewhere) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  options_.faults = FaultPolicy::parse("hang:1:1");
  std::vector<float> output(kTimeoutItems, -1.0f);
  const auto start = std::chrono::steady_clock::now();
  const auto report = run_tiles(
      devices_, kTimeoutItems, [&](Worker& worker, const Tile& tile) { compute_into(output, worker, tile); }, options_);
  EXPECT_LT(seconds_since(start), kTimeoutS + 5.0);  // did not wait for the hung thread
  expect_every_item(output);
  ASSERT_EQ(report.failures.size(), 1u);
  expect_timed_out(report.failures[0], 1);
  EXPECT_GT(report.failures[0].tile_end, report.failures[0].tile_begin);  // the tile it held went to device 0
  EXPECT_TRUE(report.devices[1].failed);
  EXPECT_EQ(report.devices[1].items, 0u);
  EXPECT_EQ(report.devices[0].items, kTimeoutItems);
}

TEST_F(TileTimeoutTest, ResultsDeliveredAfterTheTimeoutAreRefused) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  // Shared with the late thread, which outlives run_tiles.
  struct Late {
    std::vector<float> output = std::vector<float>(kTimeoutItems, -1.0f);
    std::atomic<bool> started{false};
    std::atomic<bool> refused{false};
    std::atomic<bool> done{false};
  };
  const auto late = std::make_shared<Late>();
  const auto report = run_tiles(
      devices_, kTimeoutItems,
      [late](Worker& worker, const Tile& tile) {
        if (worker.position() == 1 && !late->started.exchange(true)) {
          std::this_thread::sleep_for(std::chrono::duration<double>(3 * kTimeoutS));  // a driver call that returns late
          try {
            worker.deliver([&] { std::fill(late->output.begin(), late->output.end(), 1e30f); });
          } catch (const TileAbandoned&) {
            late->refused = true;
          }
          late->done = true;
          return;
        }
        compute_into(late->output, worker, tile);
      },
      options_);
  ASSERT_TRUE(late->started) << "device 1 took no tile";
  for (int i = 0; i < 100 && !late->done; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(late->done);
  EXPECT_TRUE(late->refused);
  expect_every_item(late->output);
  ASSERT_EQ(report.failures.size(), 1u);
  expect_timed_out(report.failures[0], 1);
}

TEST_F(TileTimeoutTest, EveryDeviceHangingIsAllDevicesFailed) {
  if (hangs_untimed(devices_)) GTEST_SKIP() << kHangsUntimed;
  options_.faults = FaultPolicy::parse("hang:*:1");
  const auto start = std::chrono::steady_clock::now();
  try {
    run_tiles(
        devices_, kTimeoutItems, [](Worker&, const Tile&) {}, options_);
    FAIL() << "no error";
  } catch (const AllDevicesFailed& error) {
    const std::string message = error.what();
    for (std::size_t i = 0; i < devices_.size(); ++i) {
      EXPECT_NE(message.find("device " + std::to_string(i) + " ("), std::string::npos) << message;
    }
    EXPECT_NE(message.find("tile timeout"), std::string::npos) << message;
  }
  EXPECT_LT(seconds_since(start), kTimeoutS + 5.0);
}

// Per block, a running sum of (step + 1) x (block + 1) over the steps; the last step delivers it.
class SumBlocks final : public BlockTask {
 public:
  SumBlocks(std::size_t blocks, std::size_t steps) : sums_(blocks), results_(blocks, -1), steps_(steps) {}

  void prepare(Worker&) override {}
  void create(Worker&, std::size_t block) override { sums_[block] = std::make_shared<long>(0); }
  void step(Worker& worker, std::size_t block, std::size_t step, bool) override {
    const std::shared_ptr<long> sum = sums_[block];
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    *sum += static_cast<long>((step + 1) * (block + 1));
    if (step + 1 == steps_) worker.deliver([&] { results_[block] = *sum; });
  }

  long expected(std::size_t block) const { return static_cast<long>((block + 1) * steps_ * (steps_ + 1) / 2); }
  const std::vector<long>& results() const { return results_; }

 private:
  std::vector<std::shared_ptr<long>> sums_;
  std::vector<long> results_;
  std::size_t steps_;
};

BlockOptions block_options(const char* faults) {
  BlockOptions options;
  options.faults = FaultPolicy::parse(faults);
  options.tile_timeout_s = kTimeoutS;
  return options;
}

TEST_F(TileTimeoutTest, BlockRunnerMovesTheBlocksOfAHungDevice) {
  if (devices_.size() < 2) GTEST_SKIP() << kNeedTwoDevices;
  // Device 1 starts with one block and takes at most 7 of the 8: its 8th block-step comes after step 0 and by step 7,
  // so its blocks have state to rebuild by replay.
  constexpr std::size_t kSteps = 8;
  const auto blocks = split_rows(40, 8);
  SumBlocks task(blocks.size(), kSteps);
  BlockRunner runner(devices_, blocks, task, block_options("hang:1:8"));
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t step = 0; step < kSteps; ++step) runner.run_step(step, "sum");
  EXPECT_LT(seconds_since(start), kTimeoutS + 5.0);
  for (std::size_t b = 0; b < blocks.size(); ++b) EXPECT_EQ(task.results()[b], task.expected(b)) << "block " << b;
  ASSERT_EQ(runner.reports().size(), 1u);
  const RunReport& report = runner.reports()[0];
  ASSERT_EQ(report.failures.size(), 1u);
  expect_timed_out(report.failures[0], 1);
  EXPECT_TRUE(report.devices[1].failed);
  EXPECT_GT(report.devices[0].replayed_items, 0u);  // device 1's blocks lost their state and were rebuilt
}

TEST_F(TileTimeoutTest, BlockRunnerWithEveryDeviceHungIsAllDevicesFailed) {
  if (hangs_untimed(devices_)) GTEST_SKIP() << kHangsUntimed;
  const auto blocks = split_rows(40, 2 * devices_.size());
  SumBlocks task(blocks.size(), 3);
  BlockRunner runner(devices_, blocks, task, block_options("hang:*:2"));
  EXPECT_THROW(
      {
        for (std::size_t step = 0; step < 3; ++step) runner.run_step(step, "sum");
      },
      AllDevicesFailed);
}

}  // namespace
}  // namespace rfrecon::sched
