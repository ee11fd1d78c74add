// The per-device upload queue and slot events of the scheduler's workers, and the fenced delivery of results.
#include "host/sched/worker.h"

#include "host/cl/error.h"

namespace rfrecon::sched {

Worker::Worker(cl::DeviceContext& device, std::size_t position, cl::KernelEntry entry, Watchdog* watchdog)
    : device_(device), position_(position), entry_(entry), watchdog_(watchdog) {}

::cl::CommandQueue& Worker::transfer_queue() {
  if (transfer_() == nullptr) {
    cl_int status = CL_SUCCESS;
    transfer_ = ::cl::CommandQueue(device_.context(), device_.device(), 0, &status);
    RF_CL_CHECK_CODE(status, "clCreateCommandQueue(transfer)");
  }
  return transfer_;
}

void Worker::mark_uploaded(int slot) {
  ::cl::Event marker;
  RF_CL_CHECK(transfer_queue().enqueueMarkerWithWaitList(nullptr, &marker));
  RF_CL_CHECK(transfer_queue().flush());
  ready_[slot] = {marker};
}

void Worker::deliver(const std::function<void()>& copy) {
  if (watchdog_ != nullptr) {
    watchdog_->deliver(position_, copy);
  } else {
    copy();
  }
}

}  // namespace rfrecon::sched
