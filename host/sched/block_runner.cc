// Steps of state-owning row blocks over several devices: first-touch ownership, failover by replay, timed calls.
#include "host/sched/block_runner.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <utility>

#include <spdlog/spdlog.h>

namespace rfrecon::sched {

namespace {
constexpr std::size_t kUnowned = std::numeric_limits<std::size_t>::max();

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

// Everything the device threads touch, shared with them: a thread abandoned after the tile timeout keeps it alive.
class BlockRunner::State : public std::enable_shared_from_this<State> {
 public:
  State(std::vector<cl::DeviceContext>& devices, std::vector<Tile> blocks, BlockTask& task, BlockOptions options)
      : devices_(devices),
        blocks_(std::move(blocks)),
        task_(task),
        options_(std::move(options)),
        watchdog_(devices, options_.tile_timeout_s),
        owner_(blocks_.size(), kUnowned),
        claimed_(blocks_.size(), false),
        created_(blocks_.size(), 0),
        current_(devices.size()),
        failed_(devices.size(), false),
        started_(devices.size(), 0) {
    const std::vector<cl::KernelEntry> entries = options_.entries.resolve(devices);
    for (std::size_t i = 0; i < devices.size(); ++i) workers_.emplace_back(devices[i], i, entries[i], &watchdog_);
    // Each device starts with one block (so every device takes part even when one starts late); the rest are
    // first-touch.
    for (std::size_t b = 0; b < std::min(blocks_.size(), devices.size()); ++b) owner_[b] = b;
  }

  void run_step(std::size_t step, const std::string& stage);
  const std::vector<RunReport>& reports() const { return reports_; }
  const std::vector<Tile>& blocks() const { return blocks_; }

 private:
  void work_on(std::size_t position, std::size_t step);
  bool next_block(std::size_t position, std::size_t& block, bool& moved);
  void fail(std::size_t position, const std::string& error, bool timed_out);
  void on_device(std::size_t position, const std::function<void(std::size_t)>& body);
  void run_round(const std::function<void(std::size_t)>& body);

  std::vector<cl::DeviceContext>& devices_;
  std::vector<Tile> blocks_;
  BlockTask& task_;
  BlockOptions options_;
  Watchdog watchdog_;
  std::vector<Worker> workers_;
  std::mutex mutex_;
  std::vector<std::size_t> owner_;    // per block; kUnowned when its state lives nowhere
  std::vector<bool> claimed_;         // per block: taken (or done) in the current step
  std::vector<char> created_;         // per block: its state exists on its owner
  std::vector<Tile> current_;         // per device: the rows of the block it works on, for failures
  std::vector<bool> failed_;          // per device
  std::vector<std::size_t> started_;  // block-steps started per device, for faults
  RunReport report_;                  // of the current step
  std::vector<RunReport> reports_;
  std::exception_ptr error_;
  bool prepared_ = false;
};

BlockRunner::BlockRunner(std::vector<cl::DeviceContext>& devices, std::vector<Tile> blocks, BlockTask& task,
                         BlockOptions options)
    : state_(std::make_shared<State>(devices, std::move(blocks), task, std::move(options))) {}

void BlockRunner::run_step(std::size_t step, const std::string& stage) { state_->run_step(step, stage); }
const std::vector<RunReport>& BlockRunner::reports() const { return state_->reports(); }
const std::vector<Tile>& BlockRunner::blocks() const { return state_->blocks(); }

// A device error drops the device; any other error stops the step (run_round rethrows it).
void BlockRunner::State::on_device(std::size_t position, const std::function<void(std::size_t)>& body) {
  try {
    body(position);
  } catch (const TileAbandoned&) {
    // Dropped after the tile timeout: the watchdog thread has moved its blocks and reported it.
  } catch (const cl::ClError& error) {
    fail(position, error.what(), false);
  } catch (...) {
    const std::lock_guard lock(mutex_);
    if (!error_) error_ = std::current_exception();
  }
}

// Runs body(position) for every live device, one thread each (see Watchdog::run), until each has returned or hung.
void BlockRunner::State::run_round(const std::function<void(std::size_t)>& body) {
  std::vector<std::size_t> live;
  {
    const std::lock_guard lock(mutex_);
    for (std::size_t i = 0; i < devices_.size(); ++i) {
      if (!failed_[i]) live.push_back(i);
    }
  }
  watchdog_.run(
      live, [self = shared_from_this(), body](std::size_t position) { self->on_device(position, body); },
      [this](std::size_t position, double elapsed_s) {
        fail(position, timeout_error(elapsed_s, options_.tile_timeout_s), true);
      });
  const std::lock_guard lock(mutex_);
  if (error_) std::rethrow_exception(error_);
}

bool BlockRunner::State::next_block(std::size_t position, std::size_t& block, bool& moved) {
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
      current_[position] = blocks_[b];
      return true;
    }
  }
  return false;
}

void BlockRunner::State::fail(std::size_t position, const std::string& error, bool timed_out) {
  const std::lock_guard lock(mutex_);
  failed_[position] = true;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    if (owner_[b] != position) continue;
    owner_[b] = kUnowned;
    claimed_[b] = false;
    created_[b] = 0;
  }
  auto& share = report_.devices[position];
  share.failed = true;
  const std::size_t begin = current_[position].begin * options_.items_per_row;
  const std::size_t end = current_[position].end * options_.items_per_row;
  report_.failures.push_back({position, share.device, begin, end, error, timed_out});
  spdlog::warn("{}: device {} ({}) failed at items [{}, {}), its blocks move to the other devices and are replayed: {}",
               report_.stage, position, share.device, begin, end, error);
}

void BlockRunner::State::work_on(std::size_t position, std::size_t step) {
  Worker& worker = workers_[position];
  DeviceShare& share = report_.devices[position];
  std::size_t block = 0;
  bool moved = false;
  while (next_block(position, block, moved)) {
    const std::size_t started = ++started_[position];
    watchdog_.call(position, [&] { options_.faults.check(position, started); });
    const auto start = std::chrono::steady_clock::now();
    const std::size_t items = blocks_[block].size() * options_.items_per_row;
    if (moved) {
      watchdog_.call(position, [&] { task_.create(worker, block); });
      for (std::size_t earlier = 0; earlier < step; ++earlier) {
        watchdog_.call(position, [&] { task_.step(worker, block, earlier, true); });
      }
      share.replayed_items += items * step;
    }
    watchdog_.call(position, [&] { task_.step(worker, block, step, false); });
    share.busy_seconds += seconds_since(start);
    ++share.tiles;
    share.items += items;
  }
}

void BlockRunner::State::run_step(std::size_t step, const std::string& stage) {
  report_ = RunReport();
  report_.stage = stage;
  for (auto& worker : workers_) {
    report_.devices.push_back({cl::describe(worker.device().info()), cl::entry_name(worker.entry())});
  }
  const auto start = std::chrono::steady_clock::now();
  if (!prepared_) {
    prepared_ = true;
    run_round([this](std::size_t position) { watchdog_.call(position, [&] { task_.prepare(workers_[position]); }); });
  }
  claimed_.assign(blocks_.size(), false);
  // A device failing late can leave blocks that every other device had already passed: run rounds until none is left.
  while (true) {
    if (std::find(failed_.begin(), failed_.end(), false) == failed_.end()) {
      std::vector<DeviceFailure> failures;
      for (const auto& earlier : reports_)
        failures.insert(failures.end(), earlier.failures.begin(), earlier.failures.end());
      failures.insert(failures.end(), report_.failures.begin(), report_.failures.end());
      throw AllDevicesFailed(stage, failures);
    }
    if (std::find(claimed_.begin(), claimed_.end(), false) == claimed_.end()) break;
    run_round([this, step](std::size_t position) { work_on(position, step); });
  }
  report_.seconds = seconds_since(start);
  for (const auto& share : report_.devices) report_.items += share.items;
  for (auto& existing : reports_) {
    if (existing.stage == stage) {
      existing.merge(report_);
      return;
    }
  }
  report_.update_shares();
  reports_.push_back(std::move(report_));
}

}  // namespace rfrecon::sched
