// Wall time per named stage of a run, in first-use order, for summaries and benchmarks.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace rfrecon {

struct StageTiming {
  std::string stage;
  double seconds = 0.0;
};

// {"stage": ..., "seconds": ...}
void to_json(nlohmann::json& json, const StageTiming& timing);

// Times of a run's stages; a stage timed several times accumulates.
class StageClock {
 public:
  // Runs `work` and adds its wall time to `stage` (also when it throws).
  template <typename F>
  auto time(const std::string& stage, F&& work) {
    const Started started{this, stage, std::chrono::steady_clock::now()};
    return std::forward<F>(work)();
  }
  // Adds the time since the previous lap (or the clock's creation) to `stage`.
  void lap(const std::string& stage);
  void add(const std::string& stage, double seconds);

  const std::vector<StageTiming>& timings() const { return timings_; }
  double total_seconds() const;

 private:
  struct Started {
    StageClock* clock;
    const std::string& stage;
    std::chrono::steady_clock::time_point start;
    ~Started() { clock->add(stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()); }
  };

  std::vector<StageTiming> timings_;
  std::chrono::steady_clock::time_point last_lap_ = std::chrono::steady_clock::now();
};

}  // namespace rfrecon
