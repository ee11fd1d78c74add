// Rate-limited progress lines through spdlog, and each step to the constructing thread's observer.
#include "host/core/progress.h"

#include <utility>

#include <spdlog/spdlog.h>

namespace rfrecon {

namespace {
thread_local ProgressObserver current_observer;
}  // namespace

ScopedProgressObserver::ScopedProgressObserver(ProgressObserver observer)
    : previous_(std::exchange(current_observer, std::move(observer))) {}

ScopedProgressObserver::~ScopedProgressObserver() { current_observer = std::move(previous_); }

Progress::Progress(std::string label, std::size_t total, std::string unit)
    : label_(std::move(label)),
      total_(total),
      unit_(std::move(unit)),
      start_(std::chrono::steady_clock::now()),
      last_report_(start_),
      observer_(current_observer) {}

void Progress::advance(std::size_t n) {
  const std::size_t now_done = done_.fetch_add(n) + n;
  const auto now = std::chrono::steady_clock::now();
  const bool finished = now_done >= total_ && now_done - n < total_;
  const std::lock_guard<std::mutex> lock(mutex_);
  // Under the lock, the count so far: never smaller than what the observer saw last, whichever thread comes first.
  if (observer_) observer_({label_, done_.load(), total_, unit_});
  if (!finished && now - last_report_ < std::chrono::seconds(1)) return;
  last_report_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const double percent = total_ == 0 ? 100.0 : 100.0 * static_cast<double>(now_done) / static_cast<double>(total_);
  spdlog::info("{}: {:.0f}% ({}/{} {}, {:.1f} s)", label_, percent, now_done, total_, unit_, seconds);
}

}  // namespace rfrecon
