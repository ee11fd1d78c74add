// One process-wide spdlog sink that hands each line to every active callback, installed while any is active.
#include "host/core/log_forwarding.h"

#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

namespace rfrecon {

namespace {

struct Forwarding {
  std::mutex mutex;
  std::shared_ptr<spdlog::logger> previous;  // the default logger before the first active callback
  std::vector<std::pair<const ScopedLogForwarding*, std::shared_ptr<LogCallback>>> active;
};

Forwarding& forwarding() {
  static Forwarding state;
  return state;
}

int level_of(spdlog::level::level_enum level) {
  if (level <= spdlog::level::debug) return 0;
  if (level == spdlog::level::info) return 1;
  if (level == spdlog::level::warn) return 2;
  return 3;
}

class CallbackSink : public spdlog::sinks::base_sink<std::mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& message) override {
    std::vector<std::shared_ptr<LogCallback>> callbacks;
    {
      const std::lock_guard<std::mutex> lock(forwarding().mutex);
      for (const auto& entry : forwarding().active) callbacks.push_back(entry.second);
    }
    const std::string text(message.payload.data(), message.payload.size());
    for (const auto& callback : callbacks) {
      try {
        (*callback)(level_of(message.level), text);
      } catch (...) {  // a log line must never end a run: a callback that throws loses that line
      }
    }
  }
  void flush_() override {}
};

}  // namespace

ScopedLogForwarding::ScopedLogForwarding(LogCallback callback) {
  if (!callback) return;
  auto& state = forwarding();
  const std::lock_guard<std::mutex> lock(state.mutex);
  if (state.active.empty()) {
    state.previous = spdlog::default_logger();
    auto logger = std::make_shared<spdlog::logger>("rfrecon", std::make_shared<CallbackSink>());
    logger->set_level(state.previous->level());
    spdlog::set_default_logger(std::move(logger));
  }
  state.active.emplace_back(this, std::make_shared<LogCallback>(std::move(callback)));
  active_ = true;
}

ScopedLogForwarding::~ScopedLogForwarding() {
  if (!active_) return;
  auto& state = forwarding();
  const std::lock_guard<std::mutex> lock(state.mutex);
  state.active.erase(std::remove_if(state.active.begin(), state.active.end(),
                                    [this](const auto& entry) { return entry.first == this; }),
                     state.active.end());
  if (state.active.empty()) spdlog::set_default_logger(std::move(state.previous));
}

}  // namespace rfrecon
