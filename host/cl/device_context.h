// One OpenCL device ready for work: its own context and in-order queue (contexts cannot span platforms).
#pragma once

#include <vector>

#include "host/cl/device_info.h"
#include "host/cl/opencl.h"

namespace rfrecon::cl {

// A device as found on the machine, before any context is made.
struct DeviceEntry {
  ::cl::Platform platform;
  ::cl::Device device;
  DeviceInfo info;
};

// Every device of every platform, in platform order then device order; empty when no ICD is installed.
std::vector<DeviceEntry> enumerate_devices();

class DeviceContext {
 public:
  explicit DeviceContext(const DeviceEntry& entry);

  const DeviceInfo& info() const { return info_; }
  const ::cl::Device& device() const { return device_; }
  const ::cl::Context& context() const { return context_; }
  // In-order queue, with profiling enabled when the device supports it.
  ::cl::CommandQueue& queue() { return queue_; }

 private:
  DeviceInfo info_;
  ::cl::Device device_;
  ::cl::Context context_;
  ::cl::CommandQueue queue_;
};

}  // namespace rfrecon::cl
