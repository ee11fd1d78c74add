// Scheduler test helpers: environment variables for one scope, and when an injected hang could not be timed.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "host/cl/device_context.h"
#include "host/sched/watchdog.h"

namespace rfrecon::testing {

// Sets (or, given nullptr, unsets) an environment variable for one scope (the scheduler reads RFRECON_INJECT_FAULT
// and RFRECON_TILE_TIMEOUT from it, as the commands do), then restores what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value != nullptr) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// A single oclgrind device works on the calling thread, untimed (sched::needs_calling_thread): a hang injected there
// would hang the test.
inline bool hangs_untimed(const std::vector<cl::DeviceContext>& devices) {
  return devices.size() == 1 && sched::needs_calling_thread(devices.front().info());
}
inline constexpr const char* kHangsUntimed =
    "one oclgrind device works on the calling thread, where no timeout applies";

}  // namespace rfrecon::testing
