// Row blocks whose state stays on one device across the steps of a stage (the transport stage: per-pixel decode and
// ELL state updated frame by frame). Each step runs every block on its owner, devices in parallel. Each device
// starts with one block; ownership of the others is first-touch: unowned blocks wait in a shared queue and belong to
// the device that takes them, so a faster device takes more. When a device fails, its blocks lose their state: they go
// back to the queue and the device that takes one rebuilds it by replaying the earlier steps (BlockTask::step with
// replay = true), so the result is the same as if the block had never moved. A device that hangs (a call past the tile
// timeout) is dropped the same way.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/entry_choice.h"
#include "host/sched/fault.h"
#include "host/sched/report.h"
#include "host/sched/scheduler.h"
#include "host/sched/watchdog.h"
#include "host/sched/worker.h"

namespace rfrecon::sched {

// The stage's side. Calls for one block never overlap, except that a call abandoned after the tile timeout may still
// run when the block's next owner calls create: a call keeps alive what it uses (create makes fresh state, it does
// not reuse the old), and results leave a call only through Worker::deliver. Calls for different blocks run on
// several threads.
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

struct BlockOptions {
  std::size_t items_per_row = 1;                         // items of one row in reports (the image width for pixels)
  FaultPolicy faults = FaultPolicy::from_environment();  // counts block-steps per device
  // Per call into the task (prepare, create, one step of one block, each replayed step alone); 0: none.
  double tile_timeout_s = tile_timeout_from_environment();
  cl::EntryChoice entries;  // each device's kernel entry (Worker::entry), as in Options::entries
};

class BlockRunner {
 public:
  BlockRunner(std::vector<cl::DeviceContext>& devices, std::vector<Tile> blocks, BlockTask& task,
              BlockOptions options = {});

  // Runs step `step` for every block (steps 0, 1, ... in order) and adds it to the report named `stage`. A device
  // whose call runs past the tile timeout is dropped like a failed one (its thread is not waited for; the task's
  // step must hand its results over through Worker::deliver, as run_tiles' compute does).
  // Throws AllDevicesFailed when no device is left; other exceptions from the task are rethrown.
  void run_step(std::size_t step, const std::string& stage);

  // One report per stage name, in first-use order.
  const std::vector<RunReport>& reports() const;
  const std::vector<Tile>& blocks() const;

 private:
  class State;
  std::shared_ptr<State> state_;  // shared with the device threads: an abandoned one keeps it alive
};

}  // namespace rfrecon::sched
