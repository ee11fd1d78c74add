// What the scheduler did in one stage: tiles, items and busy time per device, their shares, and device failures.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace rfrecon::sched {

struct DeviceShare {
  std::string device;  // cl::describe() of the device
  std::string entry;   // the kernel entry it ran: "ndrange" or "single" (cl::entry_name)
  std::size_t tiles = 0;
  std::size_t items = 0;           // items (pixels, rows) whose results this device delivered
  std::size_t replayed_items = 0;  // items it recomputed to rebuild state moved from a failed device (transport)
  double busy_seconds = 0.0;       // wall time spent in its tiles
  bool failed = false;
  double share = 0.0;  // items / the stage's items
  double items_per_second() const { return busy_seconds > 0.0 ? static_cast<double>(items) / busy_seconds : 0.0; }
};

struct DeviceFailure {
  std::size_t device = 0;  // position in the scheduler's device list
  std::string device_name;
  std::size_t tile_begin = 0;  // the tile (item range) it was running; its items went back to the queue
  std::size_t tile_end = 0;
  std::string error;       // the exception's message, or the timeout's
  bool timed_out = false;  // dropped after the tile timeout (a hung device), not after an error
};

struct RunReport {
  std::string stage;
  std::size_t items = 0;
  double seconds = 0.0;  // wall time of the stage
  std::vector<DeviceShare> devices;
  std::vector<DeviceFailure> failures;

  // Adds the counts of `other` (same devices, same stage) to this one: a stage run in several steps.
  void merge(const RunReport& other);
  // Sets every device's share from its items.
  void update_shares();
};

// {"stage", "items", "seconds", "devices": [{"device", "entry", "tiles", "items", "share", "items_per_second",
// "busy_seconds", "replayed_items", "failed"}], "failures": [{"device", "device_name", "tile": [begin, end],
// "error", "timed_out"}]}
void to_json(nlohmann::json& json, const DeviceShare& share);
void to_json(nlohmann::json& json, const DeviceFailure& failure);
void to_json(nlohmann::json& json, const RunReport& report);

// A fixed-width table, one line per stage and device: stage, seconds, device, entry, tiles, share, items/s; then one
// line per failure. Lines without a trailing newline, for spdlog or printf.
std::vector<std::string> format_table(const std::vector<RunReport>& reports);

// Logs format_table(reports) at info level, failures as warnings.
void log_reports(const std::vector<RunReport>& reports);

}  // namespace rfrecon::sched
