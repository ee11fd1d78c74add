// Accumulation of stage times.
#include "host/core/stage_clock.h"

namespace rfrecon {

void to_json(nlohmann::json& json, const StageTiming& timing) {
  json = {{"stage", timing.stage}, {"seconds", timing.seconds}};
}

void StageClock::lap(const std::string& stage) {
  const auto now = std::chrono::steady_clock::now();
  add(stage, std::chrono::duration<double>(now - last_lap_).count());
  last_lap_ = now;
}

void StageClock::add(const std::string& stage, double seconds) {
  for (auto& timing : timings_) {
    if (timing.stage == stage) {
      timing.seconds += seconds;
      return;
    }
  }
  timings_.push_back({stage, seconds});
}

double StageClock::total_seconds() const {
  double total = 0.0;
  for (const auto& timing : timings_) total += timing.seconds;
  return total;
}

}  // namespace rfrecon
