// Scheduler test helpers: when an injected hang could not be timed (and ScopedEnv, tests/common/scoped_env.h).
#pragma once

#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "host/cl/device_context.h"
#include "host/sched/watchdog.h"
#include "tests/common/scoped_env.h"

namespace rfrecon::testing {

// A single oclgrind device works on the calling thread, untimed (sched::needs_calling_thread): a hang injected there
// would hang the test.
inline bool hangs_untimed(const std::vector<cl::DeviceContext>& devices) {
  return devices.size() == 1 && sched::needs_calling_thread(devices.front().info());
}
inline constexpr const char* kHangsUntimed =
    "one oclgrind device works on the calling thread, where no timeout applies";

}  // namespace rfrecon::testing
