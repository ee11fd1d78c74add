// Timed device threads: the watch loop on the calling thread, the per-call bookkeeping and the delivery fence.
#include "host/sched/watchdog.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <utility>

#include "host/core/errors.h"

namespace rfrecon::sched {

namespace {
using Clock = std::chrono::steady_clock;

// Longer timeouts are the same as none in practice, and keep the deadlines' arithmetic far from overflow.
constexpr double kLongestTimeoutS = 1e9;

double seconds(Clock::duration duration) { return std::chrono::duration<double>(duration).count(); }
}  // namespace

double tile_timeout_from_environment() {
  const char* text = std::getenv(kTileTimeoutEnv);
  if (text == nullptr) return kDefaultTileTimeoutS;
  char* end = nullptr;
  const double timeout_s = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(timeout_s) || timeout_s < 0.0) {
    throw InputError(std::string(kTileTimeoutEnv) + ": '" + text +
                     "' is not a number of seconds >= 0 (0 disables the tile timeout)");
  }
  return timeout_s;
}

const char* TileAbandoned::what() const noexcept { return "tile abandoned after the tile timeout"; }

std::string timeout_error(double elapsed_s, double timeout_s) {
  char text[256];
  std::snprintf(text, sizeof text,
                "no answer after %.2f s, past the tile timeout of %g s (%s): the device is taken as hung and its "
                "thread abandoned",
                elapsed_s, timeout_s, kTileTimeoutEnv);
  return text;
}

bool needs_calling_thread(const cl::DeviceInfo& info) { return info.platform_name == "Oclgrind"; }

Watchdog::Watchdog(const std::vector<cl::DeviceContext>& devices, double timeout_s)
    : timeout_s_(std::max(timeout_s, 0.0)),
      timeout_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(std::min(timeout_s_, kLongestTimeoutS)))),
      lanes_(devices.size()) {
  for (std::size_t i = 0; i < devices.size(); ++i) lanes_[i].calling_thread = needs_calling_thread(devices[i].info());
}

void Watchdog::run(const std::vector<std::size_t>& positions, const std::function<void(std::size_t)>& body,
                   const std::function<void(std::size_t, double)>& on_timeout) {
  if (positions.size() == 1 && (timeout_s_ <= 0.0 || lanes_[positions.front()].calling_thread)) {
    body(positions.front());
    return;
  }
  {
    const std::lock_guard lock(mutex_);
    for (const std::size_t position : positions) lanes_[position].finished = false;
  }
  std::vector<std::thread> threads;
  threads.reserve(positions.size());
  for (const std::size_t position : positions) {
    threads.emplace_back([this, body, position] {
      body(position);
      finish(position);
    });
  }
  std::unique_lock lock(mutex_);
  while (true) {
    const Clock::time_point now = Clock::now();
    Clock::time_point wake = now + timeout_;
    bool running = false;
    std::vector<std::pair<std::size_t, double>> expired;
    for (const std::size_t position : positions) {
      Lane& lane = lanes_[position];
      if (lane.finished || lane.abandoned) continue;
      running = true;
      if (!lane.busy || timeout_s_ <= 0.0) continue;
      if (now - lane.since >= timeout_) {
        lane.abandoned = true;
        expired.emplace_back(position, seconds(now - lane.since));
      } else {
        wake = std::min(wake, lane.since + timeout_);
      }
    }
    if (!expired.empty()) {
      lock.unlock();
      for (const auto& [position, elapsed_s] : expired) on_timeout(position, elapsed_s);
      lock.lock();
      continue;
    }
    if (!running) break;
    if (timeout_s_ > 0.0) {
      finished_.wait_until(lock, wake);
    } else {
      finished_.wait(lock);
    }
  }
  std::vector<bool> abandoned(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) abandoned[i] = lanes_[positions[i]].abandoned;
  lock.unlock();
  for (std::size_t i = 0; i < threads.size(); ++i) {
    // A thread blocked for good must block neither the caller nor the process's exit: it is left to itself.
    if (abandoned[i]) {
      threads[i].detach();
    } else {
      threads[i].join();
    }
  }
}

void Watchdog::call(std::size_t position, const std::function<void()>& stage_call) {
  begin_call(position);
  try {
    stage_call();
  } catch (...) {
    end_call(position);
    throw;
  }
  end_call(position);
}

void Watchdog::deliver(std::size_t position, const std::function<void()>& copy) {
  const std::lock_guard lock(mutex_);
  if (lanes_[position].abandoned) throw TileAbandoned();
  copy();
}

void Watchdog::begin_call(std::size_t position) {
  const std::lock_guard lock(mutex_);
  Lane& lane = lanes_[position];
  lane.busy = true;
  lane.since = Clock::now();
}

void Watchdog::end_call(std::size_t position) {
  const std::lock_guard lock(mutex_);
  Lane& lane = lanes_[position];
  if (lane.abandoned) throw TileAbandoned();
  lane.busy = false;
}

void Watchdog::finish(std::size_t position) {
  const std::lock_guard lock(mutex_);
  lanes_[position].finished = true;
  finished_.notify_all();
}

}  // namespace rfrecon::sched
