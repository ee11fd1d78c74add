// Steps of state-owning row blocks over several devices: first-touch ownership, failover by replay.
#include "host/sched/block_runner.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <thread>

#include <spdlog/spdlog.h>

namespace rfrecon::sched {

namespace {
constexpr std::size_t kUnowned = std::numeric_limits<std::size_t>::max();

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

BlockRunner::BlockRunner(std::vector<cl::DeviceContext>& devices, std::vector<Tile> blocks, BlockTask& task,
                         std::size_t items_per_row, FaultPolicy faults)
    : devices_(devices),
      blocks_(std::move(blocks)),
      task_(task),
      items_per_row_(items_per_row),
      faults_(std::move(faults)),
      owner_(blocks_.size(), kUnowned),
      claimed_(blocks_.size(), false),
      created_(blocks_.size(), 0),
      failed_(devices.size(), false),
      started_(devices.size(), 0) {
  for (std::size_t i = 0; i < devices.size(); ++i) workers_.emplace_back(devices[i], i);
  // Each device starts with one block (so every device takes part even when one starts late); the rest are
  // first-touch.
  for (std::size_t b = 0; b < std::min(blocks_.size(), devices.size()); ++b) owner_[b] = b;
}

// Runs body(position) for every live device, one thread each, and joins them.
void BlockRunner::run_round(const std::function<void(std::size_t)>& body) {
  std::vector<std::size_t> live;
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    if (!failed_[i]) live.push_back(i);
  }
  // One device works on the calling thread (see run_tiles: cheaper, and oclgrind needs it).
  if (live.size() == 1) {
    body(live.front());
  } else {
    std::vector<std::thread> threads;
    threads.reserve(live.size());
    for (const std::size_t i : live) threads.emplace_back(body, i);
    for (auto& thread : threads) thread.join();
  }
  if (error_) std::rethrow_exception(error_);
}

bool BlockRunner::next_block(std::size_t position, std::size_t& block, bool& moved) {
  const std::lock_guard lock(mutex_);
  if (error_ || failed_[position]) return false;
  for (const bool own : {true, false}) {
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      if (claimed_[b] || owner_[b] != (own ? position : kUnowned)) continue;
      claimed_[b] = true;
      owner_[b] = position;
      block = b;
      moved = created_[b] == 0;  // its state is made (and earlier steps replayed) by the caller
      created_[b] = 1;
      return true;
    }
  }
  return false;
}

void BlockRunner::fail(std::size_t position, const std::string& error, const Tile& rows, RunReport& report) {
  const std::lock_guard lock(mutex_);
  failed_[position] = true;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    if (owner_[b] != position) continue;
    owner_[b] = kUnowned;
    claimed_[b] = false;
    created_[b] = 0;
  }
  auto& share = report.devices[position];
  share.failed = true;
  report.failures.push_back({position, share.device, rows.begin * items_per_row_, rows.end * items_per_row_, error});
  spdlog::warn("{}: device {} ({}) failed, its blocks move to the other devices and are replayed: {}", report.stage,
               position, share.device, error);
}

void BlockRunner::work_on(std::size_t position, std::size_t step, RunReport& report) {
  Worker& worker = workers_[position];
  DeviceShare& share = report.devices[position];
  Tile rows;
  try {
    std::size_t block = 0;
    bool moved = false;
    while (next_block(position, block, moved)) {
      rows = blocks_[block];
      faults_.check(position, ++started_[position]);
      const auto start = std::chrono::steady_clock::now();
      const std::size_t items = rows.size() * items_per_row_;
      if (moved) {
        task_.create(worker, block);
        for (std::size_t earlier = 0; earlier < step; ++earlier) task_.step(worker, block, earlier, true);
        share.replayed_items += items * step;
      }
      task_.step(worker, block, step, false);
      share.busy_seconds += seconds_since(start);
      ++share.tiles;
      share.items += items;
    }
  } catch (const cl::ClError& error) {
    fail(position, error.what(), rows, report);
  } catch (...) {
    const std::lock_guard lock(mutex_);
    if (!error_) error_ = std::current_exception();
  }
}

void BlockRunner::run_step(std::size_t step, const std::string& stage) {
  RunReport report;
  report.stage = stage;
  for (auto& device : devices_) report.devices.push_back({cl::describe(device.info())});
  const auto start = std::chrono::steady_clock::now();
  if (!prepared_) {
    prepared_ = true;
    run_round([&](std::size_t position) {
      try {
        task_.prepare(workers_[position]);
      } catch (const cl::ClError& error) {
        fail(position, error.what(), {}, report);
      } catch (...) {
        const std::lock_guard lock(mutex_);
        if (!error_) error_ = std::current_exception();
      }
    });
  }
  claimed_.assign(blocks_.size(), false);
  // A device failing late can leave blocks that every other device had already passed: run rounds until none is left.
  while (true) {
    bool live = false;
    for (const bool failed : failed_) live = live || !failed;
    if (!live) {
      std::vector<DeviceFailure> failures;
      for (const auto& earlier : reports_)
        failures.insert(failures.end(), earlier.failures.begin(), earlier.failures.end());
      failures.insert(failures.end(), report.failures.begin(), report.failures.end());
      throw AllDevicesFailed(stage, failures);
    }
    bool pending = false;
    for (const bool claimed : claimed_) pending = pending || !claimed;
    if (!pending) break;
    run_round([&](std::size_t position) { work_on(position, step, report); });
  }
  report.seconds = seconds_since(start);
  for (const auto& share : report.devices) report.items += share.items;
  for (auto& existing : reports_) {
    if (existing.stage == stage) {
      existing.merge(report);
      return;
    }
  }
  report.update_shares();
  reports_.push_back(std::move(report));
}

}  // namespace rfrecon::sched
