// Runs a stage's kernels over several OpenCL devices: items cut into tiles taken from one shared queue by one worker
// thread per device, tile sizes adapted to each device's measured throughput, failed devices' tiles run elsewhere.
//
// API (docs/scheduler.md has the design and measurements):
//
//   std::vector<cl::DeviceContext> devices = cl::open_devices(flag);
//   // Stateless row/pixel stage, results written per item (e.g. one work-item per rectified row):
//   sched::Options options;
//   options.stage = "fusion";
//   sched::RunReport report = sched::run_tiles(devices, rows, [&](sched::Worker& w, const sched::Tile& t) {
//     // enqueue the kernel for items [t.begin, t.end) on w.queue(), read the results, copy them into the host
//     // output with w.deliver (each item belongs to exactly one tile, so no locking), return when they are there
//   }, options);
//   sched::log_reports({report});   // table: per device tiles, share, items/s, failures
//   nlohmann::json j = report;      // same in the JSON summary
//
// With double buffering (inputs streamed per tile), pass a TileWork: `prepare` once per device (kernels, inputs
// shared by all tiles), `upload` enqueues non-blocking writes of a tile's inputs on w.transfer_queue() into buffer
// set `slot` (0 or 1), `compute` enqueues the kernel with w.inputs_ready(slot) as wait list and delivers the
// results. The scheduler uploads tile i+1 before computing tile i. Per-device state: index a vector by
// w.position(). split_rows() cuts N rows into fixed blocks when a stage needs a static split.
//
// Kernel entries are per device: Options::entries (cl::EntryChoice: auto by default, FPGA boards on single
// work-item entries and CPUs and GPUs on NDRange; or one entry forced; or one per device) gives each worker its
// w.entry(), which the stage passes to cl::make_kernel and cl::enqueue_kernel; the report names it per device. A
// per-device list whose length differs from the device count throws UsageError before any work.
//
// Guarantees: every item is computed exactly once in the delivered output (a tile is redone whole when its device
// failed before delivering), so results never depend on the split when the kernel computes each item alone.
// A cl::ClError from prepare/upload/compute marks that device failed (logged, recorded in the report) and its
// tiles go back to the queue; any other exception stops every worker and is rethrown. A call (prepare, an upload, a
// tile's compute) running past Options::tile_timeout_s drops its device the same way (DeviceFailure::timed_out):
// run_tiles returns without waiting for that thread, and its results never reach the output provided compute
// hands them over through Worker::deliver, as below. When every device has failed or hung, AllDevicesFailed (a
// cl::ClError: exit code 5) lists each device's error.
//
// Delivering results (what makes an abandoned tile harmless): read them into memory of the compute call itself, then
//   const auto pixels = cl::download<float>(w.queue(), output, t.size());   // blocking; may hang in the driver
//   w.deliver([&] { std::copy(pixels.begin(), pixels.end(), image.begin() + t.begin); });
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/entry_choice.h"
#include "host/cl/error.h"
#include "host/sched/fault.h"
#include "host/sched/report.h"
#include "host/sched/watchdog.h"
#include "host/sched/worker.h"

namespace rfrecon::sched {

// Items [begin, end) of a stage: camera pixels, projector pixels or rows.
struct Tile {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t size() const { return end - begin; }
};

// `rows` cut into `tiles` contiguous blocks whose sizes differ by at most one (fewer blocks when rows < tiles).
std::vector<Tile> split_rows(std::size_t rows, std::size_t tiles);

struct Options {
  std::string stage = "kernels";     // name in reports and logs
  std::size_t granularity = 0;       // tile sizes are multiples of this (the last excepted); 0: the stage picks, else 1
  std::size_t first_tile_items = 0;  // each device's first tile; 0: items / (8 x devices)
  double target_tile_seconds = 0.05;  // later tiles: measured items/s x this
  std::size_t max_tile_items = 0;     // 0: no cap
  FaultPolicy faults = FaultPolicy::from_environment();
  double tile_timeout_s = tile_timeout_from_environment();  // per call into the stage; 0: none
  cl::EntryChoice entries;  // each device's kernel entry (Worker::entry); default: cl::preferred_entry per device
};

using TileFn = std::function<void(Worker&, const Tile&)>;

struct TileWork {
  std::function<void(Worker&)> prepare;                         // optional
  std::function<void(Worker&, const Tile&, int slot)> upload;   // optional: enables double buffering
  std::function<void(Worker&, const Tile&, int slot)> compute;  // required
};

// Every selected device failed; what() names each device and its error.
class AllDevicesFailed : public cl::ClError {
 public:
  AllDevicesFailed(const std::string& stage, const std::vector<DeviceFailure>& failures);
};

RunReport run_tiles(std::vector<cl::DeviceContext>& devices, std::size_t items, const TileWork& work,
                    const Options& options = {});
RunReport run_tiles(std::vector<cl::DeviceContext>& devices, std::size_t items, const TileFn& compute,
                    const Options& options = {});

}  // namespace rfrecon::sched
