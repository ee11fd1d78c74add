// Scheduler reports: merging steps, JSON and the end-of-command table.
#include "host/sched/report.h"

#include <cstdio>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

namespace rfrecon::sched {

void RunReport::merge(const RunReport& other) {
  if (devices.size() < other.devices.size()) devices.resize(other.devices.size());
  items += other.items;
  seconds += other.seconds;
  for (std::size_t i = 0; i < other.devices.size(); ++i) {
    auto& mine = devices[i];
    const auto& theirs = other.devices[i];
    mine.device = theirs.device;
    mine.entry = theirs.entry;
    mine.tiles += theirs.tiles;
    mine.items += theirs.items;
    mine.replayed_items += theirs.replayed_items;
    mine.busy_seconds += theirs.busy_seconds;
    mine.failed = mine.failed || theirs.failed;
  }
  failures.insert(failures.end(), other.failures.begin(), other.failures.end());
  update_shares();
}

void RunReport::update_shares() {
  for (auto& device : devices) {
    device.share = items > 0 ? static_cast<double>(device.items) / static_cast<double>(items) : 0.0;
  }
}

void to_json(nlohmann::json& json, const DeviceShare& share) {
  json = {{"device", share.device},
          {"entry", share.entry},
          {"tiles", share.tiles},
          {"items", share.items},
          {"share", share.share},
          {"items_per_second", share.items_per_second()},
          {"busy_seconds", share.busy_seconds},
          {"replayed_items", share.replayed_items},
          {"failed", share.failed}};
}

void to_json(nlohmann::json& json, const DeviceFailure& failure) {
  json = {{"device", failure.device},
          {"device_name", failure.device_name},
          {"tile", {failure.tile_begin, failure.tile_end}},
          {"error", failure.error},
          {"timed_out", failure.timed_out}};
}

void to_json(nlohmann::json& json, const RunReport& report) {
  json = {{"stage", report.stage},
          {"items", report.items},
          {"seconds", report.seconds},
          {"devices", report.devices},
          {"failures", report.failures}};
}

std::vector<std::string> format_table(const std::vector<RunReport>& reports) {
  std::vector<std::string> lines;
  char line[512];
  std::snprintf(line, sizeof line, "%-10s %9s  %-40s %-7s %6s %7s %12s", "stage", "seconds", "device", "entry", "tiles",
                "share", "items/s");
  lines.emplace_back(line);
  for (const auto& report : reports) {
    for (std::size_t i = 0; i < report.devices.size(); ++i) {
      const auto& device = report.devices[i];
      char seconds[32] = "";
      if (i == 0) std::snprintf(seconds, sizeof seconds, "%.3f", report.seconds);
      std::snprintf(line, sizeof line, "%-10s %9s  %-40.40s %-7s %6zu %6.1f%% %12.4g%s",
                    i == 0 ? report.stage.c_str() : "", seconds, device.device.c_str(), device.entry.c_str(),
                    device.tiles, 100.0 * device.share, device.items_per_second(), device.failed ? "  FAILED" : "");
      lines.emplace_back(line);
    }
  }
  for (const auto& report : reports) {
    for (const auto& failure : report.failures) {
      lines.push_back("failure in " + report.stage + ": device " + std::to_string(failure.device) + " (" +
                      failure.device_name + ") at items [" + std::to_string(failure.tile_begin) + ", " +
                      std::to_string(failure.tile_end) + "): " + failure.error);
    }
  }
  return lines;
}

void log_reports(const std::vector<RunReport>& reports) {
  for (const auto& line : format_table(reports)) {
    if (line.rfind("failure", 0) == 0) {
      spdlog::warn("{}", line);
    } else {
      spdlog::info("{}", line);
    }
  }
}

}  // namespace rfrecon::sched
