// `rfrecon selfcheck`: builds and runs the self-check kernel on each selected device against its C++ reference.
#include <cmath>
#include <iostream>
#include <numeric>

#include <spdlog/spdlog.h>

#include "host/cl/device_selection.h"
#include "host/cli/commands.h"
#include "host/cli/exit_codes.h"
#include "host/selfcheck/axpy.h"

namespace rfrecon::cli {

namespace {
struct SelfcheckOptions {
  std::string selection;
  std::size_t size = 1 << 16;
};

void run_selfcheck(const SelfcheckOptions& options) {
  std::vector<float> x(options.size);
  std::vector<float> y(options.size);
  for (std::size_t i = 0; i < options.size; ++i) {
    x[i] = static_cast<float>(i % 1000) * 0.25f;
    y[i] = 1.0f - static_cast<float>(i % 7);
  }
  const float a = 1.5f;
  const auto expected = selfcheck::axpy_reference(a, x, y);
  cl::ProgramCache programs;
  int failures = 0;
  for (auto& device : cl::open_devices(options.selection)) {
    for (const auto entry : {selfcheck::KernelEntry::kNdRange, selfcheck::KernelEntry::kSingleWorkItem}) {
      const auto got = selfcheck::axpy_opencl(device, programs, entry, a, x, y);
      std::size_t mismatches = 0;
      for (std::size_t i = 0; i < got.size(); ++i) mismatches += got[i] != expected[i] ? 1 : 0;
      const char* name = entry == selfcheck::KernelEntry::kNdRange ? "NDRange" : "single work-item";
      std::cout << "[" << device.info().index << "] " << cl::describe(device.info()) << ", " << name << ": "
                << (mismatches == 0 ? "OK" : "FAILED") << " (" << got.size() << " elements, " << mismatches
                << " differ from the C++ reference)\n";
      failures += mismatches == 0 ? 0 : 1;
    }
  }
  if (failures != 0) throw CommandFailed(kExitSelfcheck, std::to_string(failures) + " self-check run(s) failed");
}
}  // namespace

void add_selfcheck_command(CLI::App& app) {
  auto options = std::make_shared<SelfcheckOptions>();
  auto* command = app.add_subcommand("selfcheck", "Run a small kernel on each device and compare with C++");
  add_devices_option(command, options->selection);
  command->add_option("--size", options->size, "Number of elements")->check(CLI::PositiveNumber);
  command->callback([options] { run_selfcheck(*options); });
}

}  // namespace rfrecon::cli
