// One device as the scheduler drives it: the device's compute queue, a second queue for uploads, and the events
// that say when each of its two input buffer sets has arrived (double buffering).
#pragma once

#include <cstddef>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/opencl.h"

namespace rfrecon::sched {

class Worker {
 public:
  Worker(cl::DeviceContext& device, std::size_t position);

  cl::DeviceContext& device() { return device_; }
  // Index of the device in the list given to the scheduler (stable across a run; reports and faults use it).
  std::size_t position() const { return position_; }
  // The device's in-order queue: kernels and result reads.
  ::cl::CommandQueue& queue() { return device_.queue(); }
  // A second in-order queue on the same context for input writes, so they overlap the kernel of the other slot.
  ::cl::CommandQueue& transfer_queue();

  // Wait list for a kernel reading buffer set `slot` (0 or 1): the uploads the scheduler marked for that slot.
  const std::vector<::cl::Event>& inputs_ready(int slot) const { return ready_[slot]; }
  // Called by the scheduler after a tile's upload: a marker on the transfer queue completes with every write.
  void mark_uploaded(int slot);
  void clear_uploads(int slot) { ready_[slot].clear(); }

 private:
  cl::DeviceContext& device_;
  std::size_t position_;
  ::cl::CommandQueue transfer_;
  std::vector<::cl::Event> ready_[2];
};

}  // namespace rfrecon::sched
