// The shared tile queue, the per-device worker loop (double buffering, throughput-sized tiles) and failover.
#include "host/sched/scheduler.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

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

// Items not yet handed out, plus tiles given back by failed devices (served first).
class TileQueue {
 public:
  explicit TileQueue(std::size_t items) : items_(items) {}

  // Non-blocking: false when nothing is available now.
  bool try_take(std::size_t size, Tile& tile) {
    const std::lock_guard lock(mutex_);
    return take_locked(size, tile);
  }

  // Waits for a tile; false when every item is delivered or taken by others and none can come back, or stopped.
  bool take(std::size_t size, Tile& tile) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return stopped_ || !returned_.empty() || next_ < items_ || in_flight_ == 0; });
    return !stopped_ && take_locked(size, tile);
  }

  void done(const Tile& tile) {
    const std::lock_guard lock(mutex_);
    --in_flight_;
    delivered_ += tile.size();
    changed_.notify_all();
  }

  void give_back(const Tile& tile) {
    const std::lock_guard lock(mutex_);
    --in_flight_;
    returned_.push_back(tile);
    changed_.notify_all();
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
  bool take_locked(std::size_t size, Tile& tile) {
    if (!returned_.empty()) {
      tile = returned_.front();
      returned_.pop_front();
    } else if (next_ < items_) {
      tile = {next_, std::min(items_, next_ + std::max<std::size_t>(size, 1))};
      next_ = tile.end;
    } else {
      return false;
    }
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
};

class TileRun {
 public:
  TileRun(std::vector<cl::DeviceContext>& devices, std::size_t items, const TileWork& work, const Options& options)
      : devices_(devices), items_(items), work_(work), options_(options), queue_(items), live_(devices.size()) {
    report_.stage = options.stage;
    report_.items = items;
    for (auto& device : devices) report_.devices.push_back({cl::describe(device.info())});
  }

  RunReport run() {
    const auto start = std::chrono::steady_clock::now();
    // One device works on the calling thread: no thread start, and runtimes that only run kernels from the thread
    // that made the context (oclgrind 21.10 crashes otherwise) work.
    if (devices_.size() == 1) {
      work_on(0);
    } else {
      std::vector<std::thread> threads;
      for (std::size_t i = 0; i < devices_.size(); ++i) threads.emplace_back([this, i] { work_on(i); });
      for (auto& thread : threads) thread.join();
    }
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

  // First tile fixed; later ones take target_tile_seconds at the device's measured rate, but never more than half
  // of the untaken items per live device, so the last tiles end together (guided self-scheduling).
  std::size_t tile_size(const DeviceShare& share) const {
    std::size_t size = options_.first_tile_items > 0 ? options_.first_tile_items
                                                     : items_ / (8 * std::max<std::size_t>(devices_.size(), 1));
    if (share.tiles > 0 && share.busy_seconds > 0.0) {
      size = static_cast<std::size_t>(share.items_per_second() * options_.target_tile_seconds);
    }
    const std::size_t live = std::max<std::size_t>(live_.load(), 1);
    size = std::min(size, queue_.untaken() / (2 * live));
    if (options_.max_tile_items > 0) size = std::min(size, options_.max_tile_items);
    return granule(size);
  }

  void upload(Worker& worker, const Tile& tile, int slot) {
    if (!work_.upload) return;
    work_.upload(worker, tile, slot);
    worker.mark_uploaded(slot);
  }

  void work_on(std::size_t position) {
    DeviceShare& share = report_.devices[position];
    Tile current;
    Tile next;
    bool has_current = false;
    bool has_next = false;
    try {
      Worker worker(devices_[position], position);
      if (work_.prepare) work_.prepare(worker);
      std::size_t started = 0;
      int slot = 0;
      while (true) {
        if (!has_current) {
          has_current = queue_.take(tile_size(share), current);
          if (!has_current) break;
          upload(worker, current, slot);
        }
        if (work_.upload) {
          has_next = queue_.try_take(tile_size(share), next);
          if (has_next) upload(worker, next, 1 - slot);
        }
        options_.faults.check(position, ++started);
        const auto start = std::chrono::steady_clock::now();
        work_.compute(worker, current, slot);
        share.busy_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ++share.tiles;
        share.items += current.size();
        worker.clear_uploads(slot);
        queue_.done(current);
        has_current = has_next;
        current = next;
        has_next = false;
        slot = 1 - slot;
      }
    } catch (const cl::ClError& error) {
      const Tile failed_tile = has_current ? current : Tile{};
      spdlog::warn("{}: device {} ({}) failed, its tiles go to the other devices: {}", options_.stage, position,
                   share.device, error.what());
      {
        const std::lock_guard lock(report_mutex_);
        report_.failures.push_back(
            {position, share.device, failed_tile.begin, failed_tile.end, std::string(error.what())});
      }
      share.failed = true;
      --live_;
      if (has_current) queue_.give_back(current);
      if (has_next) queue_.give_back(next);
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
  const TileWork& work_;
  const Options& options_;
  TileQueue queue_;
  std::atomic<std::size_t> live_;
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
  return TileRun(devices, items, work, options).run();
}

RunReport run_tiles(std::vector<cl::DeviceContext>& devices, std::size_t items, const TileFn& compute,
                    const Options& options) {
  TileWork work;
  work.compute = [&compute](Worker& worker, const Tile& tile, int) { compute(worker, tile); };
  return run_tiles(devices, items, work, options);
}

}  // namespace rfrecon::sched
