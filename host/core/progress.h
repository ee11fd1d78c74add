// Progress reporting for long runs: thread-safe, rate-limited lines on the log ("simulate: 40% (192/480 rows)"), and
// every step to the observer of the thread that started the run (a library caller's progress callback).
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace rfrecon {

// One step of a run: its label ("transport"), units done of total, and their name ("frames").
struct ProgressStep {
  std::string label;
  std::size_t done = 0;
  std::size_t total = 0;
  std::string unit;
};
using ProgressObserver = std::function<void(const ProgressStep&)>;

// While it lives, every Progress made on this thread reports each of its steps to `observer` (from the thread that
// advances it, one call at a time per Progress); the previous observer is restored after. Observers must not throw.
class ScopedProgressObserver {
 public:
  explicit ScopedProgressObserver(ProgressObserver observer);
  ~ScopedProgressObserver();
  ScopedProgressObserver(const ScopedProgressObserver&) = delete;
  ScopedProgressObserver& operator=(const ScopedProgressObserver&) = delete;

 private:
  ProgressObserver previous_;
};

class Progress {
 public:
  // label: what is running; total: number of units; unit: their name ("rows", "frames").
  Progress(std::string label, std::size_t total, std::string unit);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Records n more units done; logs at most once a second, and once when the total is reached.
  void advance(std::size_t n = 1);
  std::size_t done() const { return done_.load(); }

 private:
  std::string label_;
  std::size_t total_;
  std::string unit_;
  std::atomic<std::size_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_report_;
  ProgressObserver observer_;  // this thread's at construction
};

}  // namespace rfrecon
