// Chooses devices from a selection string given by --devices or the RFRECON_DEVICES environment variable.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "host/cl/device_context.h"

namespace rfrecon::cl {

// Environment variable read when no --devices flag is given.
inline constexpr const char* kDevicesEnv = "RFRECON_DEVICES";

// A comma-separated list of terms, each one of:
//   all | cpu | gpu | fpga (= accelerator) | an index from `rfrecon devices` | text found in "platform device"
//   (case-insensitive).
// Devices are returned once each, in enumeration order. Throws DeviceSelectionError when a term matches no device
// or the machine has no OpenCL device at all; the message lists the devices that exist.
std::vector<DeviceEntry> select_devices(const std::vector<DeviceEntry>& available, std::string_view selection);

// The selection to use: `flag` when non-empty, else $RFRECON_DEVICES, else "all".
std::string effective_selection(std::string_view flag);

// enumerate_devices() + select_devices(effective_selection(flag)), each wrapped in a DeviceContext.
std::vector<DeviceContext> open_devices(std::string_view flag);

}  // namespace rfrecon::cl
