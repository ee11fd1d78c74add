// Shared benchmark context: records the git revision and the OpenCL devices in every benchmark's JSON output.
#include <benchmark/benchmark.h>

#include "host/cl/device_context.h"

namespace {
const bool kContextAdded = [] {
  benchmark::AddCustomContext("rfrecon_version", RFRECON_VERSION);
#ifdef RFRECON_GIT_REVISION
  benchmark::AddCustomContext("git_revision", RFRECON_GIT_REVISION);
#endif
  std::string devices;
  for (const auto& entry : rfrecon::cl::enumerate_devices()) {
    devices += (devices.empty() ? "" : "; ") + rfrecon::cl::describe(entry.info);
  }
  benchmark::AddCustomContext("opencl_devices", devices);
  return true;
}();
}  // namespace
