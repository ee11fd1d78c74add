// Sends the library's log lines (spdlog's default logger) to callbacks for as long as their scopes live.
#pragma once

#include <functional>
#include <string>

namespace rfrecon {

// spdlog's levels as the front door names them: 0 debug (and trace), 1 info, 2 warning, 3 error (and critical).
using LogCallback = std::function<void(int level, const std::string& message)>;

// While any lives, spdlog's default logger is one that hands each line to the callbacks of all that live (one line at
// a time; the level threshold kept), whichever thread logs it; when the last goes, the previous default logger (the
// tool's stderr) is back. An empty callback changes nothing. Scopes may end in any order, on any thread.
class ScopedLogForwarding {
 public:
  explicit ScopedLogForwarding(LogCallback callback);
  ~ScopedLogForwarding();
  ScopedLogForwarding(const ScopedLogForwarding&) = delete;
  ScopedLogForwarding& operator=(const ScopedLogForwarding&) = delete;

 private:
  bool active_ = false;
};

}  // namespace rfrecon
