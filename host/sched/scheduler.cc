// The shared tile queue, the per-device worker loop (double buffering, throughput-sized tiles), failover and the
// tile timeout.
#include "host/sched/scheduler.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <numeric>
#include <utility>

#include <spdlog/spdlog.h>

namespace rfrecon::sched {

std::vector<Tile> split_rows(std::size_t rows, std::size_t tiles) {
  tiles = std::max<std::size_t>(1, std::min(tiles, rows));
  std::vector<Tile> blocks;
  std::size_t begin = 0;
  for (std::size_t i = 0; i < tiles && rows > 0; ++i) {
    const std::size_t size = rows / tiles + (i < rows % tiles ? 1 : 0);
    blocks.push_back({begin, begin + size});
    begin += size;
  }
  return blocks;
}

namespace {

std::string failures_text(const std::string& stage, const std::vector<DeviceFailure>& failures) {
  std::string text = "every selected device failed in stage '" + stage + "':";
  for (const auto& failure : failures) {
    text += "\n  device " + std::to_string(failure.device) + " (" + failure.device_name + "): " + failure.error;
  }
  return text;
}

// Items not yet handed out, plus tiles given back by failed devices (served first); which device holds which tile.
class TileQueue {
 public:
  TileQueue(std::size_t items, std::size_t holders) : items_(items), held_(holders) {}

  // Non-blocking: false when nothing is available now.
  bool try_take(std::size_t holder, std::size_t size, Tile& tile) {
    const std::lock_guard lock(mutex_);
    return take_locked(holder, size, tile);
  }

  // Waits for a tile; false when every item is delivered or taken by others and none can come back, or stopped.
  bool take(std::size_t holder, std::size_t size, Tile& tile) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return stopped_ || !returned_.empty() || next_ < items_ || in_flight_ == 0; });
    return !stopped_ && take_locked(holder, size, tile);
  }

  void done(std::size_t holder, const Tile& tile) {
    const std::lock_guard lock(mutex_);
    auto& held = held_[holder];
    held.erase(std::find_if(held.begin(), held.end(), [&](const Tile& t) { return t.begin == tile.begin; }));
    --in_flight_;
    delivered_ += tile.size();
    changed_.notify_all();
  }

  // Gives back every tile `holder` holds (a failed or hung device) and returns them, the oldest first.
  std::vector<Tile> give_back(std::size_t holder) {
    const std::lock_guard lock(mutex_);
    std::vector<Tile> held;
    held.swap(held_[holder]);
    in_flight_ -= held.size();
    returned_.insert(returned_.end(), held.begin(), held.end());
    changed_.notify_all();
    return held;
  }

  void stop() {
    const std::lock_guard lock(mutex_);
    stopped_ = true;
    changed_.notify_all();
  }

  std::size_t untaken() const {
    const std::lock_guard lock(mutex_);
    return items_ - next_;
  }
  std::size_t delivered() const {
    const std::lock_guard lock(mutex_);
    return delivered_;
  }

 private:
  bool take_locked(std::size_t holder, std::size_t size, Tile& tile) {
    if (!returned_.empty()) {
      tile = returned_.front();
      returned_.pop_front();
    } else if (next_ < items_) {
      tile = {next_, std::min(items_, next_ + std::max<std::size_t>(size, 1))};
      next_ = tile.end;
    } else {
      return false;
    }
    held_[holder].push_back(tile);
    ++in_flight_;
    return true;
  }

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::size_t items_;
  std::size_t next_ = 0;
  std::size_t in_flight_ = 0;
  std::size_t delivered_ = 0;
  bool stopped_ = false;
  std::deque<Tile> returned_;
  std::vector<std::vector<Tile>> held_;  // per device: at most the current tile and the prefetched next one
};

// Shared with the device threads (shared_ptr): a thread abandoned after the tile timeout keeps the run alive, so
// what it touches later is never freed memory.
class TileRun : public std::enable_shared_from_this<TileRun> {
 public:
  TileRun(std::vector<cl::DeviceContext>& devices, std::size_t items, TileWork work, Options options)
      : devices_(devices),
        items_(items),
        work_(std::move(work)),
        options_(std::move(options)),
        queue_(items, devices.size()),
        live_(devices.size()),
        entries_(options_.entries.resolve(devices)),
        watchdog_(devices, options_.tile_timeout_s) {
    report_.stage = options_.stage;
    report_.items = items;
    for (std::size_t i = 0; i < devices.size(); ++i) {
      report_.devices.push_back({cl::describe(devices[i].info()), cl::entry_name(entries_[i])});
    }
  }

  RunReport run() {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::size_t> positions(devices_.size());
    std::iota(positions.begin(), positions.end(), 0);
    watchdog_.run(
        positions, [self = shared_from_this()](std::size_t position) { self->work_on(position); },
        [this](std::size_t position, double elapsed_s) {
          drop(position, timeout_error(elapsed_s, options_.tile_timeout_s), true);
        });
    const std::lock_guard lock(report_mutex_);
    report_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_.update_shares();
    if (error_) std::rethrow_exception(error_);
    if (queue_.delivered() != items_) throw AllDevicesFailed(options_.stage, report_.failures);
    return report_;
  }

 private:
  std::size_t granule(std::size_t size) const {
    const std::size_t g = std::max<std::size_t>(options_.granularity, 1);
    return std::max(g, (size + g - 1) / g * g);
  }

  // First tile fixed; later ones take target_tile_seconds at the device's measured rate, but, with other live devices,
  // never more than half of the untaken items per live device, so the last tiles end together (guided
  // self-scheduling). A device alone has no one to wait for: halving would only add launches of ever smaller tiles.
  std::size_t tile_size(const DeviceShare& share) const {
    std::size_t size = options_.first_tile_items > 0 ? options_.first_tile_items
                                                     : items_ / (8 * std::max<std::size_t>(devices_.size(), 1));
    if (share.tiles > 0 && share.busy_seconds > 0.0) {
      size = static_cast<std::size_t>(share.items_per_second() * options_.target_tile_seconds);
    }
    const std::size_t live = live_.load();
    if (live > 1) size = std::min(size, queue_.untaken() / (2 * live));
    if (options_.max_tile_items > 0) size = std::min(size, options_.max_tile_items);
    return granule(size);
  }

  void upload(Worker& worker, const Tile& tile, int slot) {
    if (!work_.upload) return;
    watchdog_.call(worker.position(), [&] {
      work_.upload(worker, tile, slot);
      worker.mark_uploaded(slot);
    });
  }

  // The device's tiles go back to the queue for the others, the failure into the report.
  void drop(std::size_t position, const std::string& error, bool timed_out) {
    const std::vector<Tile> held = queue_.give_back(position);
    const Tile tile = held.empty() ? Tile{} : held.front();
    const std::lock_guard lock(report_mutex_);
    DeviceShare& share = report_.devices[position];
    spdlog::warn("{}: device {} ({}) failed at items [{}, {}), its tiles go to the other devices: {}", options_.stage,
                 position, share.device, tile.begin, tile.end, error);
    report_.failures.push_back({position, share.device, tile.begin, tile.end, error, timed_out});
    share.failed = true;
    --live_;
  }

  void work_on(std::size_t position) {
    DeviceShare& share = report_.devices[position];
    try {
      Worker worker(devices_[position], position, entries_[position], &watchdog_);
      if (work_.prepare) watchdog_.call(position, [&] { work_.prepare(worker); });
      Tile current;
      Tile next;
      bool has_current = false;
      bool has_next = false;
      std::size_t started = 0;
      int slot = 0;
      while (true) {
        if (!has_current) {
          has_current = queue_.take(position, tile_size(share), current);
          if (!has_current) break;
          upload(worker, current, slot);
        }
        if (work_.upload) {
          has_next = queue_.try_take(position, tile_size(share), next);
          if (has_next) upload(worker, next, 1 - slot);
        }
        ++started;
        const auto start = std::chrono::steady_clock::now();
        watchdog_.call(position, [&] {
          options_.faults.check(position, started);
          work_.compute(worker, current, slot);
        });
        share.busy_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ++share.tiles;
        share.items += current.size();
        worker.clear_uploads(slot);
        queue_.done(position, current);
        has_current = has_next;
        current = next;
        has_next = false;
        slot = 1 - slot;
      }
    } catch (const TileAbandoned&) {
      // Dropped after the tile timeout: the watchdog has given its tiles away and reported it.
    } catch (const cl::ClError& error) {
      drop(position, error.what(), false);
    } catch (...) {
      {
        const std::lock_guard lock(report_mutex_);
        if (!error_) error_ = std::current_exception();
      }
      queue_.stop();
    }
  }

  std::vector<cl::DeviceContext>& devices_;
  std::size_t items_;
  TileWork work_;
  Options options_;
  TileQueue queue_;
  std::atomic<std::size_t> live_;
  std::vector<cl::KernelEntry> entries_;  // per device
  Watchdog watchdog_;
  std::mutex report_mutex_;
  RunReport report_;
  std::exception_ptr error_;
};

}  // namespace

AllDevicesFailed::AllDevicesFailed(const std::string& stage, const std::vector<DeviceFailure>& failures)
    : cl::ClError("stage '" + stage + "' on every device", CL_DEVICE_NOT_AVAILABLE, __FILE__, __LINE__,
                  failures_text(stage, failures)) {}

RunReport run_tiles(std::vector<cl::DeviceContext>& devices, std::size_t items, const TileWork& work,
                    const Options& options) {
  if (!work.compute) throw std::invalid_argument("run_tiles: TileWork needs a compute function");
  if (devices.empty()) throw AllDevicesFailed(options.stage, {});
  return std::make_shared<TileRun>(devices, items, work, options)->run();
}

RunReport run_tiles(std::vector<cl::DeviceContext>& devices, std::size_t items, const TileFn& compute,
                    const Options& options) {
  TileWork work;
  // A copy: a thread abandoned after the tile timeout may still run it when the caller's function is gone.
  work.compute = [compute](Worker& worker, const Tile& tile, int) { compute(worker, tile); };
  return run_tiles(devices, items, work, options);
}

}  // namespace rfrecon::sched
