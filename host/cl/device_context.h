// One OpenCL device ready for work: its own context and in-order queue (contexts cannot span platforms).
#pragma once

#include <cstddef>
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

// Declares that a kernel holds `bytes` of private arrays per work-item. CPU runtimes (PoCL) run them on their worker
// threads' stacks, which they create at the first platform query: threads created from this call on get a default
// stack that holds the largest declared arrays with 8 MB to spare. The code that launches such a kernel declares it at
// static initialization (host/depth/row_solvers.cc), so that no runtime or stage needs to know another's kernels.
// Returns true, for that use.
bool reserve_private_bytes(std::size_t bytes) noexcept;

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
