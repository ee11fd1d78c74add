// Row blocks whose state stays on one device across the steps of a stage (the transport stage: per-pixel decode and
// ELL state updated frame by frame). Each step runs every block on its owner, devices in parallel. Each device
// starts with one block; ownership of the others is first-touch: unowned blocks wait in a shared queue and belong to
// the device that takes them, so a faster device takes more. When a device fails, its blocks lose their state: they go
// back to the queue and the device that takes one rebuilds it by replaying the earlier steps (BlockTask::step with
// replay = true), so the result is the same as if the block had never moved.
#pragma once

#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "host/cl/device_context.h"
#include "host/sched/fault.h"
#include "host/sched/report.h"
#include "host/sched/scheduler.h"
#include "host/sched/worker.h"

namespace rfrecon::sched {

// The stage's side. Calls for one block never overlap; calls for different blocks run on several threads.
class BlockTask {
 public:
  virtual ~BlockTask() = default;
  // Once per device before its first block, all devices in parallel (kernel builds), so that build times do not
  // decide the first-touch ownership.
  virtual void prepare(Worker& worker) = 0;
  // Makes fresh state for `block` on the worker's device, replacing any earlier state of that block.
  virtual void create(Worker& worker, std::size_t block) = 0;
  // Applies step `step` to the block's state; replay = true when rebuilding a moved block (an earlier step).
  virtual void step(Worker& worker, std::size_t block, std::size_t step, bool replay) = 0;
};

class BlockRunner {
 public:
  // items_per_row: items of one row in reports (the image width for pixels). Faults count block-steps per device.
  BlockRunner(std::vector<cl::DeviceContext>& devices, std::vector<Tile> blocks, BlockTask& task,
              std::size_t items_per_row = 1, FaultPolicy faults = FaultPolicy::from_environment());

  // Runs step `step` for every block (steps 0, 1, ... in order) and adds it to the report named `stage`.
  // Throws AllDevicesFailed when no device is left; other exceptions from the task are rethrown.
  void run_step(std::size_t step, const std::string& stage);

  // One report per stage name, in first-use order.
  const std::vector<RunReport>& reports() const { return reports_; }
  const std::vector<Tile>& blocks() const { return blocks_; }

 private:
  void work_on(std::size_t position, std::size_t step, RunReport& report);
  bool next_block(std::size_t position, std::size_t& block, bool& moved);
  void fail(std::size_t position, const std::string& error, const Tile& rows, RunReport& report);
  void run_round(const std::function<void(std::size_t)>& body);

  std::vector<cl::DeviceContext>& devices_;
  std::vector<Worker> workers_;
  std::vector<Tile> blocks_;
  BlockTask& task_;
  std::size_t items_per_row_;
  FaultPolicy faults_;
  std::mutex mutex_;
  std::vector<std::size_t> owner_;    // per block; kUnowned when its state lives nowhere
  std::vector<bool> claimed_;         // per block: taken (or done) in the current step
  std::vector<char> created_;         // per block: its state exists on its owner
  std::vector<bool> failed_;          // per device
  std::vector<std::size_t> started_;  // block-steps started per device, for faults
  std::vector<RunReport> reports_;
  std::exception_ptr error_;
  bool prepared_ = false;
};

}  // namespace rfrecon::sched
