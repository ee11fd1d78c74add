// `rfrecon selfcheck`: builds and runs the self-check kernel on each selected device against its C++ reference.
#include <iostream>

#include "host/cl/device_selection.h"
#include "host/cli/commands.h"
#include "host/cli/exit_codes.h"
#include "host/selfcheck/selfcheck.h"

namespace rfrecon::cli {

namespace {
struct SelfcheckOptions {
  std::string selection;
  std::size_t size = 1 << 16;
};

void run_selfcheck(const SelfcheckOptions& options) {
  auto devices = cl::open_devices(options.selection);
  int failures = 0;
  for (const auto& result : selfcheck::run_selfcheck(devices, options.size)) {
    const char* name = result.entry == selfcheck::KernelEntry::kNdRange ? "NDRange" : "single work-item";
    std::cout << "[" << result.device->index << "] " << cl::describe(*result.device) << ", " << name << ": "
              << (result.mismatches == 0 ? "OK" : "FAILED") << " (" << result.elements << " elements, "
              << result.mismatches << " differ from the C++ reference)\n";
    failures += result.mismatches == 0 ? 0 : 1;
  }
  if (failures != 0) throw CommandFailed(kExitSelfcheck, std::to_string(failures) + " self-check run(s) failed");
}
}  // namespace

void add_selfcheck_command(CLI::App& app) {
  auto options = std::make_shared<SelfcheckOptions>();
  auto* command = app.add_subcommand("selfcheck", "Run a small kernel on each device and compare with C++");
  add_devices_option(command, options->selection);
  command->add_option("--size", options->size, "Number of elements")
      ->check(CLI::Range(std::size_t{1}, selfcheck::kMaxSelfcheckElements))
      ->capture_default_str();
  command->callback([options] { run_selfcheck(*options); });
}

}  // namespace rfrecon::cli
