// Kernel entries per device through the scheduler, without kernels: each worker gets its device's entry from
// Options::entries / BlockOptions::entries, the reports name it per device (JSON and table), and a per-device list of
// another length than the devices is a UsageError before any work. Runs on the machine's devices (one or two).
#include <atomic>
#include <mutex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "host/cl/device_selection.h"
#include "host/core/errors.h"
#include "host/sched/block_runner.h"
#include "host/sched/scheduler.h"

namespace rfrecon::sched {
namespace {

using cl::KernelEntry;

// single, ndrange, single, ... : one entry per device, both entries as soon as there are two devices.
std::vector<KernelEntry> alternating(std::size_t devices) {
  std::vector<KernelEntry> entries;
  for (std::size_t i = 0; i < devices; ++i)
    entries.push_back(i % 2 == 0 ? KernelEntry::kSingleWorkItem : KernelEntry::kNdRange);
  return entries;
}

class SchedEntriesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(devices_.empty());
    options_.faults = FaultPolicy();
    options_.tile_timeout_s = 0.0;
    options_.first_tile_items = 16;
    options_.granularity = 16;
  }
  std::vector<cl::DeviceContext> devices_ = cl::open_devices("");
  Options options_;
};

TEST_F(SchedEntriesTest, EachWorkerRunsItsDevicesEntryAndTheReportNamesIt) {
  const auto entries = alternating(devices_.size());
  options_.entries = cl::EntryChoice(entries);
  std::atomic<int> wrong{0};
  const auto report = run_tiles(
      devices_, 1000,
      [&](Worker& worker, const Tile&) {
        if (worker.entry() != entries[worker.position()]) ++wrong;
      },
      options_);
  EXPECT_EQ(wrong.load(), 0);
  const nlohmann::json json = report;
  ASSERT_EQ(json.at("devices").size(), devices_.size());
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    EXPECT_EQ(report.devices[i].entry, cl::entry_name(entries[i]));
    EXPECT_EQ(json.at("devices")[i].at("entry"), cl::entry_name(entries[i]));
  }
  // The table: header "entry" column, each device's line with its word after the device name.
  const auto lines = format_table({report});
  ASSERT_EQ(lines.size(), 1 + devices_.size());
  EXPECT_NE(lines[0].find("entry"), std::string::npos) << lines[0];
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    EXPECT_NE(lines[1 + i].find(std::string(" ") + cl::entry_name(entries[i]) + " "), std::string::npos)
        << lines[1 + i];
  }
}

TEST_F(SchedEntriesTest, AutoGivesEachDeviceThePreferredEntry) {
  const auto report = run_tiles(
      devices_, 100, [](Worker&, const Tile&) {}, options_);
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    EXPECT_EQ(report.devices[i].entry, cl::entry_name(cl::preferred_entry(devices_[i].info())));
  }
}

TEST_F(SchedEntriesTest, ListOfAnotherLengthIsAUsageErrorBeforeAnyTile) {
  options_.entries = cl::EntryChoice(alternating(devices_.size() + 1));
  std::atomic<int> tiles{0};
  EXPECT_THROW(run_tiles(
                   devices_, 100, [&](Worker&, const Tile&) { ++tiles; }, options_),
               UsageError);
  EXPECT_EQ(tiles.load(), 0);
}

// Records each block-step's worker entry.
class EntryBlocks final : public BlockTask {
 public:
  void prepare(Worker&) override {}
  void create(Worker&, std::size_t) override {}
  void step(Worker& worker, std::size_t, std::size_t, bool) override {
    const std::lock_guard lock(mutex_);
    seen.emplace_back(worker.position(), worker.entry());
  }
  std::vector<std::pair<std::size_t, KernelEntry>> seen;

 private:
  std::mutex mutex_;
};

TEST_F(SchedEntriesTest, BlockRunnerGivesEachDeviceItsEntry) {
  const auto entries = alternating(devices_.size());
  BlockOptions options;
  options.faults = FaultPolicy();
  options.tile_timeout_s = 0.0;
  options.entries = cl::EntryChoice(entries);
  EntryBlocks task;
  BlockRunner runner(devices_, split_rows(8 * devices_.size(), 4 * devices_.size()), task, options);
  runner.run_step(0, "decode");
  ASSERT_FALSE(task.seen.empty());
  for (const auto& [position, entry] : task.seen) EXPECT_EQ(entry, entries[position]) << "device " << position;
  ASSERT_EQ(runner.reports().size(), 1u);
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    EXPECT_EQ(runner.reports()[0].devices[i].entry, cl::entry_name(entries[i]));
  }
  options.entries = cl::EntryChoice(alternating(devices_.size() + 1));
  EXPECT_THROW(BlockRunner(devices_, split_rows(8, 4), task, options), UsageError);
}

}  // namespace
}  // namespace rfrecon::sched
