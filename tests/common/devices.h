// Test helpers for OpenCL devices: the first selected device, and the skip message of the multi-device tests.
#pragma once

#include "host/cl/device_context.h"
#include "host/cl/device_selection.h"

namespace rfrecon::testing {

inline constexpr const char* kNeedTwoDevices = "needs two OpenCL devices (POCL_DEVICES=\"pthread pthread\")";

// The first device of the default selection (RFRECON_DEVICES or every device).
inline cl::DeviceContext first_device() {
  const auto selected = cl::select_devices(cl::enumerate_devices(), cl::effective_selection(""));
  return cl::DeviceContext(selected.front());
}

}  // namespace rfrecon::testing
