// Which kernel entry each device of a run uses: the rule (single work-item on FPGA boards, NDRange on CPUs and GPUs),
// one entry forced on every device, or one entry per device, as `--entry auto|ndrange|single|LIST` says.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/device_info.h"
#include "host/cl/kernel_entry.h"

namespace rfrecon::cl {

// The entry that suits a device: single work-item on FPGA boards (the Intel FPGA SDK and Xilinx XRT platforms, for
// which the program cache's preamble defines RF_TARGET_INTEL_FPGA / RF_TARGET_XILINX_FPGA, and any device of type
// CL_DEVICE_TYPE_ACCELERATOR), NDRange on CPUs, GPUs and every other device.
KernelEntry preferred_entry(const DeviceInfo& info);

// "ndrange" or "single", the words of `--entry` and of the scheduler's reports.
const char* entry_name(KernelEntry entry);

class EntryChoice {
 public:
  // Auto: each device runs preferred_entry() of its DeviceInfo.
  EntryChoice() = default;
  // Every device runs `entry` (implicit, so a KernelEntry passes wherever a choice is expected).
  EntryChoice(KernelEntry entry);  // NOLINT(google-explicit-constructor)
  // Device i of the selected list (cl::open_devices order, as `rfrecon devices` shows it) runs per_device[i].
  explicit EntryChoice(std::vector<KernelEntry> per_device);

  // "auto", "ndrange", "single", or a comma-separated list of "ndrange" / "single" with one word per device.
  // Throws UsageError quoting the word that is none of these.
  static EntryChoice parse(const std::string& text);

  // Throws UsageError naming both counts when a per-device list does not have exactly `devices` entries.
  void check_device_count(std::size_t devices) const;
  // The entry of the device at `position` of the selected list; `info` is that device's.
  KernelEntry entry_for(std::size_t position, const DeviceInfo& info) const;
  // entry_for() of every device, after check_device_count(devices.size()).
  std::vector<KernelEntry> resolve(const std::vector<DeviceContext>& devices) const;

  // "auto", the forced entry's word, or the list's words separated by commas (for messages and logs).
  std::string text() const;

 private:
  enum class Mode { kAuto, kForced, kPerDevice };
  Mode mode_ = Mode::kAuto;
  std::vector<KernelEntry> entries_;  // kForced: the one entry; kPerDevice: one per device
};

}  // namespace rfrecon::cl
