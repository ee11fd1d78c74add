// `rfrecon devices`: lists the OpenCL devices and how rfrecon would load programs on each; clears the program cache.
#include <cstdint>
#include <iostream>

#include <nlohmann/json.hpp>

#include "host/cl/device_selection.h"
#include "host/cl/entry_choice.h"
#include "host/cl/program_cache.h"
#include "host/cli/commands.h"

namespace rfrecon::cli {

namespace {
constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;

struct DevicesOptions {
  bool json = false;
  bool clear_cache = false;
  std::string selection;
};

std::string program_origin(const cl::ProgramCache& programs, const cl::DeviceInfo& info) {
  if (!programs.uses_binary(info)) return "source";
  if (programs.binary_location().empty()) return std::string("binary (set ") + cl::kBinaryEnv + ")";
  return "binary from " + programs.binary_location().string();
}

void run_devices(const DevicesOptions& options) {
  if (options.clear_cache) {
    const cl::ProgramStore store;
    const std::size_t removed = store.clear();
    std::cout << "program cache: " << (store.enabled() ? store.directory().string() : std::string("off")) << ", "
              << removed << " stored program" << (removed == 1 ? "" : "s") << " removed\n";
    return;
  }
  const auto available = cl::enumerate_devices();
  // Without --devices every device is listed; with it, only the selection (and a bad selection is an error).
  const auto shown = cl::select_devices(available, options.selection.empty() ? "all" : options.selection);
  const cl::ProgramCache programs;
  if (options.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& entry : shown) {
      nlohmann::json item = entry.info;
      item["programs"] = program_origin(programs, entry.info);
      item["entry"] = cl::entry_name(cl::preferred_entry(entry.info));
      list.push_back(item);
    }
    std::cout << nlohmann::json{{"devices", list}}.dump(2) << "\n";
    return;
  }
  for (const auto& entry : shown) {
    const auto& info = entry.info;
    std::cout << "[" << info.index << "] " << info.device_name << "\n"
              << "    platform:       " << info.platform_name << " (" << info.platform_vendor << ")\n"
              << "    type:           " << cl::to_string(info.kind) << "\n"
              << "    compute units:  " << info.compute_units << "\n"
              << "    global memory:  " << info.global_mem_bytes / kMiB << " MiB (max allocation "
              << info.max_alloc_bytes / kMiB << " MiB)\n"
              << "    local memory:   " << info.local_mem_bytes / 1024 << " KiB\n"
              << "    OpenCL C:       " << info.opencl_c_version << "\n"
              << "    fp64 / fp16:    " << (info.fp64 ? "yes" : "no") << " / " << (info.fp16 ? "yes" : "no") << "\n"
              << "    programs:       " << program_origin(programs, info) << "\n"
              << "    entry (auto):   " << cl::entry_name(cl::preferred_entry(info)) << "\n";
  }
}
}  // namespace

void add_devices_command(CLI::App& app) {
  auto options = std::make_shared<DevicesOptions>();
  auto* command = app.add_subcommand("devices", "List OpenCL platforms and devices");
  command->add_flag("--json", options->json, "Print JSON instead of text");
  command->add_flag("--clear-cache", options->clear_cache,
                    "Remove the stored program binaries ($RFRECON_PROGRAM_CACHE, else ~/.cache/rfrecon/programs)");
  add_devices_option(command, options->selection);
  command->callback([options] { run_devices(*options); });
}

}  // namespace rfrecon::cli
