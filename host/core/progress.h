// Progress reporting for long runs: thread-safe, rate-limited lines on the log ("simulate: 40% (192/480 rows)").
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace rfrecon {

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
};

}  // namespace rfrecon
