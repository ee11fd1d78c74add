// One device as the scheduler drives it: the device's compute queue, a second queue for uploads, the events that say
// when each of its two input buffer sets has arrived (double buffering), the kernel entry it runs, and the fenced
// delivery of results.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/kernel_entry.h"
#include "host/cl/opencl.h"
#include "host/sched/watchdog.h"

namespace rfrecon::sched {

class Worker {
 public:
  // entry: the kernel entry of this device (Options::entries resolved for it). watchdog: the one timing this worker's
  // calls (Worker::deliver asks it); none: deliver always copies.
  Worker(cl::DeviceContext& device, std::size_t position, cl::KernelEntry entry, Watchdog* watchdog = nullptr);

  cl::DeviceContext& device() { return device_; }
  // Index of the device in the list given to the scheduler (stable across a run; reports and faults use it).
  std::size_t position() const { return position_; }
  // The entry the stage's kernels use on this device (cl::make_kernel, cl::enqueue_kernel).
  cl::KernelEntry entry() const { return entry_; }
  // The device's in-order queue: kernels and result reads.
  ::cl::CommandQueue& queue() { return device_.queue(); }
  // A second in-order queue on the same context for input writes, so they overlap the kernel of the other slot.
  ::cl::CommandQueue& transfer_queue();

  // Wait list for a kernel reading buffer set `slot` (0 or 1): the uploads the scheduler marked for that slot.
  const std::vector<::cl::Event>& inputs_ready(int slot) const { return ready_[slot]; }
  // Called by the scheduler after a tile's upload: a marker on the transfer queue completes with every write.
  void mark_uploaded(int slot);
  void clear_uploads(int slot) { ready_[slot].clear(); }

  // The only way a tile's results reach the stage's output: read them (blocking) into memory of the calling thread,
  // then deliver([&] { copy them into the output }). Throws TileAbandoned instead when the scheduler gave the tile
  // to another device after the tile timeout, so a late thread never writes the output (docs/scheduler.md).
  void deliver(const std::function<void()>& copy);

 private:
  cl::DeviceContext& device_;
  std::size_t position_;
  cl::KernelEntry entry_;
  Watchdog* watchdog_;
  ::cl::CommandQueue transfer_;
  std::vector<::cl::Event> ready_[2];
};

}  // namespace rfrecon::sched
